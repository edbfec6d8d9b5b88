// A convex shape against a triangle mesh: the manifolds of the triangles it touches, or
// can reach within the step, with inner edges smoothed over (mesh_features.h).
#pragma once

#include <vector>

#include "collision/narrowphase.h"

namespace cyclone::detail {

/// One contact reported by FCL, oriented from A to B; the triangle of the side that is a
/// mesh (the other side's index means nothing).
struct RawContact {
    Vector3 normal;
    real depth;
    int triangleA;
    int triangleB;
};

/// The manifolds of shape `a` against `b`, one of them a mesh, from FCL's contacts `raw`
/// (one per triangle the shape overlaps) and, when `reach` > 0, from the triangles apart
/// from it by less than `reach` (speculative contacts, their depths the gap). Points up
/// to `speculative` apart are kept. Returns the number appended to `out`.
int meshContacts(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                 real speculative, real reach, const RawContact *raw, int rawCount, std::vector<Manifold> &out);

}  // namespace cyclone::detail
