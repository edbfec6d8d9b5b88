// Exact ray tests: a ray against each shape type, and against a box of a tree.
#pragma once

#include <fcl/fcl.h>

#include "collision/collision_shape.h"

namespace cyclone::detail {

/// A ray in world space: origin (m), unit direction, and the longest distance that
/// counts (m, > 0, may be infinite).
struct Ray {
    Vector3 origin;
    Vector3 direction;
    real maxDistance;
};

/// Where a ray meets a surface: distance along the ray (m) and unit world normal.
struct RaySurfaceHit {
    real distance = 0;
    Vector3 normal = Vector3::UnitY();
};

/// The first point where `ray` enters `shape` placed at `pose`, within [0, maxDistance]:
/// exact for boxes, spheres, capsules, cylinders, convex hulls and planes (whose solid
/// side the ray must enter from outside), and for mesh triangles hit from either side.
/// A solid that contains the origin is not hit; a compound is hit where the ray first
/// enters one of its children. False when there is no such point.
bool rayShape(const Ray &ray, const CollisionShape &shape, const Matrix4 &pose, RaySurfaceHit &hit);

/// The distance at which `ray` enters `box` (0 when it starts inside), if it does so
/// within [0, limit].
bool rayBox(const Vector3 &origin, const Vector3 &direction, const Vector3 &min, const Vector3 &max, real limit,
            real &enter);

/// Visits the two children of a tree node nearest first: `reached[k]` and `enter[k]` say
/// whether and at what distance the ray enters child k. A child is skipped when not
/// reached or entered beyond `limit`, which is read at each visit: visiting the first
/// child may shorten it.
template <class Child, class Visit>
void visitNearestFirst(const Child (&children)[2], const bool (&reached)[2], const real (&enter)[2],
                       const real &limit, Visit visit) {
    const int first = !reached[0] || (reached[1] && enter[1] < enter[0]) ? 1 : 0;
    for (const int k : {first, 1 - first})
        if (reached[k] && enter[k] <= limit) visit(children[k]);
}

}  // namespace cyclone::detail
