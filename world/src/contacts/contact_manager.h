// The contacts' lifecycle: candidate pairs from the broadphase, the narrowphase (or a
// manifold kept from the last step when its bodies hardly moved), persistent pairs with
// their warm-start impulses, and the contact begin and end events.
#pragma once

#include <cstdint>
#include <vector>

#include "collision/broadphase.h"
#include "collision/narrowphase.h"
#include "contacts/pair_cache.h"
#include "cyclone/world/world.h"
#include "world/body_store.h"

namespace cyclone::detail {

struct WorldState;

/// A pair slot's touching state at the end of the last step, for contact events.
struct ContactTrack {
    BodyId a;
    BodyId b;
    bool touching = false;
};

class ContactManager {
public:
    PairCache pairs;
    /// Pairs touching after this step's narrowphase, in the broadphase's order.
    std::vector<std::uint32_t> touchingPairs;

    /// The broadphase stage: refits the awake bodies' boxes and lists the candidate pairs
    /// (planes tested apart).
    void findCandidates(WorldState &world);
    /// The narrowphase stage: each candidate's manifolds, kept or made anew; wakes
    /// sleeping bodies a new contact touches; drops the pairs that separated.
    void updateContacts(WorldState &world);
    /// Records the contacts that began or ended since the last call in the step's events.
    void reportContactEvents(WorldState &world);

    ManifoldState &manifold(ManifoldRef ref) { return pairs[ref.pair].manifolds[ref.index]; }
    /// The pair of bodies i and j, created (and listed with both bodies) if new.
    std::uint32_t findOrAddPair(BodyStore &bodies, std::uint32_t i, std::uint32_t j, bool &created);
    /// Removes a pair from the cache and from its bodies' lists.
    void removePair(BodyStore &bodies, std::uint32_t pair);
    /// Removes every pair of body `index`.
    void removePairsOf(BodyStore &bodies, std::uint32_t index);
    /// A number for a new set of anchors (ManifoldState::anchorsId), never given before.
    std::uint64_t newAnchorsId() { return ++anchorsIssued_; }

private:
    /// Refreshes pair p's manifolds from their anchors when its bodies hardly moved
    /// relative to each other since it was last tested; false: it must be tested.
    bool reuseManifolds(const WorldState &world, std::uint32_t p);
    /// Runs the narrowphase on pair p and merges what it finds into the pair's manifolds.
    void testPair(WorldState &world, std::uint32_t p);

    static constexpr std::uint32_t kNoSlot = ~std::uint32_t(0);
    std::uint64_t anchorsIssued_ = 0;
    std::vector<fcl::CollisionObjectd *> movedObjects_;  ///< Objects whose fat box moved.
    std::vector<CandidatePair> candidates_;
    std::vector<CandidatePair> planeCandidates_;  ///< This step's body-plane pairs, found before the trees'.
    /// Pair slot of each candidate when it was last looked up (kNoSlot: none), by position.
    std::vector<std::uint32_t> candidateSlots_;
    std::vector<Manifold> fresh_;
    std::vector<std::uint32_t> stepPairs_;  ///< Pair slots the broadphase reported this step.
    std::vector<char> pairReused_;          ///< Per entry of stepPairs_.
    std::vector<ContactTrack> tracks_;      ///< By pair slot.
    /// Pair slots whose touching state may have changed since the last contact events:
    /// seen by the narrowphase or removed (reportContactEvents looks at these only).
    std::vector<std::uint32_t> eventSlots_;
};

}  // namespace cyclone::detail
