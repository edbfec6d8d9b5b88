// Continuous collision for bodies with BodySettings::ccd, after the sub-steps.
//
// Design note. A ccd body that moved further in the step than its inner radius may have
// passed through something the step's discrete contacts never saw. Its motion (from the
// pose its collision object still holds, the step's start, to its pose now) is swept
// against every body whose box overlaps the swept box, each of those moving from its own
// start to end pose, and against the planes. At the earliest time of impact the body is
// put back to where it first touches; its velocity is kept, so the next step's contact
// stops or bounces it (the rest of the step's motion is lost, as in Bullet's motion
// clamping). Pairs already in contact at the step's start are left to the solver, whose
// speculative contacts cannot be passed through. Bodies without ccd cost nothing here.
//
// fcl::continuousCollide with conservative advancement finds the time for boxes,
// spheres, capsules, cylinders and meshes. For convex hulls the sweep samples poses
// (sweepMethod): tests/world/ccd_test.cpp checks every pair of shapes either way.
#include "ccd.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "world_impl.h"

namespace cyclone {
namespace detail {
namespace {

// Gap to which a time of impact is refined, m; below the speculative distance, so that
// the next step's narrowphase reports the contact.
constexpr real kContactTolerance = 0.001;
// Smallest fraction of the motion a time of impact is refined to.
constexpr real kFractionTolerance = 1e-4;
// Most poses the sampled sweep tests (a hull with a tiny inner radius moving far).
constexpr int kMaxSamples = 4096;

real rotationAngle(const Matrix4 &from, const Matrix4 &to) {
    return Eigen::AngleAxis<real>(to.linear() * from.linear().transpose()).angle();
}

// How far any point of a shape of bounding radius `radius` moves, m.
real travel(const Matrix4 &from, const Matrix4 &to, real radius) {
    return (to.translation() - from.translation()).norm() + rotationAngle(from, to) * radius;
}

bool touching(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB) {
    fcl::CollisionRequestd request;
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::CollisionResultd result;
    return fcl::collide(a.geometry().get(), poseA, b.geometry().get(), poseB, request, result) > 0;
}

real boundingRadius(const CollisionShape &shape) {
    const fcl::AABBd &box = shape.geometry()->aabb_local;
    return std::max(box.min_.norm(), box.max_.norm());
}

}  // namespace

real innerRadius(const CollisionShape &c) {
    const Shape &shape = c.shape();
    switch (shape.type) {
        case ShapeType::Box: return shape.halfExtents.minCoeff();
        case ShapeType::Sphere:
        case ShapeType::Capsule: return shape.radius;
        case ShapeType::Cylinder: return std::min(shape.radius, shape.length / 2);
        case ShapeType::Convex: {
            real inner = std::numeric_limits<real>::infinity();
            for (std::size_t f = 0; f < c.faces().size(); ++f)
                inner = std::min(inner, c.faceNormals()[f].dot(c.vertices()[c.faces()[f][0]]));
            return std::max(inner, real(0));
        }
        case ShapeType::Plane:
        case ShapeType::Mesh: break;
    }
    return 0;
}

SweepMethod sweepMethod(const CollisionShape &a, const CollisionShape &b) {
    if (a.shape().type == ShapeType::Convex || b.shape().type == ShapeType::Convex) return SweepMethod::Sampled;
    return SweepMethod::ConservativeAdvancement;
}

Matrix4 interpolate(const Matrix4 &from, const Matrix4 &to, real t) {
    Matrix4 pose = Matrix4::Identity();
    pose.translation() = from.translation() + t * (to.translation() - from.translation());
    pose.linear() = Quaternion(from.linear()).slerp(t, Quaternion(to.linear())).toRotationMatrix();
    return pose;
}

bool timeOfImpact(const CollisionShape &a, const Matrix4 &a0, const Matrix4 &a1, real aInnerRadius,
                  const CollisionShape &b, const Matrix4 &b0, const Matrix4 &b1, real &t, Matrix4 &poseA) {
    const real motion = travel(a0, a1, boundingRadius(a)) + travel(b0, b1, boundingRadius(b));
    if (!(motion > 0)) return false;
    const real tolerance = std::max(kFractionTolerance, kContactTolerance / motion);

    if (sweepMethod(a, b) == SweepMethod::ConservativeAdvancement) {
        fcl::ContinuousCollisionRequestd request(1000, tolerance, fcl::CCDM_LINEAR, fcl::GST_LIBCCD,
                                                 fcl::CCDC_CONSERVATIVE_ADVANCEMENT);
        fcl::ContinuousCollisionResultd result;
        fcl::continuousCollide(a.geometry().get(), a0, a1, b.geometry().get(), b0, b1, request, result);
        if (!result.is_collide || !(result.time_of_contact > 0) || !(result.time_of_contact < 1)) return false;
        t = result.time_of_contact;
        poseA = result.contact_tf1;
        return true;
    }

    // Sampled: consecutive poses of `a` overlap (no sample is further than its inner
    // radius from the last, b's motion included), so nothing thicker than zero lies
    // between two samples unseen.
    if (touching(a, a0, b, b0)) return false;
    const real spacing = std::max(aInnerRadius, boundingRadius(a) * 1e-3);
    const int samples = std::clamp(static_cast<int>(std::ceil(motion / spacing)), 1, kMaxSamples);
    real free = 0;
    for (int i = 1; i <= samples; ++i) {
        const real s = real(i) / samples;
        if (!touching(a, interpolate(a0, a1, s), b, interpolate(b0, b1, s))) {
            free = s;
            continue;
        }
        real hit = s;
        while (hit - free > tolerance) {
            const real mid = 0.5 * (free + hit);
            if (touching(a, interpolate(a0, a1, mid), b, interpolate(b0, b1, mid))) hit = mid;
            else free = mid;
        }
        if (!(free > 0)) return false;
        t = free;
        poseA = interpolate(a0, a1, free);
        return true;
    }
    return false;
}

}  // namespace detail

void World::Impl::sweepContinuous() {
    for (std::uint32_t index : simulatedBodies) {
        BodyRecord &r = bodies[index];
        if (!r.ccd || r.quarantined || !r.object) continue;
        const Matrix4 start = r.object->getTransform();
        const Matrix4 end = r.body.getTransform();
        const real radius = r.boundingRadius;
        if (!(detail::travel(start, end, radius) > r.innerRadius)) continue;
        ++stats.ccdSweeps;

        real earliest = 1;
        Matrix4 stop = end;
        const auto alreadyTouching = [&](std::uint32_t other) {
            const long p = pairs.find(index, other);
            return p >= 0 && pairs[p].lastSeen == stepCount && pairs[p].touching();
        };

        fcl::AABBd swept(start.translation(), end.translation());
        swept.expand(fcl::Vector3d::Constant(radius + detail::kBroadphaseMargin));
        sweepCandidates.clear();
        broadphase.overlapping(swept, sweepCandidates);
        for (std::uint32_t other : sweepCandidates) {
            if (other == index || alreadyTouching(other)) continue;
            const BodyRecord &o = bodies[other];
            real t;
            Matrix4 pose;
            if (detail::timeOfImpact(*r.shape, start, end, r.innerRadius, *o.shape, o.object->getTransform(),
                                     o.body.getTransform(), t, pose) &&
                t < earliest) {
                earliest = t;
                stop = pose;
            }
        }

        // Planes: the time at which the shape's lowest point along the normal reaches the
        // surface, with the pose interpolated (exact for a translating sphere).
        for (std::uint32_t plane : planes) {
            if (alreadyTouching(plane)) continue;
            const detail::CollisionShape &p = *bodies[plane].shape;
            const Vector3 &n = p.planeNormal();
            const real above0 = n.dot(r.shape->supportPoint(start, -n, 0)) - p.planeOffset();
            const real above1 = n.dot(r.shape->supportPoint(end, -n, 0)) - p.planeOffset();
            if (!(above0 > 0 && above1 < 0)) continue;
            const real t = above0 / (above0 - above1);
            if (t < earliest) {
                earliest = t;
                stop = detail::interpolate(start, end, t);
            }
        }

        if (earliest < 1) {
            r.body.setPosition(stop.translation());
            r.body.setOrientation(Quaternion(stop.linear()));
            ++stats.ccdHits;
        }
    }
}

}  // namespace cyclone
