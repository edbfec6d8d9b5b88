// A scene pays only for what it uses, read from the per-stage counters of StepStats:
// no friction rows without friction, no spring, ccd or restitution work unless a body
// asks for it, and sleeping bodies cost no per-step work.
#include <gtest/gtest.h>

#include "solver/contact_solver.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// Three unit boxes stacked on the ground, the bottom one frictionless: friction is the
// geometric mean of the two materials, so only the top pair has any. Each face contact
// has 4 points: 12 contacts, and the top pair's patch has 3 friction rows (two tangents
// and a twist), not 2 for each of its points.
TEST(PayForUse, FrictionRowsOnlyForPairsWithFriction) {
    WorldFixture f(noSleep());
    f.ground(0.6);
    f.box(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5), 1, 0);
    f.box(Vector3(0, 1.5, 0), Vector3(0.5, 0.5, 0.5), 1, 0.6);
    f.box(Vector3(0, 2.5, 0), Vector3(0.5, 0.5, 0.5), 1, 0.6);
    f.simulate(1);
    EXPECT_EQ(f.world.stats().manifolds, 3);
    EXPECT_EQ(f.world.stats().contacts, 12);
    EXPECT_EQ(f.world.stats().frictionRows, 3);
}

// A sphere touches the ground at one point: its patch has the two tangent rows and no
// twist row (nothing to turn about).
TEST(PayForUse, OnePointContactHasNoTwistRow) {
    WorldFixture f(noSleep());
    f.ground(0.6);
    f.sphere(Vector3(0, 0.5, 0));
    f.simulate(0.1);
    EXPECT_EQ(f.world.stats().contacts, 1);
    EXPECT_EQ(f.world.stats().frictionRows, 2);
}

TEST(PayForUse, FrictionlessStackHasNoFrictionRows) {
    WorldFixture f(noSleep());
    f.ground(0);
    for (int level = 0; level < 3; ++level) f.box(Vector3(0, 0.5 + level, 0), Vector3(0.5, 0.5, 0.5), 1, 0);
    f.simulate(1);
    EXPECT_EQ(f.world.stats().contacts, 12);
    EXPECT_EQ(f.world.stats().frictionRows, 0);
}

// The solve stage's parts (StageTimes::solveParts) show what a solver setting costs: no
// carrier pass time with the carrier pass off, neither carrier nor position time
// without contacts, and the parts never add up to more than the stage.
TEST(PayForUse, SolvePartsAreZeroForWhatDidNotRun) {
    WorldSettings settings = noSleep();
    settings.debug.carrierPass = false;
    WorldFixture f(settings);
    f.ground(0.6);
    for (int level = 0; level < 3; ++level) f.box(Vector3(0, 0.5 + level, 0), Vector3(0.5, 0.5, 0.5));
    f.simulate(1);
    const StageTimes &ms = f.world.stats().ms;
    EXPECT_EQ(ms.solveParts.carrier, 0.0);
    EXPECT_EQ(f.world.stats().carrierSweeps, 0);
    EXPECT_GT(ms.solveParts.velocity, 0.0);
    // Each part is timed within the stage's own intervals; the 1e-9 covers the rounding
    // of summing the same intervals in another order.
    EXPECT_LE(ms.solveParts.setup + ms.solveParts.velocity + ms.solveParts.position, ms.solve * (1 + 1e-9));

    WorldFixture withSupport(noSleep());
    withSupport.ground(0.6);
    for (int level = 0; level < 3; ++level) withSupport.box(Vector3(0, 0.5 + level, 0), Vector3(0.5, 0.5, 0.5));
    withSupport.simulate(1);
    const SolveTimes &parts = withSupport.world.stats().ms.solveParts;
    EXPECT_GT(parts.carrier, 0.0);
    // Three carried bodies (the lowest on the ground), one run each per sub-step, of one
    // to kCarrierSweeps sweeps; the stack at rest takes the resting step's sub-steps.
    const int runs = 3 * withSupport.world.stats().substeps;
    EXPECT_GE(withSupport.world.stats().carrierSweeps, runs);
    EXPECT_LE(withSupport.world.stats().carrierSweeps, runs * detail::kCarrierSweeps);
    EXPECT_LE(parts.setup + parts.velocity + parts.carrier + parts.position,
              withSupport.world.stats().ms.solve * (1 + 1e-9));

    // A body alone in the air: no contacts, so no pass runs at all.
    WorldFixture alone(noSleep());
    alone.sphere(Vector3(0, 5, 0));
    alone.world.step(1.0 / 60);
    EXPECT_EQ(alone.world.stats().ms.solveParts.carrier, 0.0);
    EXPECT_EQ(alone.world.stats().ms.solveParts.position, 0.0);
}

