// Shape casts: the first time a shape moving along a straight line, and perhaps turning
// as it goes, touches another.
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

/// How a cast shape moves: over the cast (fraction s from 0 to 1) every point of it moves
/// by s translation and turns by s angle about `axis` through `pivot` (the pivot itself
/// moving with the translation): a constant linear and angular velocity.
struct CastMotion {
    Vector3 translation = Vector3::Zero();  ///< World space, m over the cast.
    Vector3 pivot = Vector3::Zero();        ///< The point turned about, at the start, world space, m.
    Vector3 axis = Vector3::UnitY();        ///< Unit, world space.
    real angle = 0;                         ///< rad over the cast, >= 0; 0: a straight cast.

    /// A pose `start` (at s = 0) carried to fraction s.
    Matrix4 at(const Matrix4 &start, real s) const;
    /// The velocity (per unit of s) at s of the point that is at `point` then.
    Vector3 velocity(const Vector3 &point, real s) const;
    /// The most any point within `reach` of the pivot moves along unit `direction` per
    /// unit of s: translation.direction plus angle |direction x axis| reach.
    real closingBound(const Vector3 &direction, real reach) const;
    /// How far from the pivot the points of a shape of bounding radius `radius` at
    /// `start` lie, at most (0 for a straight cast: nothing turns).
    real reach(const Matrix4 &start, real radius) const;
};

/// The first fraction of `motion` at which `moving`, starting at `start`, touches
/// `target` at `targetPose`, if at or before `limit` (<= 1). The motion must move the
/// shape (a translation or an angle not zero). Solids (and each child of a compound,
/// each triangle of a mesh or a height field) by conservative advancement on their GJK
/// distance d along the unit direction n between them: no point of the moving shape
/// closes on the separating plane faster than closingBound(n, reach), so it may advance
/// by d over that bound without passing the first touch. Without a turn the bound is the
/// closing speed itself and, the distance of two convex shapes being convex along a
/// translation, a few steps reach the tolerance (one for flat contacts). Planes in
/// closed form when the shape does not turn. A shape that overlaps or touches the target
/// at the start hits it at 0 only if the motion takes its deepest (touching) point
/// deeper into it; otherwise the target is left out, so that a cast from a resting pose
/// slides along what it rests on.
bool castShape(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
               const CollisionShape &target, const Matrix4 &targetPose, real limit, CastHit &hit);

}  // namespace cyclone::detail
