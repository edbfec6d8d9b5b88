// Time of impact between two shapes moving from one pose to another over a step, by
// sampling and bisection with FCL's contact test (collideShapes: fcl::collide without its
// allocations; two boxes by the separating axes, box_box.h; why not
// fcl::continuousCollide: docs/solver.md, "Figures behind constants in the code").
#include "collision/time_of_impact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/box_box.h"
#include "collision/broadphase.h"
#include "collision/shape_contact.h"

namespace cyclone::detail {
namespace {

// Smallest fraction of the motion a time of impact is refined to.
constexpr real kFractionTolerance = 1e-7;
// Most poses the sampled sweep tests (a hull with a tiny inner radius moving far).
constexpr int kMaxSamples = 4096;

// Calls visit(geometry, pose) for the shape, or for each child of a compound.
template <class Visit>
bool anyPart(const SweptShape &shape, const Matrix4 &pose, Visit visit) {
    if (!shape.compound) return visit(shape.geometry, pose);
    const CollisionShape &c = *shape.compound;
    for (std::size_t k = 0; k < c.children().size(); ++k)
        if (visit(c.children()[k].shape->geometry().get(), partPose(c, k, pose))) return true;
    return false;
}

bool overlap(const SweptShape &a, const Matrix4 &poseA, const SweptShape &b, const Matrix4 &poseB) {
    static const fcl::CollisionRequestd request = [] {
        fcl::CollisionRequestd r;
        r.gjk_solver_type = fcl::GST_LIBCCD;
        return r;
    }();
    // Reused so that its contact vector keeps its capacity between calls.
    static thread_local fcl::CollisionResultd result;
    // Parts whose boxes are apart are not tested: two compounds of 300 children near each
    // other had 90,000 exact tests at every sampled pose (docs/hostile_input.md).
    // (A plane's box is unbounded: no culling against it.)
    const fcl::AABBd wholeB = a.compound || b.compound ? placedBox(*b.geometry, poseB) : fcl::AABBd();
    const bool cull = (a.compound || b.compound) && wholeB.min_.allFinite() && wholeB.max_.allFinite();
    return anyPart(a, poseA, [&](const fcl::CollisionGeometryd *ga, const Matrix4 &pa) {
        const fcl::AABBd boxA = cull ? placedBox(*ga, pa) : fcl::AABBd();
        if (cull && !boxA.overlap(wholeB)) return false;
        return anyPart(b, poseB, [&](const fcl::CollisionGeometryd *gb, const Matrix4 &pb) {
            if (cull && !boxA.overlap(placedBox(*gb, pb))) return false;
            // Two boxes by the separating axes (touching counts, as in FCL): FCL's own box
            // test fills vectors of its own on every call.
            if (ga->getNodeType() == fcl::GEOM_BOX && gb->getNodeType() == fcl::GEOM_BOX) {
                Vector3 normal;
                real depth = 0;
                return boxBoxAxis(0.5 * static_cast<const fcl::Boxd *>(ga)->side, pa,
                                  0.5 * static_cast<const fcl::Boxd *>(gb)->side, pb, normal, depth);
            }
            result.clear();
            return collideShapes(ga, pa, gb, pb, request, result) > 0;
        });
    });
}

// A ball about the shape's origin that it holds, m (0 where none is known): a solid's own
// (CollisionShape::innerRadius), a compound's largest child's less that child's offset.
real innerRadius(const CollisionShape &c) {
    if (c.shape().type != ShapeType::Compound) return std::max(c.innerRadius(), real(0));
    real inner = 0;
    for (const CompoundPart &part : c.children())
        inner = std::max(inner, innerRadius(*part.shape) - part.pose.translation().norm());
    return inner;
}

real boundingRadius(const fcl::CollisionGeometryd &geometry) {
    const fcl::AABBd &box = geometry.aabb_local;
    return std::max(box.min_.norm(), box.max_.norm());
}

}  // namespace

SweptShape sweptShape(const CollisionShape &shape) {
    SweptShape swept;
    swept.geometry = shape.geometry().get();
    swept.compound = shape.isCompound() ? &shape : nullptr;
    swept.boundingRadius = boundingRadius(*shape.geometry());
    swept.innerRadius = innerRadius(shape);
    return swept;
}

std::shared_ptr<fcl::CollisionGeometryd> makeCore(const SweptShape &shape) {
    auto core = std::make_shared<fcl::Sphered>(0.25 * std::max(shape.innerRadius, 0.01 * shape.boundingRadius));
    core->computeLocalAABB();
    return core;
}

SweptShape sweptCore(const fcl::CollisionGeometryd &core) {
    SweptShape swept;
    swept.geometry = &core;
    swept.boundingRadius = boundingRadius(core);
    swept.innerRadius = swept.boundingRadius;
    return swept;
}

bool separation(const SweptShape &a, const Matrix4 &poseA, const SweptShape &b, const Matrix4 &poseB,
                real &distance, Vector3 &direction) {
    fcl::DistanceRequestd request(true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::DistanceResultd result;
    bool found = false;
    // The nearest pair of parts (a compound's children); any touching pair means none.
    const bool touching = anyPart(a, poseA, [&](const fcl::CollisionGeometryd *ga, const Matrix4 &pa) {
        return anyPart(b, poseB, [&](const fcl::CollisionGeometryd *gb, const Matrix4 &pb) {
            result.clear();
            if (!(distanceShapes(ga, pa, gb, pb, request, result) > 0)) return true;
            const Vector3 between = result.nearest_points[1] - result.nearest_points[0];
            const real gap = between.norm();
            if (!(gap > 0) || !between.allFinite()) return true;
            if (!found || gap < distance) {
                distance = gap;
                direction = between / gap;
                found = true;
            }
            return false;
        });
    });
    return found && !touching;
}

real travel(const Matrix4 &from, const Matrix4 &to, real radius) {
    const real angle = Eigen::AngleAxis<real>(to.linear() * from.linear().transpose()).angle();
    return (to.translation() - from.translation()).norm() + angle * radius;
}

// A turn by angle t has |R1 - R0|_F = 2 sqrt(2) sin(t / 2), and t <= pi sin(t / 2) on
// [0, pi], so t <= pi |R1 - R0|_F / (2 sqrt(2)): about pi / 2 times t for a small turn.
// The margin keeps the bound's rounding, and travel()'s, from deciding.
bool travelWithin(const Matrix4 &from, const Matrix4 &to, real radius, real limit) {
    constexpr real kTurnPerDistance = 1.1107207345395915;  // pi / (2 sqrt(2))
    constexpr real kMargin = 1e-6;                         // m
    const real turn = kTurnPerDistance * (to.linear() - from.linear()).norm();
    return (to.translation() - from.translation()).norm() + turn * radius < limit - kMargin;
}

Matrix4 interpolate(const Matrix4 &from, const Matrix4 &to, real t) {
    Matrix4 pose = Matrix4::Identity();
    pose.translation() = from.translation() + t * (to.translation() - from.translation());
    pose.linear() = Quaternion(from.linear()).slerp(t, Quaternion(to.linear())).toRotationMatrix();
    return pose;
}

namespace {

// timeOfImpact() with `t` null: stops at the first sample in contact, unrefined.
Impact sweep(const SweptShape &a, const Matrix4 &a0, const Matrix4 &a1, const SweptShape &b, const Matrix4 &b0,
             const Matrix4 &b1, real *t) {
    if (overlap(a, a0, b, b0)) return Impact::Overlapping;
    const real motion = travel(a0, a1, a.boundingRadius) + travel(b0, b1, b.boundingRadius);
    if (!(motion > 0)) return Impact::None;
    const real tolerance = std::max(kFractionTolerance, kSweepTolerance / motion);

    // Consecutive poses of `a` are no further apart than its inner radius, b's motion
    // included, so its centre cannot cross a surface between two of them unseen.
    const real spacing = std::max(a.innerRadius, a.boundingRadius * 1e-3);
    const int samples = std::clamp(static_cast<int>(std::ceil(motion / spacing)), 1, kMaxSamples);
    real free = 0;
    for (int i = 1; i <= samples; ++i) {
        const real s = real(i) / samples;
        if (!overlap(a, interpolate(a0, a1, s), b, interpolate(b0, b1, s))) {
            free = s;
            continue;
        }
        if (!t) return Impact::Hit;
        real hit = s;
        while (hit - free > tolerance) {
            const real mid = 0.5 * (free + hit);
            if (overlap(a, interpolate(a0, a1, mid), b, interpolate(b0, b1, mid))) hit = mid;
            else free = mid;
        }
        *t = free;
        return Impact::Hit;
    }
    return Impact::None;
}

}  // namespace

Impact timeOfImpact(const SweptShape &a, const Matrix4 &a0, const Matrix4 &a1, const SweptShape &b,
                    const Matrix4 &b0, const Matrix4 &b1, real &t) {
    return sweep(a, a0, a1, b, b0, b1, &t);
}

Impact meetDuring(const SweptShape &a, const Matrix4 &a0, const Matrix4 &a1, const SweptShape &b, const Matrix4 &b0,
                  const Matrix4 &b1) {
    return sweep(a, a0, a1, b, b0, b1, nullptr);
}

}  // namespace cyclone::detail
