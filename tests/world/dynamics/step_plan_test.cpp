// Resting steps (DebugSettings::restingSubsteps, dynamics/step_plan.h): a step in which
// every awake body touches something, on contacts solved last step of which at least one
// carried a normal impulse, and moves less than 1 mm takes restingSubsteps sub-steps with
// restingIterations velocity passes in all (at most a full step's); any other step takes
// `substeps`.
#include <vector>

#include <gtest/gtest.h>

#include "../world_fixture.h"

namespace cyclone::test {
namespace {

// The defaults: 4 sub-steps of 3 velocity passes, 3 * 4 = 12 passes in a full step; 1
// sub-step of 8 passes when resting.
constexpr int kPassesPerStep = 12;
constexpr int kRestingPasses = 8;

TEST(RestingStep, ABoxAtRestOnTheGroundTakesOneSubstepOfTheRestingPasses) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));  // touching the plane from the first step
    // Its contact has no warm start in the first step: every sub-step.
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 4);
    for (int i = 1; i < 60; ++i) {
        f.world.step(kDt);
        ASSERT_EQ(f.world.stats().substeps, 1) << "step " << i;
        ASSERT_EQ(f.world.stats().velocityIterations, kRestingPasses) << "step " << i;
    }
    // At rest it stays: within 0.1 mm of where it was put (the slop is 0.2 mm).
    EXPECT_NEAR(f.position(box).y(), 0.5, 1e-4);
    EXPECT_NEAR(f.position(box).x(), 0, 1e-6);
}

TEST(RestingStep, ASideContactThatCarriesNothingStillRests) {
    // Two boxes side by side on the ground, their faces touching at x = 0.5: with gravity
    // alone nothing pushes one box into the other, so the side contact needs no impulse
    // (its relative normal velocity stays 0 and its depth within the slop). Each box rests
    // on the ground's warm contact; the unloaded side contact, solved every step, must not
    // keep the step on 4 sub-steps (as a pyramid's unloaded supports did).
    WorldFixture f(noSleep());
    f.ground();
    const BodyId a = f.box(Vector3(0, 0.5, 0));
    const BodyId b = f.box(Vector3(1, 0.5, 0));
    f.world.step(kDt);  // new contacts: every sub-step
    EXPECT_EQ(f.world.stats().substeps, 4);
    for (int i = 1; i < 60; ++i) {
        f.world.step(kDt);
        ASSERT_EQ(f.world.stats().substeps, 1) << "step " << i;
    }
    // Within 0.1 mm of where they were put (the slop is 0.2 mm).
    EXPECT_NEAR(f.position(a).y(), 0.5, 1e-4);
    EXPECT_NEAR(f.position(b).y(), 0.5, 1e-4);
    EXPECT_NEAR(f.position(b).x() - f.position(a).x(), 1, 1e-4);
}

TEST(RestingStep, ANewContactTakesEverySubstepOnce) {
    // A static wall put against the side of a resting box: the box still rests on the
    // ground's warm contact, but its contact with the wall was not solved last step, so the
    // step takes every sub-step; the next step, every contact solved, it rests again.
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    f.simulate(3 * kDt);
    ASSERT_EQ(f.world.stats().substeps, 1);
    f.staticBox(Vector3(1, 0.5, 0), Vector3(0.5, 0.5, 0.5));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 4);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 1);
}

TEST(RestingStep, AFallingBodyTakesEverySubstep) {
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 3, 0));  // at rest but touching nothing: it falls
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 4);
    // 0.5 s later it falls at g t = 4.9 m/s: 8 cm a step.
    f.simulate(0.5);
    EXPECT_EQ(f.world.stats().substeps, 4);
}

TEST(RestingStep, ABodySlidingFasterThanAMillimetreAStepTakesEverySubstep) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(2 * kDt);
    ASSERT_EQ(f.world.stats().substeps, 1);
    // 0.1 m/s over 1/60 s is 1.7 mm: more than the 1 mm a resting body may move.
    f.world.setVelocity(box, Vector3(0.1, 0, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 4);
    EXPECT_EQ(f.world.stats().velocityIterations, kPassesPerStep);
    // 0.03 m/s is 0.5 mm a step: resting again.
    f.world.setVelocity(box, Vector3(0.03, 0, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 1);
    EXPECT_EQ(f.world.stats().velocityIterations, kRestingPasses);
}

TEST(RestingStep, OneMovingBodyAnywhereKeepsEverySubstep) {
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    f.box(Vector3(10, 0.5, 0));
    f.simulate(2 * kDt);
    ASSERT_EQ(f.world.stats().substeps, 1);
    f.sphere(Vector3(-10, 5, 0));  // falls, far from both boxes
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 4);
}

TEST(RestingStep, ZeroOrAllSubstepsTurnsItOff) {
    for (const int resting : {0, 4}) {
        WorldSettings s = noSleep();
        s.debug.restingSubsteps = resting;
        WorldFixture f(s);
        f.ground();
        f.box(Vector3(0, 0.5, 0));
        f.simulate(3 * kDt);
        EXPECT_EQ(f.world.stats().substeps, 4) << "restingSubsteps " << resting;
    }
}

// A box put on the ground and stepped twice: the second step rests (its contact is warm).
void restABox(WorldFixture &f) {
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    f.simulate(2 * kDt);
}

