// GJK (gjk.h) on the Minkowski difference of the two cores: a sphere's or a capsule's
// nearest point lies a radius out from its core's along the line between the cores, so the
// distance is the cores' less the radii, along the same line. On a point or a segment GJK
// ends in a few iterations, where on the round surface it would creep.
#include "collision/separation.h"

#include "collision/gjk.h"

namespace cyclone::detail {

bool separation(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                real &distance, Vector3 &direction) {
    auto support = [&](const Vector3 &d) {
        return Vector3(coreSupport(a, poseA, d, -1) - coreSupport(b, poseB, -d, -1));
    };
    Vector3 start = poseA.translation() - poseB.translation();
    if (!(start.squaredNorm() > 0)) start = Vector3::UnitX();
    Vector3 closest;
    if (!closestToOrigin(support, start.normalized(), closest)) return false;
    // The cores' nearest points, A's less B's: B's lies along -closest from A's.
    const real cores = closest.norm();
    distance = cores - coreRadius(a) - coreRadius(b);
    if (!(distance > 0)) return false;
    direction = -closest / cores;
    return true;
}

}  // namespace cyclone::detail
