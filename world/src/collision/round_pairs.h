// Round pairs in closed form: sphere-capsule, capsule-capsule and capsule-box from their
// closest features, exact at any depth. FCL's libccd answers these through MPR, whose
// normal for a deep overlap is only approximate.
#pragma once

#include "collision/narrowphase.h"

namespace cyclone::detail {

/// The closest points of segments [p0, p1] and [q0, q1]: p0 + s (p1 - p0) and
/// q0 + t (q1 - q0), s and t in [0, 1]. Parallel segments that overlap along their
/// direction have many; this gives the one at an end of the overlap.
void closestOnSegments(const Vector3 &p0, const Vector3 &p1, const Vector3 &q0, const Vector3 &q1, real &s, real &t);

/// Sphere A (`radius` about `centre`) against capsule B (`capsuleRadius` about the
/// segment [end0, end1]). Returns false when they are apart by more than `reach` (m);
/// otherwise fills `out` with one point, as sphereSphere does for the sphere and the end
/// sphere centred on the segment's point nearest `centre`. A centre on the segment is
/// pushed out across the segment (any direction across it: every one is as deep).
bool sphereCapsule(real radius, const Vector3 &centre, real capsuleRadius, const Vector3 &end0, const Vector3 &end1,
                   Manifold &out, real reach = 0);

/// The contact normal (unit, world space, from A to B) of capsule A (`radiusA` about
/// [a0, a1]) and capsule B (`radiusB` about [b0, b1]): along the segments' closest points,
/// or, where the segments meet, across both. Returns false when the capsules are apart by
/// more than `reach` (m); `depth` is then unset, else it is the penetration along
/// `normal` (negative when apart), m.
bool capsuleCapsuleNormal(real radiusA, const Vector3 &a0, const Vector3 &a1, real radiusB, const Vector3 &b0,
                          const Vector3 &b1, Vector3 &normal, real &depth, real reach = 0);

/// The contact normal (unit, world space, from the capsule to the box) of a capsule
/// (`radius` about [end0, end1]) and a box (half extents `half` at `poseBox`): along the
/// closest points of the segment and the box while the segment is outside the box, else
/// the axis of least penetration among the box's three face normals and the segment's
/// direction crossed with its three edge directions (the face normals of the box swept
/// along the segment; a face wins a tie). Returns false when apart by more than `reach`
/// (m); otherwise `depth` is the penetration along `normal` (negative when apart), m.
bool capsuleBoxNormal(real radius, const Vector3 &end0, const Vector3 &end1, const Vector3 &half,
                      const Matrix4 &poseBox, Vector3 &normal, real &depth, real reach = 0);

}  // namespace cyclone::detail
