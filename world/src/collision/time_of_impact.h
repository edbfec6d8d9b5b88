// Continuous collision: the time at which a shape moving over a step first touches
// another, for bodies that ask for it (BodySettings::ccd).
#pragma once

#include <memory>

#include "collision/collision_shape.h"

namespace cyclone::detail {

/// How far apart timeOfImpact() may leave two shapes at the time it reports, m.
inline constexpr real kSweepTolerance = 0.00005;

/// A shape as a sweep sees it.
struct SweptShape {
    const fcl::CollisionGeometryd *geometry = nullptr;
    /// A compound, whose children are tested in place of `geometry`; null otherwise.
    const CollisionShape *compound = nullptr;
    /// Farthest point of the shape from its origin, m.
    real boundingRadius = 0;
    /// Radius of the largest ball about the origin inside the shape, m (0 for a mesh, or
    /// a hull whose origin is not inside it; a compound's is its children's largest ball
    /// about the centre of mass, if any child holds one). A body that moves less than this in a step
    /// cannot pass through anything.
    real innerRadius = 0;
};

/// The sweep's view of a compiled shape (not a plane).
SweptShape sweptShape(const CollisionShape &shape);

/// The core of a shape: a sphere at its origin, a quarter of its inner radius (or of 1%
/// of its bounding radius, if it has none). Swept when the shape itself already touches.
std::shared_ptr<fcl::CollisionGeometryd> makeCore(const SweptShape &shape);
/// The sweep's view of a core made by makeCore.
SweptShape sweptCore(const fcl::CollisionGeometryd &core);

/// What timeOfImpact() found.
enum class Impact {
    None,         ///< No contact before the end of the motion.
    Hit,          ///< First contact at the fraction reported.
    Overlapping,  ///< The shapes already overlap at the start.
};

/// The earliest fraction t in (0, 1) of the motion at which `a`, moving from `a0` to `a1`
/// (translation linear, rotation at constant angular velocity), touches `b`, moving
/// likewise from `b0` to `b1`. On Hit the shapes are apart at t by at most
/// kSweepTolerance (or 1e-7 of the motion, if that is larger). Poses are sampled no
/// further apart than a's inner radius (b's motion included), so that consecutive poses
/// of `a` overlap and its centre cannot cross a surface unseen; each is tested with
/// FCL's contact test (two boxes by their separating axes, box_box.h), and the first
/// interval that ends in contact is bisected.
Impact timeOfImpact(const SweptShape &a, const Matrix4 &a0, const Matrix4 &a1, const SweptShape &b,
                    const Matrix4 &b0, const Matrix4 &b1, real &t);

/// What timeOfImpact() reports for the same motions, without finding the time: it stops
/// at the first sampled pose in contact instead of bisecting towards the first contact.
Impact meetDuring(const SweptShape &a, const Matrix4 &a0, const Matrix4 &a1, const SweptShape &b, const Matrix4 &b0,
                  const Matrix4 &b1);

/// The distance between `a` and `b` and the unit direction from a's nearest point to
/// b's, by fcl::distance; false when they touch or FCL gives no direction.
bool separation(const SweptShape &a, const Matrix4 &poseA, const SweptShape &b, const Matrix4 &poseB,
                real &distance, Vector3 &direction);

/// How far any point of a shape of bounding radius `radius` moves from `from` to `to`
/// (translation plus rotation angle times radius), m.
real travel(const Matrix4 &from, const Matrix4 &to, real radius);

/// Whether travel(from, to, radius) is surely below `limit`, from a bound on it without
/// trigonometry (at most pi / 2 times the travel, and 1e-6 m of margin): true only when
/// travel() is below `limit`; false may also mean the bound could not tell.
bool travelWithin(const Matrix4 &from, const Matrix4 &to, real radius, real limit);

/// The pose at fraction t of the motion from `from` to `to` (translation linear,
/// rotation at constant angular velocity).
Matrix4 interpolate(const Matrix4 &from, const Matrix4 &to, real t);

}  // namespace cyclone::detail
