// Shape casts: the first time a shape moving along a straight line touches another.
#pragma once

#include "collision/collision_shape.h"

namespace cyclone::detail {

/// How far apart a shape cast leaves the two shapes at the distance it reports, at most,
/// m: the cast stops when the gap is below this, and never lets the shapes overlap.
inline constexpr real kShapeCastTolerance = 1e-4;

/// Where a shape cast first touches.
struct CastHit {
    real fraction = 0;                  ///< Of the translation, in [0, 1].
    Vector3 point = Vector3::Zero();    ///< Where the shapes touch, world space, m.
    Vector3 normal = Vector3::UnitY();  ///< Unit, out of the target, towards the cast shape.
};

/// The first fraction of `translation` (world space, m, not zero) at which `moving`,
/// starting at `start` and keeping its orientation, touches `target` at `targetPose`,
/// if at or before `limit` (<= 1). Solids (and each child of a compound, each triangle of
/// a mesh) by conservative advancement on their GJK distance: the distance along the
/// motion's closing speed is a safe step, as the distance of two convex shapes is a
/// convex function of a translation. Planes in closed form. A shape that overlaps the
/// target at the start hits it at 0 only if the motion goes deeper into it (along the
/// contact normal); otherwise the target is left out, so that a cast from a resting pose
/// slides along what it rests on.
bool castShape(const CollisionShape &moving, const Matrix4 &start, const Vector3 &translation,
               const CollisionShape &target, const Matrix4 &targetPose, real limit, CastHit &hit);

}  // namespace cyclone::detail
