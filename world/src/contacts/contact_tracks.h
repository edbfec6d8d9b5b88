// Each pair slot's contact as the contact events last reported it.
//
// Design note. The events compare a slot's touching state with the one it had at the
// end of the last step. A record per slot would hold it for every pair the broadphase
// ever reported, though a landing pile's slots are mostly pairs that never touch (11,400
// slots, about 2,300 touching, in mixed1000): here a slot holds only an index, and the
// records are kept for the contacts that are on.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/world/settings.h"
#include "world/room.h"

namespace cyclone::detail {

/// A pair slot's contact at the end of the last step, for contact events.
struct ContactTrack {
    BodyId a;
    BodyId b;
    bool touching = false;
    std::uint64_t userDataA = 0, userDataB = 0;  ///< The bodies' user data when it began (for the end event).
};

class ContactTracks {
public:
    /// Pair slots [0, slots()) are covered: grows the cover to `slots`.
    void cover(std::size_t slots) {
        if (of_.size() < slots) of_.resize(slots, kNone);
    }
    std::size_t slots() const { return of_.size(); }

    /// Slot `slot`'s contact (not touching when it has none).
    const ContactTrack &at(std::uint32_t slot) const {
        return slot < of_.size() && of_[slot] != kNone ? tracks_[of_[slot]] : none_;
    }

    /// Gives slot `slot` the contact that began there.
    void begin(std::uint32_t slot, const ContactTrack &track) {
        cover(std::size_t(slot) + 1);
        if (of_[slot] == kNone) {
            if (free_.empty()) {
                of_[slot] = static_cast<std::uint32_t>(tracks_.size());
                makeRoom(tracks_);
                tracks_.push_back(track);
                free_.reserve(tracks_.capacity());  // an end never allocates
                return;
            }
            of_[slot] = free_.back();
            free_.pop_back();
        }
        tracks_[of_[slot]] = track;
    }

    /// Slot `slot`'s contact ended.
    void end(std::uint32_t slot) {
        if (slot >= of_.size() || of_[slot] == kNone) return;
        free_.push_back(of_[slot]);
        of_[slot] = kNone;
    }

    /// No contact on any slot; `slots` covered (a snapshot being read).
    void reset(std::size_t slots) {
        of_.assign(slots, kNone);
        tracks_.clear();
        free_.clear();
    }

private:
    static constexpr std::uint32_t kNone = ~std::uint32_t(0);
    std::vector<std::uint32_t> of_;       ///< By pair slot: its entry in tracks_, or kNone.
    std::vector<ContactTrack> tracks_;    ///< The contacts on, and free entries.
    std::vector<std::uint32_t> free_;     ///< Entries of tracks_ no slot holds.
    ContactTrack none_;
};

}  // namespace cyclone::detail
