// Continuous collision: the time at which a shape moving over a step first touches
// another, for bodies that ask for it (BodySettings::ccd).
#pragma once

#include "collision_shape.h"

namespace cyclone::detail {

/// Radius of the largest ball about the shape's origin that fits inside the shape, m
/// (0 for a plane or mesh, or a hull whose origin is not inside it). A body that moves
/// less than this in a step cannot pass through anything.
real innerRadius(const CollisionShape &shape);

/// How timeOfImpact() found the time of a pair.
enum class SweepMethod {
    /// fcl::continuousCollide with conservative advancement (linear interpolation of
    /// both poses): boxes, spheres, capsules, cylinders and meshes.
    ConservativeAdvancement,
    /// Poses sampled no further apart than the moving body's inner radius, fcl::collide
    /// at each, and bisection of the first interval that ends in contact: convex hulls.
    Sampled,
};

/// The method timeOfImpact() uses for shapes `a` (the moving body) and `b`.
SweepMethod sweepMethod(const CollisionShape &a, const CollisionShape &b);

/// The earliest fraction t in (0, 1) of the motion at which `a`, moving from `a0` to
/// `a1` (translation linear, rotation at constant angular velocity), touches `b`,
/// moving likewise from `b0` to `b1`; `aInnerRadius` is innerRadius(a). False when they
/// do not touch before the end, or already touch at the start (the step's contacts deal
/// with that pair). On true, `poseA` is a's pose at t, in contact within 1 mm or
/// 1e-4 of the motion, whichever is larger. Neither shape may be a plane.
bool timeOfImpact(const CollisionShape &a, const Matrix4 &a0, const Matrix4 &a1, real aInnerRadius,
                  const CollisionShape &b, const Matrix4 &b0, const Matrix4 &b1, real &t, Matrix4 &poseA);

/// The pose at fraction t of the motion from `from` to `to` (translation linear,
/// rotation at constant angular velocity).
Matrix4 interpolate(const Matrix4 &from, const Matrix4 &to, real t);

}  // namespace cyclone::detail