// No spring is evaluated while both its ends sleep; waking one end wakes the other and
// the spring is evaluated once per step.
TEST(PayForUse, SpringsEvaluatedOnlyWithAnAwakeEnd) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    f.simulate(0.1);
    EXPECT_EQ(f.world.stats().springs, 0) << "a world without springs";
    // Two spheres 1 m apart on a spring of rest length 1 m: no force, so they fall asleep.
    const BodyId a = f.sphere(Vector3(0, 0, 0), 0.2);
    const BodyId b = f.sphere(Vector3(1, 0, 0), 0.2);
    SpringSettings spring;
    spring.a = a;
    spring.b = b;
    spring.restLength = 1;
    f.world.addSpring(spring);
    f.simulate(5);
    ASSERT_FALSE(f.awake(a));
    ASSERT_FALSE(f.awake(b));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().springs, 0);
    EXPECT_EQ(f.world.stats().integratedBodies, 0);
    f.world.setAwake(a, true);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().springs, 1);
    EXPECT_TRUE(f.awake(b));
}

// A fast body is swept only when it asks for continuous collision (BodySettings::ccd).
TEST(PayForUse, NoCcdUnlessABodyAsksForIt) {
    for (bool ccd : {false, true}) {
        WorldSettings settings;
        settings.gravity = Vector3::Zero();
        WorldFixture f(settings);
        BodySettings s;
        s.shape = Shape::sphere(0.1);
        s.velocity = Vector3(60, 0, 0);  // 1 m per step, ten times its radius
        s.ccd = ccd;
        f.world.addBody(s);
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().ccdSweeps, ccd ? 1 : 0) << "ccd " << ccd;
    }
}

// A ball hitting the ground at about 6 m/s bounces only with restitution.
TEST(PayForUse, NoRestitutionWorkWithoutRestitution) {
    for (real restitution : {0.0, 0.5}) {
        WorldFixture f(noSleep());
        f.ground();
        BodySettings s;
        s.shape = Shape::sphere(0.5);
        s.position = Vector3(0, 2.5, 0);
        s.material.restitution = restitution;
        f.world.addBody(s);
        int bouncing = 0;
        for (int i = 0; i < 60; ++i) {
            f.world.step(kDt);
            bouncing += f.world.stats().restitutionContacts;
        }
        if (restitution > 0) {
            EXPECT_GT(bouncing, 0);
        } else {
            EXPECT_EQ(bouncing, 0);
        }
    }
}

