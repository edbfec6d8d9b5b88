// Debug drawing (debug_draw.cpp): the World's bodies, boxes, joints and contacts as lines
// through the game's DebugDraw. World::debugDraw (world/world_queries.cpp) calls these.
#pragma once

#include <cstdint>

#include "contacts/pair_cache.h"
#include "cyclone/world/world.h"
#include "joints/joint_set.h"
#include "world/body_store.h"

namespace cyclone::detail {

/// What debug drawing reads: the bodies, the joints, the contact pairs, and the count of
/// the World's changing calls (WorldState::changingCalls), against which a DebugDraw that
/// changed the World is refused.
struct DrawScene {
    const BodyStore &bodies;
    const JointSet &joints;
    const PairCache &pairs;
    const std::uint64_t &changingCalls;
};

/// Refuses (naming World::debugDraw) an option out of range.
void validateDrawOptions(const DebugDrawOptions &options);
/// Draws the scene through `draw` as `options` (valid) asks.
void debugDraw(const DrawScene &scene, DebugDraw &draw, const DebugDrawOptions &options);

}  // namespace cyclone::detail
