#include "solver/round_depths.h"

#include <algorithm>

#include "contacts/contact_manager.h"
#include "world/body_store.h"

namespace cyclone::detail {

void RoundDepths::add(std::size_t slot, const BodyRecord &a, const BodyRecord &b, const ContactManager &contacts,
                      const ManifoldRef &source, const Vector3 &normal) {
    if (!mayBeRound(*a.shape) && !mayBeRound(*b.shape)) return;
    const ManifoldState &m = contacts.pairs[source.pair].manifolds[source.index];
    Entry &e = entries_[slot];
    e.startA = a.body.getTransform().linear().transpose() * normal;
    e.startB = -(b.body.getTransform().linear().transpose() * normal);
    e.coreA = roundSideAt(*a.shape, m.childA, e.startA);
    e.coreB = roundSideAt(*b.shape, m.childB, e.startB);
    round_[slot] = e.coreA.radius > 0 || e.coreB.radius > 0;
}

void RoundDepths::finish() { any_ = std::find(round_.begin(), round_.end(), 1) != round_.end(); }

real RoundDepths::change(std::size_t s, const DepthFrame &frame) const {
    if (!round_[s]) return 0;
    const Entry &e = entries_[s];
    real change = 0;
    if (e.coreA.radius > 0) change += roundDepthChange(e.coreA, e.startA, frame.normalA);
    if (e.coreB.radius > 0) change += roundDepthChange(e.coreB, e.startB, -frame.normalB);
    return change;
}

}  // namespace cyclone::detail
