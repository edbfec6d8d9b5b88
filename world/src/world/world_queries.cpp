// The World's queries and debug drawing: each passes what it reads to queries/queries.cpp
// or queries/debug_draw.cpp.
#include "queries/debug_draw.h"
#include "queries/queries.h"
#include "world/world_impl.h"

namespace cyclone {

std::optional<RayHit> World::rayCast(const Vector3 &origin, const Vector3 &direction, real maxDistance,
                                     const QueryFilter &filter) const {
    return detail::rayCast(impl_->queryScene(), origin, direction, maxDistance, filter);
}

std::size_t World::rayCastAll(const Vector3 &origin, const Vector3 &direction, std::vector<RayHit> &out,
                              real maxDistance, const QueryFilter &filter) const {
    return detail::rayCastAll(impl_->queryScene(), origin, direction, out, maxDistance, filter);
}

std::size_t World::overlap(const Shape &shape, const Vector3 &position, const Quaternion &orientation,
                           std::vector<BodyId> &out, const QueryFilter &filter) const {
    return detail::overlap(impl_->queryScene(), shape, position, orientation, out, filter);
}

std::optional<ShapeCastHit> World::shapeCast(const Shape &shape, const Vector3 &position,
                                             const Quaternion &orientation, const Vector3 &translation,
                                             const QueryFilter &filter) const {
    return detail::shapeCast(impl_->queryScene(), shape, position, orientation, translation, filter);
}

std::optional<ShapeCastHit> World::shapeCast(const Shape &shape, const Vector3 &position,
                                             const Quaternion &orientation, const Vector3 &translation,
                                             const Quaternion &endOrientation, const QueryFilter &filter) const {
    // The turn's arguments are checked before the state is reached.
    const detail::CastMotion motion = detail::checkedTurn(position, orientation, translation, endOrientation);
    // Without a turn, the straight cast (its refusals and its answer).
    if (motion.angle == 0) return shapeCast(shape, position, orientation, translation, filter);
    return detail::turningCast(impl_->queryScene(), shape, position, orientation, motion, filter);
}

void World::debugDraw(DebugDraw &draw, const DebugDrawOptions &options) const {
    detail::validateDrawOptions(options);  // before the state is reached
    const Impl &w = *impl_;
    detail::debugDraw({w.bodies, w.joints, w.contacts.pairs, w.changingCalls}, draw, options);
}

}  // namespace cyclone
