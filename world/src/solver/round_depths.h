// Depths of contacts on round bodies within a step. After the first sub-step the solver
// reads a manifold's depths from its anchors at the bodies' current poses (DepthFrame),
// each anchor a point fixed on its body. On a rolling ball, capsule or cylinder that
// point turns away from the contact with the body, r (1 - cos a) after a turn by a
// (0.65 mm per sub-step for a 0.25 m ball at 4.3 m/s and 60 Hz x 4), while the surface's
// deepest point stays below the core: read from the anchors alone, the depths are too
// shallow and the body sinks through the later sub-steps. The round side's share of the depth is corrected by
// roundDepthChange (collision/round_side.h), the same for every point of the manifold,
// so it goes into the frame's offset (docs/solver.md, "Round bodies").
//
// Design note. The slots are looked at once per step, each on its own (on the threads);
// a step without a round side reads nothing more per sub-step, and a world without round
// bodies (BodyStore::roundCount, a box pile) does not look.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "collision/round_side.h"
#include "contacts/pair_cache.h"
#include "solver/penetration_pass.h"
#include "world/room.h"

namespace cyclone::detail {

struct BodyRecord;
class ContactManager;

class RoundDepths {
public:
    /// Forgets the last step's slots.
    void clear() {
        round_.clear();
        any_ = false;
    }
    /// Makes room for `slots` solver slots, none of them round yet.
    void reset(std::size_t slots) {
        resizeAnew(entries_, slots);
        resizeAnew(round_, slots);
        std::fill(round_.begin(), round_.end(), 0);
        any_ = false;
    }
    /// Notes slot `slot` if its manifold has a round side: `a` and `b` its bodies at the
    /// step's start, `source` the pair manifold it was made from (which children it
    /// touches), `normal` the solver's normal (from A to B). Different slots may be noted
    /// on different threads at once.
    void add(std::size_t slot, const BodyRecord &a, const BodyRecord &b, const ContactManager &contacts,
             const ManifoldRef &source, const Vector3 &normal);
    /// After the slots are noted: settles whether any has a round side.
    void finish();
    /// Whether no slot has a round side (then nothing else needs calling).
    bool empty() const { return !any_; }
    /// How much deeper slot `s`'s points are than its anchors say at the poses of `frame`
    /// (the slot's DepthFrame), m; 0 for a slot without a round side.
    real change(std::size_t s, const DepthFrame &frame) const;

private:
    struct Entry {
        RoundCore coreA, coreB;  ///< radius 0: that side is not round here.
        Vector3 startA = Vector3::Zero();  ///< A's outward normal (n) in A's frame at the step's start.
        Vector3 startB = Vector3::Zero();  ///< B's outward normal (-n) in B's frame at the step's start.
    };
    std::vector<Entry> entries_;  ///< Per slot; read only where round_ is set.
    std::vector<char> round_;     ///< Per slot: whether it has a round side (empty: none has).
    bool any_ = false;
};

}  // namespace cyclone::detail
