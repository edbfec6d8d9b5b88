// Round pairs from their closest features. A capsule is a segment grown by its radius, so
// two round shapes touch where their core features (a point, a segment, a box) come
// within the sum of the radii, along the line between the features' closest points: that
// line is the exact contact normal, and the radii less its length the exact depth,
// however deep, for as long as the cores stay apart. Cores that meet (a capsule's segment
// through a box, two segments crossing) are pushed apart along the axis of least
// penetration of the cores, which the radii then deepen by the same amount along every
// axis. The narrowphase clips the manifold along the normal found here, as for the other
// closed-form pairs.
#include "collision/round_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cyclone::detail {
namespace {

// Features closer than this have no line between them to give a normal, m.
constexpr real kMinFeatureDistance = 1e-9;
// Segments whose cross product is below this times their lengths' product are parallel.
constexpr real kParallel = 1e-12;
// A face axis wins a tie with a swept edge axis within this overlap, m.
constexpr real kFaceAxisPreference = 1e-9;

// A unit vector across v, the same for the same v: across world y too where v allows
// (x when v is vertical or zero), so that round shapes whose cores meet are pushed apart
// sideways. With gravity along -y, the vertical choice pushed the lower of each pair into
// the floor under it: 100 capsules spawned at one point on a 0.2 m box floor lost 27
// through it (docs/hostile_input.md).
Vector3 across(const Vector3 &v) {
    const Vector3 c = v.cross(Vector3::UnitY());
    const real length = c.norm();
    return length > kParallel * v.norm() ? Vector3(c / length) : Vector3::UnitX();
}

// Whether segment [p, q] (box-local) meets the box of half extents `half`, touching
// included: the segment clipped against the three slabs keeps some of itself.
bool segmentMeetsBox(const Vector3 &p, const Vector3 &q, const Vector3 &half) {
    const Vector3 d = q - p;
    real lo = 0, hi = 1;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0) {
            if (std::abs(p[k]) > half[k]) return false;
            continue;
        }
        real t0 = (-half[k] - p[k]) / d[k];
        real t1 = (half[k] - p[k]) / d[k];
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
        if (lo > hi) return false;
    }
    return true;
}

// The closest points of segment [p, q] and the box of half extents `half` (box-local),
// for a segment that does not meet the box. The distance, a convex function along the
// segment, is smallest either at an end of the segment or where the segment passes
// nearest one of the box's twelve edges: within a face's region it changes linearly.
void closestToBox(const Vector3 &p, const Vector3 &q, const Vector3 &half, Vector3 &onSegment, Vector3 &onBox) {
    real best = std::numeric_limits<real>::infinity();
    const auto consider = [&](const Vector3 &s, const Vector3 &b) {
        const real d = (b - s).squaredNorm();
        if (d < best) best = d, onSegment = s, onBox = b;
    };
    consider(p, p.cwiseMax(-half).cwiseMin(half));
    consider(q, q.cwiseMax(-half).cwiseMin(half));
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        for (int corner = 0; corner < 4; ++corner) {
            Vector3 e0 = Vector3::Zero(), e1 = Vector3::Zero();
            e0[i] = e1[i] = corner & 1 ? half[i] : -half[i];
            e0[j] = e1[j] = corner & 2 ? half[j] : -half[j];
            e0[k] = -half[k];
            e1[k] = half[k];
            real s = 0, t = 0;
            closestOnSegments(p, q, e0, e1, s, t);
            consider(p + s * (q - p), e0 + t * (e1 - e0));
        }
    }
}

}  // namespace

void closestOnSegments(const Vector3 &p0, const Vector3 &p1, const Vector3 &q0, const Vector3 &q1, real &s, real &t) {
    const Vector3 u = p1 - p0;
    const Vector3 v = q1 - q0;
    const Vector3 w = p0 - q0;
    const real uu = u.squaredNorm(), vv = v.squaredNorm();
    const real uw = u.dot(w), vw = v.dot(w);
    s = t = 0;
    if (uu <= 0 && vv <= 0) return;
    if (uu <= 0) {
        t = std::clamp(vw / vv, real(0), real(1));
        return;
    }
    if (vv <= 0) {
        s = std::clamp(-uw / uu, real(0), real(1));
        return;
    }
    // Minimise |w + s u - t v|^2: the lines' closest points, then each clamped to its
    // segment with the other's parameter found again from it.
    const real uv = u.dot(v);
    const real denominator = uu * vv - uv * uv;
    s = denominator > kParallel * uu * vv ? std::clamp((uv * vw - vv * uw) / denominator, real(0), real(1)) : 0;
    t = (uv * s + vw) / vv;
    if (t < 0) {
        t = 0;
        s = std::clamp(-uw / uu, real(0), real(1));
    } else if (t > 1) {
        t = 1;
        s = std::clamp((uv - uw) / uu, real(0), real(1));
    }
}

