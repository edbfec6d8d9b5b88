// Sphere against sphere and sphere against box: closed-form contacts without FCL.
#pragma once

#include "collision/narrowphase.h"

namespace cyclone::detail {

/// Both take `reach`, m: spheres apart by less than it still get their point, with a
/// negative depth (a speculative contact).
///
/// Sphere A (`radiusA` about `centreA`) against sphere B. Returns false when they are
/// apart (touching is a contact, 0 deep, as in FCL) or their centres are too close to give a normal;
/// otherwise fills `out` with one point: the normal from A's centre to B's, pointA and
/// pointB each sphere's point deepest into the other.
bool sphereSphere(real radiusA, const Vector3 &centreA, real radiusB, const Vector3 &centreB, Manifold &out,
                  real reach = 0);

/// Sphere A (`radius` about `centre`) against box B (half extents `half` at `poseB`).
/// Returns false when they are apart (touching is a contact); otherwise fills `out` with one point: pointB
/// the box's point nearest the centre (its nearest face's point when the centre is
/// inside), pointA the sphere's point deepest into the box, the normal from A to B.
bool sphereBox(real radius, const Vector3 &centre, const Vector3 &half, const Matrix4 &poseB, Manifold &out,
               real reach = 0);

}  // namespace cyclone::detail
