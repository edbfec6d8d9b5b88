#include "solver/round_depths.h"

#include "contacts/contact_manager.h"
#include "world/body_store.h"

namespace cyclone::detail {

void RoundDepths::add(std::size_t slot, std::size_t slots, const BodyRecord &a, const BodyRecord &b,
                      const ContactManager &contacts, const ManifoldRef &source, const Vector3 &normal) {
    if (!mayBeRound(*a.shape) && !mayBeRound(*b.shape)) return;
    const ManifoldState &m = contacts.pairs[source.pair].manifolds[source.index];
    Entry e;
    e.startA = a.body.getTransform().linear().transpose() * normal;
    e.startB = -(b.body.getTransform().linear().transpose() * normal);
    e.coreA = roundSideAt(*a.shape, m.childA, e.startA);
    e.coreB = roundSideAt(*b.shape, m.childB, e.startB);
    if (e.coreA.radius == 0 && e.coreB.radius == 0) return;
    if (entryOfSlot_.empty()) entryOfSlot_.assign(slots, -1);
    entryOfSlot_[slot] = static_cast<int>(entries_.size());
    entries_.push_back(e);
}

real RoundDepths::change(std::size_t s, const DepthFrame &frame) const {
    if (entryOfSlot_.empty() || entryOfSlot_[s] < 0) return 0;
    const Entry &e = entries_[static_cast<std::size_t>(entryOfSlot_[s])];
    real change = 0;
    if (e.coreA.radius > 0) change += roundDepthChange(e.coreA, e.startA, frame.normalA);
    if (e.coreB.radius > 0) change += roundDepthChange(e.coreB, e.startB, -frame.normalB);
    return change;
}

}  // namespace cyclone::detail
