// Sphere contacts in closed form. The general narrowphase reaches the same answers
// through FCL's exact sphere routines and its least-overlap choice of normal (for a
// sphere the least overlap is the true penetration); these skip FCL and its
// allocations.
#include "collision/sphere_pairs.h"

#include <algorithm>
#include <cmath>

namespace cyclone::detail {
namespace {

// Centres closer than this have their offset scaled before it is normalised, m.
constexpr real kMinCentreDistance = 1e-9;

// The direction from centre a to centre b (`distance` apart), for a normal: their
// offset's when they are apart, however little (scaled before normalising so that 1e-200 m does not underflow
// to zero); +x when they coincide, so that coincident spheres are still pushed apart,
// every run alike. Sideways rather than up (Jolt's choice): with gravity along -y, up
// pushes the lower sphere of each pair down, and 100 spheres spawned at one point on a
// 0.2 m box floor drove 38 of them through it (docs/hostile_input.md).
Vector3 apart(const Vector3 &offset, real distance) {
    if (distance > kMinCentreDistance) return offset / distance;
    const real largest = offset.cwiseAbs().maxCoeff();
    if (!(largest > 0)) return Vector3::UnitX();
    const Vector3 scaled = offset / largest;
    return scaled / scaled.norm();
}

void onePoint(const Vector3 &normal, const Vector3 &pointA, const Vector3 &pointB, real depth, Manifold &out) {
    out.normal = normal;
    out.count = 1;
    out.points[0].pointA = pointA;
    out.points[0].pointB = pointB;
    out.points[0].depth = depth;
}

}  // namespace

bool sphereSphere(real radiusA, const Vector3 &centreA, real radiusB, const Vector3 &centreB, Manifold &out,
                  real reach) {
    const Vector3 offset = centreB - centreA;
    const real distance = offset.norm();
    const real depth = radiusA + radiusB - distance;
    if (!(depth >= -reach)) return false;
    const Vector3 n = apart(offset, distance);
    onePoint(n, centreA + radiusA * n, centreB - radiusB * n, depth, out);
    return true;
}

bool sphereBox(real radius, const Vector3 &centre, const Vector3 &half, const Matrix4 &poseB, Manifold &out,
               real reach) {
    const Matrix3 rotation = poseB.linear();
    const Vector3 local = rotation.transpose() * (centre - poseB.translation());
    const Vector3 nearest = local.cwiseMax(-half).cwiseMin(half);
    const Vector3 toBox = nearest - local;
    const real distance = toBox.norm();
    if (distance > 0) {
        // Centre outside the box: the normal runs from the centre to the nearest point.
        const real depth = radius - distance;
        if (!(depth >= -reach)) return false;
        const Vector3 n = rotation * (toBox / distance);
        onePoint(n, centre + radius * n, rotation * nearest + poseB.translation(), depth, out);
        return true;
    }
    // Centre inside: out through the nearest face.
    int axis = 0;
    real inside = half[0] - std::abs(local[0]);
    for (int k = 1; k < 3; ++k) {
        const real d = half[k] - std::abs(local[k]);
        if (d < inside) inside = d, axis = k;
    }
    const real side = local[axis] >= 0 ? 1 : -1;
    Vector3 onFace = local;
    onFace[axis] = side * half[axis];
    const Vector3 n = -side * rotation.col(axis);
    onePoint(n, centre + radius * n, rotation * onFace + poseB.translation(), radius + inside, out);
    return true;
}

}  // namespace cyclone::detail
