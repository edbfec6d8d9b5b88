// The shipped ragdoll falling down the stairs (examples/scenes/ragdoll-stairs.json), run
// step by step through the scene loader and the World: its joints hold, its limited
// hinges stay within their limits, no limb sinks into a stair, and it comes to rest on
// the stairs, below where it started, and sleeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runner_test_support.h"
#include "scene_loader.h"
#include "scene_world.h"

namespace {

using namespace runner_test;
using namespace cyclone;
using namespace cyclone::scene;

// Distance from point p to the axis-aligned box centred at c with half extents e (0 inside).
real pointBoxDistance(const Vector3 &p, const Vector3 &c, const Vector3 &e) {
    const Vector3 outside = ((p - c).cwiseAbs() - e).cwiseMax(0);
    return outside.norm();
}

// Distance from the segment [p, q] to that box. Along a line the distance to a convex set
// is a convex function of the parameter, so a golden-section search finds its minimum.
real segmentBoxDistance(const Vector3 &p, const Vector3 &q, const Vector3 &c, const Vector3 &e) {
    const auto at = [&](real t) { return pointBoxDistance(p + t * (q - p), c, e); };
    const real g = (std::sqrt(real(5)) - 1) / 2;
    real lo = 0, hi = 1;
    for (int i = 0; i < 80; ++i) {
        const real x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        if (at(x1) <= at(x2)) hi = x2;
        else lo = x1;
    }
    return std::min({at(0), at(1), at((lo + hi) / 2)});
}

struct Capsule {
    BodyId id;
    real radius = 0;
    real halfLength = 0;  // of the cylindrical part, along the body's z
    // The end points of its axis segment now.
    void ends(const World &world, Vector3 *p, Vector3 *q) const {
        const RigidBody &body = world.body(id);
        const Vector3 axis = body.getDirectionInWorldSpace(Vector3::UnitZ()) * halfLength;
        *p = body.getPosition() - axis;
        *q = body.getPosition() + axis;
    }
};

struct StairBox {
    Vector3 centre, half;
};

// The scene's hinges with limits, with their limits.
struct LimitedHinge {
    std::size_t joint = 0;
    JointLimits limits;
};

TEST(RagdollStairs, HoldsTogetherStaysOutOfTheStairsAndComesToRestOnThem) {
    const Scene scene = loadScene(readText(scenePath("ragdoll-stairs")), "ragdoll-stairs");
    SceneWorld built = buildWorld(scene);
    World &world = built.world;

    std::vector<Capsule> capsules;
    std::vector<StairBox> stairs;
    real mass = 0;
    Vector3 startCentre = Vector3::Zero();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodySettings &s = scene.bodies[i].settings;
        if (s.motion == Motion::Static && s.shape.type == ShapeType::Box) stairs.push_back({s.position, s.shape.halfExtents});
        if (s.motion == Motion::Static) continue;
        ASSERT_EQ(s.shape.type, ShapeType::Capsule) << s.name;
        capsules.push_back({built.ids[i], s.shape.radius, s.shape.length / 2});
        mass += s.mass;
        startCentre += s.mass * s.position;
    }
    startCentre /= mass;
    ASSERT_EQ(capsules.size(), 11u);  // head, torso, pelvis, two upper and lower arms and legs
    ASSERT_GE(stairs.size(), 5u);
    std::vector<LimitedHinge> hinges;
    int balls = 0;
    for (std::size_t j = 0; j < scene.joints.size(); ++j) {
        const JointSettings &s = scene.joints[j].settings;
        if (s.type == JointType::Hinge && s.limits) hinges.push_back({j, *s.limits});
        if (s.type == JointType::Ball) ++balls;
    }
    ASSERT_EQ(hinges.size(), 6u);  // elbows, knees, waist, neck
    ASSERT_EQ(balls, 4);           // shoulders, hips

    // Stairs: how far a capsule is inside one (its radius less the distance from its
    // axis to the box), the deepest over the run.
    const auto deepestInStairs = [&](real *nearest) {
        real deepest = -1;
        *nearest = 1e9;
        for (const Capsule &c : capsules) {
            Vector3 p, q;
            c.ends(world, &p, &q);
            for (const StairBox &b : stairs) {
                const real gap = segmentBoxDistance(p, q, b.centre, b.half) - c.radius;
                deepest = std::max(deepest, -gap);
                *nearest = std::min(*nearest, gap);
            }
            deepest = std::max(deepest, c.radius - std::min(p.y(), q.y()));  // the floor, y = 0
        }
        return deepest;
    };

