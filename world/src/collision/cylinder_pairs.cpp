// Cylinder pairs from their closest features. A cylinder's side, like a capsule's, is its
// axis segment grown by its radius across the axis: where the closest points of two axis
// segments lie inside both, each surface there is its axis point plus the radius along
// the line between the points, so that line is the exact normal and the radii less its
// length the exact depth, however deep. A cap's axis is a candidate too (a short
// cylinder), as for every closed-form pair the candidate of least overlap wins
// (separating axes); where a cap wins, or a rim or cap faces the other shape, FCL's path
// answers. Nearly parallel round pairs also get their axis segments' ends as points.
#include "collision/cylinder_pairs.h"

#include <cmath>
#include <limits>
#include <utility>

#include "collision/round_pairs.h"

namespace cyclone::detail {
namespace {

// Features closer than this have no line between them to give a normal, m.
constexpr real kMinAxisDistance = 1e-9;
// Axes whose cross product's square is below this times their squared lengths' product
// are parallel (within 1e-6 rad).
constexpr real kParallelAxes = 1e-12;
// Cores whose axes are within 20 degrees of parallel get their segments' ends as points:
// cos(20 deg).
constexpr real kNearlyParallelCosine = 0.9396926207859084;
// ... and only for a normal within 20 degrees of across both axes: sin(20 deg).
constexpr real kAcrossSine = 0.3420201433256687;
// An end's point within this of a point the clipping found is that point, m.
constexpr real kSameEnd = 0.01;
// A cap's axis wins a tie with a side's normal within this overlap (a cap lying flat), m.
constexpr real kCapPreference = 1e-9;

struct AxisCandidate {
    Vector3 normal = Vector3::UnitZ();
    real overlap = std::numeric_limits<real>::infinity();
};

// Both directions along a cylinder's axis (a cap's normal) as candidates.
void considerCap(const Pair &pair, const AxisCore &core, AxisCandidate &best) {
    if (!core.cylinder) return;
    const Vector3 segment = core.end1 - core.end0;
    const real length = segment.norm();
    if (!(length > kMinAxisDistance)) return;
    for (const real sign : {real(1), real(-1)}) {
        const Vector3 n = sign * segment / length;
        const real o = pair.overlap(n);
        if (o <= best.overlap + kCapPreference) {
            best.normal = n;
            best.overlap = o;
        }
    }
}

// The point of `core`'s surface at the end `end` of its segment that reaches farthest
// along -outward (unit): a capsule's end sphere's point, a cylinder's rim point.
Vector3 surfaceTowards(const AxisCore &core, const Vector3 &end, const Vector3 &outward) {
    if (!core.cylinder) return end - core.radius * outward;
    const Vector3 axis = (core.end1 - core.end0).normalized();
    const Vector3 across = outward - outward.dot(axis) * axis;
    const real length = across.norm();
    return length > kMinAxisDistance ? Vector3(end - core.radius * across / length) : end;
}

}  // namespace

void addAxisEnds(const AxisCore &a, const AxisCore &b, const Vector3 &normal, real speculative, PointSet &points) {
    const Vector3 u = a.end1 - a.end0, v = b.end1 - b.end0;
    const real lengths = u.norm() * v.norm();
    if (!(lengths > 0) || std::abs(u.dot(v)) < kNearlyParallelCosine * lengths) return;
    // Only for a normal across both axes (side on side, or a rim on a side): a cap's
    // normal has its own polygon.
    if (std::abs(normal.dot(u)) > kAcrossSine * u.norm() || std::abs(normal.dot(v)) > kAcrossSine * v.norm()) return;
    for (int side = 0; side < 2; ++side) {
        const AxisCore &own = side == 0 ? a : b;
        const AxisCore &other = side == 0 ? b : a;
        // The direction from the other core towards this one.
        const Vector3 towards = side == 0 ? Vector3(-normal) : normal;
        const Vector3 line = other.end1 - other.end0;
        const real line2 = line.squaredNorm();
        for (const Vector3 &end : {own.end0, own.end1}) {
            const real t = (end - other.end0).dot(line) / line2;
            if (!(t > 0 && t < 1)) continue;
            const Vector3 foot = other.end0 + t * line;
            const Vector3 away = end - foot;
            const real distance = away.norm();
            if (!(distance > kMinAxisDistance)) continue;
            // `outward`: from the other core out towards this end.
            const Vector3 outward = away / distance;
            if (outward.dot(towards) < kNearlyParallelCosine) continue;
            const Vector3 onOwn = surfaceTowards(own, end, outward);
            const Vector3 rel = onOwn - other.end0;
            const Vector3 under = other.end0 + rel.dot(line) / line2 * line;
            const Vector3 radial = onOwn - under;
            const real radialLength = radial.norm();
            if (!(radialLength > kMinAxisDistance)) continue;
            const Vector3 onOther = under + other.radius * radial / radialLength;
            const Vector3 &pointA = side == 0 ? onOwn : onOther;
            const Vector3 &pointB = side == 0 ? onOther : onOwn;
            const real depth = (pointA - pointB).dot(normal);
            bool known = false;
            for (int k = 0; k < points.count && !known; ++k)
                known = (points.points[k].pointA - pointA).squaredNorm() < kSameEnd * kSameEnd;
            if (depth >= -speculative && !known) points.add(pointA, pointB, depth);
        }
    }
}

AxisCore axisCore(const CollisionShape &shape, const Matrix4 &pose) {
    const Vector3 half = pose.linear().col(2) * (shape.shape().length / 2);
    AxisCore core;
    core.end0 = pose.translation() - half;
    core.end1 = pose.translation() + half;
    core.radius = shape.shape().radius;
    core.cylinder = shape.shape().type == ShapeType::Cylinder;
    return core;
}

bool cylinderRoundPair(ShapeType a, ShapeType b) {
    if (a != ShapeType::Cylinder) std::swap(a, b);
    return a == ShapeType::Cylinder && (b == ShapeType::Cylinder || b == ShapeType::Capsule);
}

Vector3 coreLine(const AxisCore &a, const AxisCore &b) {
    real s = 0, t = 0;
    closestOnSegments(a.end0, a.end1, b.end0, b.end1, s, t);
    const Vector3 between = (b.end0 + t * (b.end1 - b.end0)) - (a.end0 + s * (a.end1 - a.end0));
    const real distance = between.norm();
    return distance > kMinNormalLength ? Vector3(between / distance) : Vector3::Zero();
}

CylinderPairResult cylinderPairNormal(const Pair &pair, const AxisCore &a, const AxisCore &b, real reach,
                                      Vector3 &normal) {
    real s = 0, t = 0;
    closestOnSegments(a.end0, a.end1, b.end0, b.end1, s, t);
    const Vector3 u = a.end1 - a.end0, v = b.end1 - b.end0;
    const real uu = u.squaredNorm(), vv = v.squaredNorm();
    if (uu > 0 && vv > 0 && u.cross(v).squaredNorm() <= kParallelAxes * uu * vv) {
        // Parallel: every pair across the segments' common stretch is as close; its middle
        // (closestOnSegments gives an end of it, where the other may get out over the rim).
        const real s0 = (b.end0 - a.end0).dot(u) / uu, s1 = (b.end1 - a.end0).dot(u) / uu;
        const real lo = std::max(real(0), std::min(s0, s1)), hi = std::min(real(1), std::max(s0, s1));
        if (lo <= hi) {
            s = 0.5 * (lo + hi);
            t = (a.end0 + s * u - b.end0).dot(v) / vv;
        }
    }
    const Vector3 between = (b.end0 + t * (b.end1 - b.end0)) - (a.end0 + s * (a.end1 - a.end0));
    const real distance = between.norm();
    // A cylinder's side faces the other shape where the closest point lies inside its
    // segment, farther from either end than the other's radius: nearer an end, the other
    // shape may get out more easily over the rim. A capsule's whole surface is round.
    const auto side = [](const AxisCore &core, real at, real margin) {
        const real length = (core.end1 - core.end0).norm();
        return !core.cylinder || (at * length > margin && (1 - at) * length > margin);
    };
    if (!side(a, s, b.radius) || !side(b, t, a.radius) || !(distance > kMinAxisDistance))
        return CylinderPairResult::NotHandled;
    // Two round sides: the line between the axes' closest points crosses both. Their
    // surfaces' points along it, each its core point plus the radius, are the closest
    // points when apart; when the cores are nearer than the radii, the point that divides
    // the line in the radii's ratio lies within both.
    AxisCandidate best;
    best.normal = between / distance;
    best.overlap = pair.overlap(best.normal);
    const real sides = best.overlap;
    considerCap(pair, a, best);
    considerCap(pair, b, best);
    // A short cylinder whose cap overlaps less: a cap against a side or rim, left to FCL.
    if (best.overlap < sides) return CylinderPairResult::NotHandled;
    if (!(best.overlap >= -reach)) return CylinderPairResult::Apart;
    normal = best.normal;
    return CylinderPairResult::Found;
}

}  // namespace cyclone::detail
