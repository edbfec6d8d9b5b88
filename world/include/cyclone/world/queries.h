/// \file
/// Queries against a World's bodies: the closest hit of a ray (World::rayCast), the
/// first hit of a moving shape (World::shapeCast) and the bodies a shape overlaps
/// (World::overlap). Both walk the broadphase trees, so their
/// cost grows with the bodies near the ray or the shape, not with the world's size.
#pragma once

#include <functional>
#include <optional>

#include "cyclone/core.h"
#include "cyclone/world/settings.h"

namespace cyclone {

/// Which bodies a query considers. The default considers every body.
struct QueryFilter {
    /// Whether static bodies (planes and meshes included) are considered.
    bool staticBodies = true;
    /// Whether dynamic bodies, awake or asleep, are considered.
    bool dynamicBodies = true;
    /// Whether kinematic bodies, moving or not, are considered.
    bool kinematicBodies = true;
    /// The layers considered, bit k for layer k (BodySettings::layer); every layer by default.
    std::uint32_t layers = kAllLayers;
    /// Whether sensors (BodySettings::sensor) are considered; by default a ray or a shape
    /// passes through them as bodies do.
    bool sensors = false;
    /// A body to leave out, e.g. the player's own body when casting from its eyes (a
    /// handle that names no body of the world leaves nothing out).
    std::optional<BodyId> ignore;
    /// When set, a body is considered only if this returns true for it. It is called
    /// only for bodies that pass the fields above and whose bounding box the query
    /// reaches, before the exact test; it must not change the World: one that calls a
    /// member of the World that may change it (addBody, removeBody, setVelocity, step,
    /// any non-const one) makes the query throw InvalidArgument (field
    /// "filter.accept") as soon as it returns (the change itself stays made).
    std::function<bool(BodyId)> accept;
};

/// The closest hit of a ray, as returned by World::rayCast().
struct RayHit {
    /// The body hit.
    BodyId body;
    /// World-space point where the ray meets the body's surface, m.
    Vector3 point = Vector3::Zero();
    /// Unit surface normal at `point`, world space: outward for solid shapes and planes;
    /// for a mesh triangle (hit from either side), the side the ray came from.
    Vector3 normal = Vector3::UnitY();
    /// Distance from the ray's origin to `point`, m, in [0, maxDistance].
    real distance = 0;
    /// The body's BodySettings::userData.
    std::uint64_t userData = 0;
};

/// The first hit of a shape cast, as returned by World::shapeCast().
struct ShapeCastHit {
    /// The body hit.
    BodyId body;
    /// How much of the translation the shape travels before it touches, in [0, 1].
    real fraction = 0;
    /// The same as a distance along the translation, m: fraction times its length (0 for
    /// a shape that turns in place).
    real distance = 0;
    /// World-space point where the shapes touch, on the cast shape, m (along a face or
    /// an edge, one of its points).
    Vector3 point = Vector3::Zero();
    /// Unit surface normal of the body hit at `point`, world space, pointing out of it
    /// towards the cast shape.
    Vector3 normal = Vector3::UnitY();
    /// The body's BodySettings::userData.
    std::uint64_t userData = 0;
};

}  // namespace cyclone
