// The round side of a contact: a sphere, a capsule, or a cylinder touched on its side or
// rim. A contact point on such a surface is its core (the sphere's centre, a point of the
// capsule's segment, a point of the cylinder's axis) plus the radius along the surface's
// outward normal there. When the body rolls, its deepest point along the contact normal
// stays below the core while a point fixed on the body turns away from it; these say how
// far, so that depths read from anchors fixed on the body stay those of the surface
// (solver/round_depths.h), and match a contact's points by their cores from step to step
// (contacts/pair_cache.h).
#pragma once

#include "collision/collision_shape.h"

namespace cyclone::detail {

/// The round core of a shape in its body's frame. radius 0: the shape is not round.
struct RoundCore {
    real radius = 0;                     ///< m, >= 0 (0: not round).
    Vector3 centre = Vector3::Zero();    ///< The core's middle, body frame, m.
    Vector3 axis = Vector3::Zero();      ///< Capsule, cylinder: unit axis, body frame (zero: a sphere).
    real halfLength = 0;                 ///< Half the core segment's length along the axis, m.
    bool cylinder = false;               ///< The surface is the core's circles (directions taken across the axis).
};

/// The round core of `shape` (of its child `child` when it is a compound), in the body's
/// frame; radius 0 for every other shape.
RoundCore roundCore(const CollisionShape &shape, int child);

/// Whether a contact whose outward normal on the shape is `outward` (unit, body frame)
/// lies on the round part of `core`: always for a sphere or a capsule, for a cylinder
/// unless within 15 degrees of its axis (its cap, a flat face).
bool onRoundPart(const RoundCore &core, const Vector3 &outward);

/// Whether `shape` may have round parts: a sphere, a capsule, a cylinder or a compound.
bool mayBeRound(const CollisionShape &shape);

/// The round core of the side of `shape` (its child `child`) that a contact whose outward
/// normal on it is `outward` (unit, body frame) touches: roundCore where onRoundPart,
/// else radius 0.
RoundCore roundSideAt(const CollisionShape &shape, int child, const Vector3 &outward);

/// The side line of a capsule or cylinder at `pose` (world) that reaches farthest along
/// `direction` (world, unit): its two ends, each an end of the core plus the radius along
/// `direction` (across the axis, for a cylinder). False for other shapes, a cylinder
/// whose axis is along `direction` (its cap reaches farthest) and a core of no length.
bool farthestSideLine(const CollisionShape &shape, const Matrix4 &pose, const Vector3 &direction, Vector3 &end0,
                      Vector3 &end1);

/// The point of the core nearest `point` (body frame, m).
Vector3 nearestCorePoint(const RoundCore &core, const Vector3 &point);

/// How much deeper along its outward normal the round surface reaches than a point fixed
/// on the body that was its deepest point when the outward normal was `start` (body
/// frame, unit), now that it is `now`: r (|P now| - P start / |P start| . now), P taking
/// away the component along a cylinder's axis (the identity for a sphere or capsule).
/// Zero when now = start, r (1 - cos a) after a turn by a.
real roundDepthChange(const RoundCore &core, const Vector3 &start, const Vector3 &now);

}  // namespace cyclone::detail