    const std::int64_t steps = scene.steps;
    real largestGap = 0, deepest = 0, largestOvershoot = 0;
    std::int64_t asleepAt = -1;
    for (std::int64_t step = 0; step < steps; ++step) {
        world.step(scene.dt);
        for (const JointId &j : built.joints) largestGap = std::max(largestGap, world.jointState(j).error);
        for (const LimitedHinge &h : hinges) {
            const real angle = world.jointState(built.joints[h.joint]).position;
            largestOvershoot = std::max({largestOvershoot, h.limits.lower - angle, angle - h.limits.upper});
        }
        real nearest;
        deepest = std::max(deepest, deepestInStairs(&nearest));
        bool awake = false;
        for (const Capsule &c : capsules) awake = awake || world.body(c.id).getAwake();
        if (!awake && asleepAt < 0) asleepAt = step;
        if (awake) asleepAt = -1;  // asleep for good: from this step to the end
    }
    real nearest;
    deepestInStairs(&nearest);
    Vector3 endCentre = Vector3::Zero();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        if (scene.bodies[i].settings.motion != Motion::Static)
            endCentre += scene.bodies[i].settings.mass * world.body(built.ids[i]).getPosition();
    }
    endCentre /= mass;
    std::printf("ragdoll: largest joint gap %.3g m, largest hinge overshoot %.4f rad, deepest in a stair %.4f m, "
                "asleep after step %lld, centre of mass from (%.2f, %.2f) to (%.2f, %.2f) m, nearest stair %.4f m\n",
                largestGap, largestOvershoot, deepest, static_cast<long long>(asleepAt), startCentre.x(),
                startCentre.y(), endCentre.x(), endCentre.y(), nearest);

    // The joints: the position projection leaves every row within 1e-9 m after each
    // sub-step (kProjectionTolerance), so a gap, up to sqrt(3) rows of it, is ~2e-9 m;
    // 1 um leaves room for the contacts' last word and is 2000 times below the issue's
    // 2 mm for a chain.
    EXPECT_LT(largestGap, 1e-6);
    // The limits: no more past them than the issue allows a door swung into its limit.
    EXPECT_LT(largestOvershoot, 0.02);
    // The stairs: no limb deeper in a stair, at the end of any step, than the landing
    // correction's tolerance for these pairs, 5 mm (a forearm's tenth of its bounding
    // radius, 16 mm, is more), plus 1 mm: the correction pushes the ragdoll out whole
    // (its bodies move as one joint group). Resting contacts keep 0.2 mm
    // (penetrationSlop); the deepest moment is a limb turning at about 17 rad/s whose first
    // contact with a stair's edge comes a step late, which without the correction's push
    // went up to 22 mm deep (docs/contacts_and_sleep.md, "The ragdoll's deepest contact").
    EXPECT_LT(deepest, 0.006);
    // At rest on the stairs: touching one (within the 2 cm the contacts keep, their
    // speculative distance), its centre of mass over the flight (x in [0.5, 3.3] m) and
    // more than two steps (0.5 m) below where it started.
    EXPECT_LT(nearest, 0.02);
    EXPECT_GT(endCentre.x(), 0.5);
    EXPECT_LT(endCentre.x(), 3.3);
    EXPECT_LT(endCentre.y(), startCentre.y() - 0.5);
    // Asleep within the scene's 15 s, and for good.
    EXPECT_GE(asleepAt, 0);
    EXPECT_LT(asleepAt, steps - 1);
}

// The same ragdoll with its eleven capsules thrown apart: each at 60 m/s in a direction of
// its own (eight fixed patterns), against joints that hold them together. The joints must
// take the limbs' momentum without blowing up: every body finite after every one of 300
// steps, and no joint open by more than 1 um (as above). Before the joint passes solved
// the equality rows first and let each limit's impulse reach the others through them,
// seven of these eight ragdolls were no longer finite after their first or second step
// (docs/joints.md, "Limits and pulls see held velocities").
TEST(RagdollStairs, ThrownApartItStaysFiniteAndItsJointsHold) {
    const std::string text = readText(scenePath("ragdoll-stairs"));
    for (int pattern = 0; pattern < 8; ++pattern) {
        Scene scene = loadScene(text, "ragdoll-stairs");
        int limb = 0;
        for (SceneBody &b : scene.bodies) {
            if (b.settings.motion == Motion::Static) continue;
            for (int c = 0; c < 3; ++c) b.settings.velocity[c] = 60 * std::sin(1.7 * limb + 2.3 * c + 0.9 * pattern);
            ++limb;
        }
        SceneWorld built = buildWorld(scene);
        World &world = built.world;
        real largestGap = 0;
        for (int step = 0; step < 300; ++step) {
            world.step(scene.dt);
            for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
                const RigidBody &body = world.body(built.ids[i]);
                ASSERT_TRUE(body.getPosition().allFinite() && body.getVelocity().allFinite())
                    << "pattern " << pattern << ", " << scene.bodies[i].settings.name << " after step " << step + 1;
            }
            for (const JointId &j : built.joints) largestGap = std::max(largestGap, world.jointState(j).error);
        }
        EXPECT_LT(largestGap, 1e-6) << "pattern " << pattern;
    }
}

}  // namespace