TEST(RestingStep, TwoRestingSubstepsShareThePassesRoundedUp) {
    // The default 8 passes over 2 sub-steps: 4 each. 7 passes: 4 each too, 8 in all.
    for (const int passes : {kRestingPasses, 7}) {
        WorldSettings s = noSleep();
        s.debug.restingSubsteps = 2;
        s.debug.restingIterations = passes;
        WorldFixture f(s);
        restABox(f);
        EXPECT_EQ(f.world.stats().substeps, 2) << "restingIterations " << passes;
        EXPECT_EQ(f.world.stats().velocityIterations, 8) << "restingIterations " << passes;
    }
}

TEST(RestingStep, NeverTakesMorePassesThanAFullStep) {
    WorldSettings s = noSleep();
    s.debug.restingIterations = 50;
    WorldFixture f(s);
    restABox(f);
    EXPECT_EQ(f.world.stats().substeps, 1);
    EXPECT_EQ(f.world.stats().velocityIterations, kPassesPerStep);
    // With more passes per sub-step, the resting step takes the 50 asked for.
    s.velocityIterations = 20;
    f.world.setSettings(s);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().substeps, 1);
    EXPECT_EQ(f.world.stats().velocityIterations, 50);
}

TEST(RestingStep, JointsKeepEverySubstep) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId a = f.box(Vector3(0, 0.5, 0));
    const BodyId b = f.box(Vector3(1.05, 0.5, 0));
    f.joint(JointType::Ball, a, b, Vector3(0.525, 0.5, 0));
    f.simulate(3 * kDt);
    EXPECT_EQ(f.world.stats().substeps, 4);
}

TEST(RestingStep, LongStepsKeepEverySubstep) {
    // One sub-step of 1/20 s lets gravity move a body |g| h^2 = 9.81 / 400 = 24.5 mm, more
    // than the 20 mm speculative distance: the step keeps its 4 sub-steps. At 1/30 s,
    // 10.9 mm: resting.
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    f.world.step(1.0 / 30);  // cold contact: every sub-step
    f.world.step(1.0 / 30);
    EXPECT_EQ(f.world.stats().substeps, 1);
    f.world.step(1.0 / 20);
    EXPECT_EQ(f.world.stats().substeps, 4);
}

// A pyramid of boxes 1.05 m apart, each on two boxes below (the benchmark's), base 16:
// 136 boxes and some 270 manifolds, enough for the solver to split its passes in two
// halves on two threads (threads/partition.h).
std::vector<BodyId> restingPyramid(World &world) {
    std::vector<BodyId> ids;
    BodySettings floor;
    floor.motion = Motion::Static;
    floor.shape = Shape::plane(Vector3::UnitY(), 0);
    ids.push_back(world.addBody(floor));
    constexpr int kBase = 16;
    for (int row = 0; row < kBase; ++row) {
        for (int i = 0; i < kBase - row; ++i) {
            BodySettings box;
            box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            box.position = Vector3(1.05 * (i - 0.5 * (kBase - 1 - row)), 0.5 + row, 0);
            ids.push_back(world.addBody(box));
        }
    }
    return ids;
}

TEST(RestingStep, OneAndTwoThreadsGiveBitIdenticalRestingSteps) {
    // The resting decision reads only the pairs' last solve, which every thread count makes
    // alike: the states stay bit-identical, and the pyramid, at rest from the start, takes
    // resting steps once its contacts are warm: every step but the first, which takes all
    // four sub-steps on new contacts.
    WorldSettings one = noSleep(), two = noSleep();
    two.threads = 2;
    World a(one), b(two);
    const std::vector<BodyId> ids = restingPyramid(a);
    restingPyramid(b);
    int resting = 0;
    constexpr int kSteps = 60;
    for (int step = 0; step < kSteps; ++step) {
        a.step(kDt);
        b.step(kDt);
        ASSERT_EQ(a.stats().substeps, b.stats().substeps) << "step " << step;
        resting += a.stats().substeps == 1;
        for (BodyId id : ids) ASSERT_TRUE(sameBits(a.body(id), b.body(id))) << "step " << step;
    }
    EXPECT_EQ(resting, kSteps - 1);
}

TEST(RestingStep, ACountBeyondTheSubstepsIsRefused) {
    for (const int resting : {-1, 5}) {
        WorldSettings s;
        s.debug.restingSubsteps = resting;
        try {
            World world(s);
            FAIL() << "accepted restingSubsteps " << resting;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.field(), "restingSubsteps") << e.what();
            EXPECT_NE(std::string(e.what()).find(std::to_string(resting)), std::string::npos) << e.what();
        }
    }
}

TEST(RestingStep, APassCountOutsideItsRangeIsRefusedAndTheSettingsKept) {
    WorldFixture f(noSleep());
    for (const int passes : {0, -1, 10001}) {
        WorldSettings s = noSleep();
        s.debug.restingIterations = passes;
        try {
            f.world.setSettings(s);
            FAIL() << "accepted restingIterations " << passes;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.field(), "restingIterations") << e.what();
            EXPECT_NE(std::string(e.what()).find("World::setSettings"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::to_string(passes)), std::string::npos) << e.what();
        }
        EXPECT_EQ(f.world.settings().debug.restingIterations, kRestingPasses);
    }
}

}  // namespace
}  // namespace cyclone::test
