// Queries (queries.cpp): a ray's closest hit and every hit, a shape's overlaps and casts,
// through the broadphase trees. The World's query members (world/world_queries.cpp) and
// the characters' casts call these.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "collision/broadphase.h"
#include "collision/shape_cast.h"
#include "cyclone/world/world.h"
#include "world/body_store.h"

namespace cyclone::detail {

/// What a query reads: the bodies, the broadphase trees, and the count of the World's
/// changing calls (WorldState::changingCalls), against which a QueryFilter::accept that
/// changed the World is refused.
struct QueryScene {
    const BodyStore &bodies;
    const Broadphase &broadphase;
    const std::uint64_t &changingCalls;
};

/// Whether a query considers the body; refused when the filter's accept changed the World.
bool accepts(const QueryScene &scene, std::uint32_t index, const QueryFilter &filter);

/// World::rayCast.
std::optional<RayHit> rayCast(const QueryScene &scene, const Vector3 &origin, const Vector3 &direction,
                              real maxDistance, const QueryFilter &filter);
/// World::rayCastAll.
std::size_t rayCastAll(const QueryScene &scene, const Vector3 &origin, const Vector3 &direction,
                       std::vector<RayHit> &out, real maxDistance, const QueryFilter &filter);
/// World::overlap.
std::size_t overlap(const QueryScene &scene, const Shape &shape, const Vector3 &position,
                    const Quaternion &orientation, std::vector<BodyId> &out, const QueryFilter &filter);
/// World::shapeCast without a turn.
std::optional<ShapeCastHit> shapeCast(const QueryScene &scene, const Shape &shape, const Vector3 &position,
                                      const Quaternion &orientation, const Vector3 &translation,
                                      const QueryFilter &filter);

/// The motion of World::shapeCast with an end orientation: refused (naming
/// World::shapeCast) when a place, a quaternion or the translation is out of range; no
/// turn (angle 0) when the orientations are equal.
CastMotion checkedTurn(const Vector3 &position, const Quaternion &orientation, const Vector3 &translation,
                       const Quaternion &endOrientation);
/// World::shapeCast along `motion`, a turn that checkedTurn gave.
std::optional<ShapeCastHit> turningCast(const QueryScene &scene, const Shape &shape, const Vector3 &position,
                                        const Quaternion &orientation, const CastMotion &motion,
                                        const QueryFilter &filter);

}  // namespace cyclone::detail