// 100 sleeping boxes and one awake sphere resting on the ground far from them: the step
// integrates, pairs and tests the sphere alone (its one pair is with the ground).
// Without sensors there is no sensor stage (its time stays exactly 0, it is not even
// timed), and a sensor whose box meets nothing tests nothing: a ball falling beside a
// trigger box is never a sensor pair.
TEST(PayForUse, SensorsCostNothingUntilSomethingReachesThem) {
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    const BodyId ball = f.sphere(Vector3(5, 3, 0), 0.25);
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().ms.sensors, 0);
        EXPECT_EQ(f.world.stats().sensorPairs, 0);
        EXPECT_EQ(f.world.stats().filteredPairs, 0);
    }
    BodySettings zone;
    zone.motion = Motion::Static;
    zone.sensor = true;
    zone.shape = Shape::box(Vector3(1, 1, 1));
    zone.position = Vector3(0, 5, 0);  // above the box, 4 m from the ball's path
    f.world.addBody(zone);
    // Once, when it is added, the sensor is tested against what its box meets, and against
    // the ground plane, which has no box: one test, no overlap.
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().sensorPairs, 1);
    EXPECT_TRUE(f.world.events().sensorBegins.empty());
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().sensorPairs, 0) << i;
        EXPECT_TRUE(f.world.events().sensorBegins.empty());
    }
    EXPECT_LT(f.position(ball).y(), 3);
}

TEST(PayForUse, SleepingBodiesCostNoStepWork) {
    WorldFixture f;
    f.ground();
    for (int stack = 0; stack < 10; ++stack) {
        for (int level = 0; level < 10; ++level) {
            BodySettings box;
            box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            box.position = Vector3(stack * 2.0, 0.5 + level, 0);
            box.awake = false;
            f.world.addBody(box);
        }
    }
    BodySettings ball;
    ball.shape = Shape::sphere(0.5);
    ball.position = Vector3(-20, 0.5, 0);
    ball.canSleep = false;
    f.world.addBody(ball);
    f.simulate(0.5);
    const StepStats &stats = f.world.stats();
    EXPECT_EQ(stats.bodies, 102);
    EXPECT_EQ(stats.awakeBodies, 1);
    EXPECT_EQ(stats.integratedBodies, 1);
    EXPECT_EQ(stats.broadphasePairs, 1);
    EXPECT_EQ(stats.pairsTested + stats.pairsReused, 1);
    EXPECT_EQ(stats.islands, 1);
    EXPECT_TRUE(f.world.events().fellAsleep.empty());
}

// A step in which no broadphase box moved gives the last walk's pairs again: those must
// still follow every change. Unit boxes, no gravity: 1.01 m apart their fat boxes (2 cm
// margin, +-0.52 m) overlap, 5 m apart they do not. The static box is in a tree of its
// own; moved below the first box, 0.2 m aside, its fat box stops at x = 0.32, short of
// the second box's at 0.49.
TEST(PayForUse, BroadphasePairsFollowMovedBodies) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    f.box(Vector3(0, 0, 0));
    const BodyId b = f.box(Vector3(5, 0, 0));
    const BodyId wall = f.staticBox(Vector3(0, -5, 0), Vector3(0.5, 0.5, 0.5));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 0);
    f.world.setPosition(b, Vector3(1.01, 0, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 1);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 1) << "nothing moved";
    f.world.setPosition(wall, Vector3(-0.2, -1.01, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 2);
    f.world.setPosition(b, Vector3(5, 0, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 1);
    f.world.removeBody(wall);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 0);
}

// The pre-solve stage runs only with a contact listener or a body with a one-way
// direction or a surface velocity: a resting stack of three boxes (3 manifolds) costs
// nothing there without them, and shows each manifold to the stage with a listener.
TEST(PayForUse, PreSolveOnlyWithAListenerOrRules) {
    struct Quiet final : ContactListener {
        void preSolve(PreSolveContact &) override {}
    } quiet;
    for (const bool listening : {false, true}) {
        WorldFixture f(noSleep());
        f.ground();
        for (int level = 0; level < 3; ++level) f.box(Vector3(0, 0.5 + level, 0));
        if (listening) f.world.setContactListener(&quiet);
        f.simulate(0.5);
        EXPECT_EQ(f.world.stats().manifolds, 3);
        EXPECT_EQ(f.world.stats().preSolvedManifolds, listening ? 3 : 0);
    }
}

}  // namespace
}  // namespace cyclone::test