bool sphereCapsule(real radius, const Vector3 &centre, real capsuleRadius, const Vector3 &end0, const Vector3 &end1,
                   Manifold &out, real reach) {
    const Vector3 axis = end1 - end0;
    const real length2 = axis.squaredNorm();
    const real s = length2 > 0 ? std::clamp((centre - end0).dot(axis) / length2, real(0), real(1)) : real(0);
    const Vector3 core = end0 + s * axis;
    const Vector3 offset = core - centre;
    const real distance = offset.norm();
    const real depth = radius + capsuleRadius - distance;
    if (!(depth >= -reach)) return false;
    const Vector3 n = distance > kMinFeatureDistance ? Vector3(offset / distance) : across(axis);
    out.normal = n;
    out.count = 1;
    out.points[0].pointA = centre + radius * n;
    out.points[0].pointB = core - capsuleRadius * n;
    out.points[0].depth = depth;
    return true;
}

bool capsuleCapsuleNormal(real radiusA, const Vector3 &a0, const Vector3 &a1, real radiusB, const Vector3 &b0,
                          const Vector3 &b1, Vector3 &normal, real &depth, real reach) {
    real s = 0, t = 0;
    closestOnSegments(a0, a1, b0, b1, s, t);
    const Vector3 between = (b0 + t * (b1 - b0)) - (a0 + s * (a1 - a0));
    const real distance = between.norm();
    if (distance > kMinFeatureDistance) {
        depth = radiusA + radiusB - distance;
        if (!(depth >= -reach)) return false;
        normal = between / distance;
        return true;
    }
    // The segments meet: along any direction across both, each projects to one value, the
    // same for both, so the overlap there is the sum of the radii, the least possible
    // (along any other the segments' projections overlap as well).
    const Vector3 u = a1 - a0, v = b1 - b0;
    const Vector3 centres = 0.5 * (b0 + b1 - a0 - a1);
    Vector3 n = u.cross(v);
    if (n.squaredNorm() <= kParallel * u.squaredNorm() * v.squaredNorm()) {
        // Parallel (or a capsule without length): across the longer one, towards B.
        const Vector3 line = u.squaredNorm() >= v.squaredNorm() ? u : v;
        const real line2 = line.squaredNorm();
        n = line2 > 0 ? Vector3(centres - centres.dot(line) / line2 * line) : centres;
        if (n.norm() <= kMinFeatureDistance) n = across(line);
    }
    n.normalize();
    normal = n.dot(centres) >= 0 ? n : Vector3(-n);
    depth = radiusA + radiusB;
    return true;
}

bool capsuleBoxNormal(real radius, const Vector3 &end0, const Vector3 &end1, const Vector3 &half,
                      const Matrix4 &poseBox, Vector3 &normal, real &depth, real reach) {
    const Matrix3 rotation = poseBox.linear();
    const Vector3 p = rotation.transpose() * (end0 - poseBox.translation());
    const Vector3 q = rotation.transpose() * (end1 - poseBox.translation());
    if (!segmentMeetsBox(p, q, half)) {
        Vector3 onSegment = p, onBox = p;
        closestToBox(p, q, half, onSegment, onBox);
        const Vector3 between = onBox - onSegment;
        const real distance = between.norm();
        if (distance > kMinFeatureDistance) {
            depth = radius - distance;
            if (!(depth >= -reach)) return false;
            normal = rotation * (between / distance);
            return true;
        }
    }
    // The segment meets the box: the least overlap over the face normals of the box swept
    // along the segment (box-local; n from the capsule to the box).
    const auto overlap = [&](const Vector3 &n) {
        return std::max(p.dot(n), q.dot(n)) + radius + n.cwiseAbs().dot(half);
    };
    Vector3 best = Vector3::UnitX();
    real least = std::numeric_limits<real>::infinity();
    const auto consider = [&](const Vector3 &n, real preference) {
        for (const real sign : {real(1), real(-1)}) {
            const real o = overlap(sign * n);
            if (o < least - preference) least = o, best = sign * n;
        }
    };
    for (int k = 0; k < 3; ++k) consider(Vector3::Unit(k), 0);
    const Vector3 u = q - p;
    for (int k = 0; k < 3; ++k) {
        const Vector3 c = u.cross(Vector3::Unit(k));
        const real length = c.norm();
        if (length > kParallel * u.norm()) consider(c / length, kFaceAxisPreference);
    }
    depth = least;
    normal = rotation * best;
    return true;
}

}  // namespace cyclone::detail
