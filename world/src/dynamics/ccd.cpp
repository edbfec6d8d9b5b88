// Continuous collision for bodies with BodySettings::ccd, after the sub-steps.
//
// Design note. A ccd body that moved further in the step than its inner radius may have
// passed through something the step's discrete contacts never saw. Its motion (from the
// pose its collision object still holds, the step's start, to its pose now) is swept
// against every body whose box overlaps the swept box, each of those moving from its own
// start to end pose, and against the planes. At the earliest time of impact the body is
// put back to where it first touches, a slop deep (the narrowphase reports touching
// shapes only, so the next step's contact must overlap); its velocity is kept, so the
// next step's contact stops or bounces it (the rest of the step's motion is lost, as in
// Bullet's motion clamping).
//
// A pair already in contact at the step's start is the solver's, but one contact point
// does not stop a fast tumbling body: it pivots about the point and carries the rest of
// itself through within the step. For such pairs the body's core, a small sphere at its
// centre, is swept instead (Box2D v3's fallback), and the body stops where the core
// touches: deep, but on the near side, and with its centre's speed towards the obstacle
// taken away, or the sweep would hold it there step after step. Bodies without ccd cost
// nothing. What the layers, a pair rule or a sensor keep from touching is not swept against.
#include "dynamics/ccd.h"

#include <algorithm>

#include "collision/time_of_impact.h"
#include "collision/broadphase.h"
#include "contacts/pair_cache.h"
#include "world/body_store.h"
#include "world/step_context.h"

namespace cyclone::detail {

void ContinuousCollision::sweep(const StepContext &context, BodyStore &bodies, Broadphase &broadphase,
                                const PairCache &pairs, StepStats &stats) {
    const WorldSettings &settings = context.settings;
    const std::uint64_t stepCount = context.stepCount;
    // How deep a stopped body is left in what it hits: the slop, which the solver leaves
    // alone, and at least 0.1 mm.
    const real depth = std::max(settings.penetrationSlop, real(0.0001));
    for (std::uint32_t index : bodies.simulated) {
        BodyRecord &r = bodies[index];
        if (!r.core || r.isolated || !r.object) continue;
        const Matrix4 start = r.object->getTransform();
        const Matrix4 end = r.body.getTransform();
        const SweptShape self = sweptShape(*r.shape);
        const real travel = detail::travel(start, end, self.boundingRadius);
        if (!(travel > self.innerRadius)) continue;
        ++stats.ccdSweeps;
        const Stop at = earliestStop(bodies, broadphase, pairs, stepCount, index, start, end, travel, depth);
        if (!(at.fraction < 1)) continue;
        stopAt(bodies, index, start, end, at);
        ++stats.ccdHits;
    }
}

// The earliest fraction of body `index`'s motion from `start` to `end` at which it must
// stop, against the bodies its swept box meets and the planes, and the body whose core
// stopped it (-1: none).
ContinuousCollision::Stop ContinuousCollision::earliestStop(const BodyStore &bodies, Broadphase &broadphase,
                                                            const PairCache &pairs, std::uint64_t stepCount,
                                                            std::uint32_t index, const Matrix4 &start,
                                                            const Matrix4 &end, real travel, real depth) {
    const BodyRecord &r = bodies[index];
    const SweptShape self = sweptShape(*r.shape);
    real stop = 1;
    long coreStop = -1;
    const auto touching = [&](std::uint32_t other) {
        const long p = pairs.find(index, other);
        return p >= 0 && pairs[p].lastSeen == stepCount && pairs[p].touching();
    };
    const SweptShape core = sweptCore(*r.core);

    fcl::AABBd swept(start.translation(), end.translation());
    swept.expand(fcl::Vector3d::Constant(self.boundingRadius + kBroadphaseMargin));
    candidates_.clear();
    broadphase.overlapping(swept, candidates_);
    const bool filtering = bodies.filtering();
    for (std::uint32_t other : candidates_) {
        if (other == index || (filtering && bodies.classify(index, other) != PairKind::Contact)) continue;
        const BodyRecord &o = bodies[other];
        // FCL's sweep would meet a height field's box, not its surface: left to the
        // contacts' reach (docs/level_features.md, "Heightfields").
        if (o.shape->shape().type == ShapeType::Heightfield) continue;
        const SweptShape target = sweptShape(*o.shape);
        const Matrix4 &otherStart = o.object->getTransform();
        const Matrix4 otherEnd = o.body.getTransform();
        real t;
        if (!touching(other)) {
            const Impact impact = timeOfImpact(self, start, end, target, otherStart, otherEnd, t);
            if (impact == Impact::Hit) stop = std::min(stop, t + (kSweepTolerance + depth) / travel);
            if (impact != Impact::Overlapping) continue;
        }
        if (timeOfImpact(core, start, end, target, otherStart, otherEnd, t) == Impact::Hit &&
            t < stop) {
            stop = t;
            coreStop = other;
        }
    }

    // Planes: the time at which the shape's lowest point along the normal is `depth`
    // below the surface, with the pose interpolated (exact for a translating body). A
    // half-space has no far side to tunnel to: a touching plane is the solver's.
    for (std::uint32_t plane : bodies.planes) {
        if (touching(plane) || (filtering && bodies.classify(index, plane) != PairKind::Contact)) continue;
        const CollisionShape &p = *bodies[plane].shape;
        const Vector3 &n = p.planeNormal();
        const real above0 = n.dot(r.shape->supportPoint(start, -n, 0)) - p.planeOffset();
        const real above1 = n.dot(r.shape->supportPoint(end, -n, 0)) - p.planeOffset();
        const real t = (above0 + depth) / (above0 - above1);
        if (above0 > 0 && above1 < -depth && t < stop) {
            stop = t;
            coreStop = -1;
        }
    }
    return {stop, coreStop};
}

// Puts body `index` where its motion stops. A core stop: the solver let this body's centre
// head into what it already touched (a spinning body whose contact point moves away while
// its centre does not). Its core is put half its radius from the obstacle, so that the
// next sweep starts apart, and its centre's speed towards the obstacle is taken away,
// which only removes energy: were it kept, the sweep would hold the body here step after
// step.
void ContinuousCollision::stopAt(BodyStore &bodies, std::uint32_t index, const Matrix4 &start, const Matrix4 &end,
                                 const Stop &at) {
    BodyRecord &r = bodies[index];
    const SweptShape core = sweptCore(*r.core);
    Matrix4 pose = interpolate(start, end, at.fraction);
    real gap;
    Vector3 n;
    if (at.core >= 0 &&
        separation(core, pose, sweptShape(*bodies[at.core].shape),
                           bodies[at.core].body.getTransform(), gap, n)) {
        pose.translation() -= std::max(real(0), 0.5 * core.boundingRadius - gap) * n;
        const real approach = r.body.getVelocity().dot(n);
        if (approach > 0) r.body.setVelocity(r.body.getVelocity() - approach * n);
    }
    r.body.setPosition(pose.translation());
    r.body.setOrientation(Quaternion(pose.linear()));
}

}  // namespace cyclone::detail
