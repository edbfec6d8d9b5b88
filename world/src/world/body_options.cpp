// The World's per-body options beyond shape, mass and material: gravity scale, locked axes,
// user data.
#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {

void World::setGravityScale(BodyId id, real scale) {
    static const char *function = "World::setGravityScale";
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.dynamicRecord(id, function);
    detail::requireGravityScale(function, "scale", scale, w.settings.gravity);
    r.gravityScale = scale;
    r.body.setAcceleration(w.settings.gravity * scale);
    w.wake(id.index);
}

real World::gravityScale(BodyId id) const { return impl_->bodies.record(id, "World::gravityScale").gravityScale; }

void World::setLockedAxes(BodyId id, const LockedAxes &axes) {
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.dynamicRecord(id, "World::setLockedAxes");
    w.bodies.lockedCount += axes.any() - r.locked.any();
    r.locked = axes;
    r.body.setVelocity(detail::freeLinear(axes, r.body.getVelocity()));
    r.body.setRotation(detail::freeAngular(axes, r.body.getRotation()));
    w.wake(id.index);
}

const LockedAxes &World::lockedAxes(BodyId id) const { return impl_->bodies.record(id, "World::lockedAxes").locked; }

void World::setUserData(BodyId id, std::uint64_t userData) {
    impl_->bodies.record(id, "World::setUserData").userData = userData;
}

std::uint64_t World::userData(BodyId id) const { return impl_->bodies.record(id, "World::userData").userData; }

}  // namespace cyclone
