// Depths of contacts on round bodies within a step. After the first sub-step the solver
// reads a manifold's depths from its anchors at the bodies' current poses (DepthFrame),
// each anchor a point fixed on its body. On a rolling ball, capsule or cylinder that
// point turns away from the contact with the body, r (1 - cos a) after a turn by a
// (0.65 mm per sub-step for a 0.25 m ball at 4.3 m/s and 60 Hz x 4), while the surface's
// deepest point stays below the core: the depths read too shallow and the body sank
// through the later sub-steps. The round side's share of the depth is corrected by
// roundDepthChange (collision/round_side.h), the same for every point of the manifold,
// so it goes into the frame's offset (docs/solver.md, "Round bodies").
//
// Design note. Only manifolds with a round side are listed, once per step; a step
// without any keeps the list empty and reads nothing more per sub-step, and a world
// without round bodies (BodyStore::roundCount, a box pile) does not look.
#pragma once

#include <cstdint>
#include <vector>

#include "collision/round_side.h"
#include "contacts/pair_cache.h"
#include "solver/penetration_pass.h"

namespace cyclone::detail {

struct BodyRecord;
class ContactManager;

class RoundDepths {
public:
    /// Forgets the last step's slots.
    void clear() {
        entries_.clear();
        entryOfSlot_.clear();
    }
    /// Lists slot `slot` (of `slots`) if its manifold has a round side: `a` and `b` its
    /// bodies at the step's start, `source` the pair manifold it was made from (which
    /// children it touches), `normal` the solver's normal (from A to B).
    void add(std::size_t slot, std::size_t slots, const BodyRecord &a, const BodyRecord &b,
             const ContactManager &contacts, const ManifoldRef &source, const Vector3 &normal);
    /// Whether no slot has a round side (then nothing else needs calling).
    bool empty() const { return entries_.empty(); }
    /// How much deeper slot `s`'s points are than its anchors say at the poses of `frame`
    /// (the slot's DepthFrame), m; 0 for a slot without a round side.
    real change(std::size_t s, const DepthFrame &frame) const;

private:
    struct Entry {
        RoundCore coreA, coreB;  ///< radius 0: that side is not round here.
        Vector3 startA = Vector3::Zero();  ///< A's outward normal (n) in A's frame at the step's start.
        Vector3 startB = Vector3::Zero();  ///< B's outward normal (-n) in B's frame at the step's start.
    };
    std::vector<Entry> entries_;
    std::vector<int> entryOfSlot_;  ///< -1: no round side (sized only when entries_ is not empty).
};

}  // namespace cyclone::detail
