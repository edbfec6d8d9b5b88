// Cylinder pairs from their closest features: a cylinder against a cylinder or a capsule
// where two round sides touch. FCL's libccd answers these through MPR, whose normal for
// a deep overlap is only approximate.
#pragma once

#include "collision/contact_building.h"

namespace cyclone::detail {

/// The straight core of a cylinder or capsule, world space: its axis segment [end0, end1]
/// and its radius; `cylinder` false for a capsule (whose ends are round).
struct AxisCore {
    Vector3 end0, end1;
    real radius;
    bool cylinder;
};

/// The axis core of a cylinder or capsule placed at `pose` (its segment along the local z
/// axis, `length` long).
AxisCore axisCore(const CollisionShape &shape, const Matrix4 &pose);

/// Whether shapes of these types are a cylinder and a cylinder or a capsule.
bool cylinderRoundPair(ShapeType a, ShapeType b);

/// The unit direction from A's axis segment's closest point to B's (zero when they meet).
Vector3 coreLine(const AxisCore &a, const AxisCore &b);

/// How cylinderPairNormal ended.
enum class CylinderPairResult {
    Apart,      ///< Apart by more than the reach: no contact.
    Found,      ///< `normal` is set.
    NotHandled  ///< Not two round sides facing each other: ask FCL.
};

/// The contact normal (unit, world space, from A to B) of the pair's shapes, cores `a` and
/// `b`, at least one a cylinder, where two round sides face each other: the closest
/// points of the two axis segments lie inside each cylinder's segment, farther than the
/// other's radius from its ends (anywhere on a capsule's), and no cap's axis overlaps
/// less.
/// The normal is then the line between those points, exact at any depth (the radii less
/// their distance is the depth).
CylinderPairResult cylinderPairNormal(const Pair &pair, const AxisCore &a, const AxisCore &b, real reach,
                                      Vector3 &normal);

/// Adds to `points` the contact points of the axis segments' ends of nearly parallel
/// cores (within 20 degrees) whose `normal` (A to B) lies within 20 degrees of across
/// both: each end over the other core's side, on the normal's side of it (within 20
/// degrees), its surface point nearest that side and the side's point under it,
/// measured along `normal`, when no farther apart than `speculative` (m) and not within
/// 1 cm of a point already in `points`. A cylinder landing on another at a slant touches
/// at one end first; its other end then has a point before it comes down (a point with a
/// gap only lets the gap close).
void addAxisEnds(const AxisCore &a, const AxisCore &b, const Vector3 &normal, real speculative, PointSet &points);

}  // namespace cyclone::detail
