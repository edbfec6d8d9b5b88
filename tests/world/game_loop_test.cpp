// FixedStepper: whole steps from frame times, the cap on steps per frame, and the
// interpolated transforms. Step sizes are powers of two so that the sums are exact.
#include <cmath>
#include <limits>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

FixedStepSettings quarterSecond(int maxSteps = 5) {
    FixedStepSettings s;
    s.stepSeconds = 0.25;
    s.maxStepsPerFrame = maxSteps;
    return s;
}

// 0.625 s is two steps of 0.25 and half a step left; the next 0.125 completes a third.
TEST(FixedStepper, RunsWholeStepsAndCarriesTheRest) {
    WorldFixture f;
    const BodyId ball = f.sphere(Vector3(0, 100, 0));
    FixedStepper stepper(f.world, quarterSecond());
    EXPECT_EQ(stepper.advance(0.625), 2);
    EXPECT_EQ(stepper.accumulatedSeconds(), 0.125);
    EXPECT_EQ(stepper.alpha(), 0.5);
    EXPECT_EQ(stepper.advance(0.125), 1);
    EXPECT_EQ(stepper.alpha(), 0);
    EXPECT_EQ(stepper.advance(0.125), 0);
    EXPECT_EQ(stepper.alpha(), 0.5);
    EXPECT_EQ(stepper.totalSteps(), 3u);
    EXPECT_EQ(stepper.droppedSeconds(), 0);
    // Three world steps of 0.25 s: free fall at g for 0.75 s.
    EXPECT_NEAR(f.world.body(ball).getVelocity().y(), -9.81 * 0.75, 1e-12);
}

// Capped at two steps, a 1.125 s frame (four and a half steps due) runs two, keeps the
// half step and drops the two whole steps beyond the cap.
TEST(FixedStepper, CapsStepsPerFrameAndDropsTheExcess) {
    WorldFixture f;
    FixedStepper stepper(f.world, quarterSecond(2));
    EXPECT_EQ(stepper.advance(1.125), 2);
    EXPECT_EQ(stepper.droppedSeconds(), 0.5);
    EXPECT_EQ(stepper.alpha(), 0.5);
    EXPECT_EQ(stepper.advance(0.25), 1);  // the next frame is not burdened
    EXPECT_EQ(stepper.alpha(), 0.5);
    // A huge stall costs the cap, not a spiral.
    EXPECT_EQ(stepper.advance(1e6), 2);
    EXPECT_LT(stepper.alpha(), 1);
    EXPECT_EQ(stepper.totalSteps(), 5u);
}

// 0.01 added ten times is 0.09999999999999999, not 0.1: without the tolerance the tenth
// frame would run no step and the eleventh would.
TEST(FixedStepper, StepsWhenFrameTimesAddUpToAStep) {
    WorldFixture f;
    FixedStepSettings tenth;
    tenth.stepSeconds = 0.1;
    FixedStepper stepper(f.world, tenth);
    for (int frame = 0; frame < 100; ++frame)
        ASSERT_EQ(stepper.advance(0.01), frame % 10 == 9 ? 1 : 0) << "frame " << frame;
    EXPECT_EQ(stepper.totalSteps(), 10u);
    FixedStepper sixty(f.world);
    for (int frame = 0; frame < 600; ++frame) ASSERT_EQ(sixty.advance(1.0 / 60.0), 1) << "frame " << frame;
    // At 120 Hz frames a step runs every other frame, half a step apart.
    FixedStepper fast(f.world);
    for (int frame = 0; frame < 100; ++frame) {
        ASSERT_EQ(fast.advance(1.0 / 120.0), frame % 2);
        ASSERT_NEAR(fast.alpha(), frame % 2 ? 0 : 0.5, 1e-9);
    }
}

// Each step replaces the events of the one before: afterStep sees every step's own.
TEST(FixedStepper, AfterStepSeesEveryStepsEvents) {
    WorldFixture f;
    f.ground();
    const BodyId ball = f.sphere(Vector3(0, 1.5, 0));
    FixedStepper stepper(f.world);  // 1/60 s steps
    int steps = 0, begins = 0;
    // 28 steps in one frame (cap 30): the ball lands in step 28 (events_test.cpp).
    FixedStepSettings s;
    s.maxStepsPerFrame = 30;
    stepper.setSettings(s);
    const int run = stepper.advance(28.5 / 60, [](real) {}, [&](real) {
        ++steps;
        begins += static_cast<int>(f.world.events().contactBegins.size());
    });
    EXPECT_EQ(run, 28);
    EXPECT_EQ(steps, 28);
    EXPECT_EQ(begins, 1);
    EXPECT_TRUE(f.awake(ball));
}

TEST(FixedStepper, CallsBeforeStepOncePerStep) {
    WorldFixture f;
    const BodyId ball = f.sphere(Vector3(0, 100, 0));
    FixedStepper stepper(f.world, quarterSecond());
    int calls = 0;
    // An upward force of m g each step cancels gravity exactly.
    const int steps = stepper.advance(1.0, [&](real dt) {
        EXPECT_EQ(dt, 0.25);
        ++calls;
        f.world.addForce(ball, Vector3(0, 9.81, 0));
    });
    EXPECT_EQ(steps, 4);
    EXPECT_EQ(calls, 4);
    EXPECT_NEAR(f.world.body(ball).getVelocity().y(), 0, 1e-12);
}

// Moving at 2 m/s without gravity, a body is at x = 0.5 before the second step and 1.0
// after it; with half a step left over, it is drawn at 0.75.
TEST(FixedStepper, InterpolatesBetweenTheLastTwoSteps) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    BodySettings s;
    s.shape = Shape::sphere(0.5);
    s.velocity = Vector3(2, 0, 0);
    s.canSleep = false;
    const BodyId ball = f.world.addBody(s);
    FixedStepper stepper(f.world, quarterSecond());
    stepper.advance(0.625);
    EXPECT_NEAR(f.position(ball).x(), 1.0, 1e-12);
    EXPECT_NEAR(stepper.transform(ball).translation().x(), 0.75, 1e-12);
}

// Position blends linearly and orientation spherically: half way from the identity to 90
// degrees about z is 45 degrees about z.
TEST(FixedStepper, BlendsOrientationAndGivesColumnMajorMatrices) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    const BodyId box = f.box(Vector3::Zero());
    FixedStepper stepper(f.world, quarterSecond());
    stepper.resetInterpolation();
    f.world.setPosition(box, Vector3(2, 0, 0));
    f.world.setOrientation(box, Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitZ())));
    EXPECT_EQ(stepper.advance(0.125), 0);  // alpha 0.5, no step
    const Matrix4 t = stepper.transform(box);
    EXPECT_NEAR(t.translation().x(), 1, 1e-12);
    const double c = std::sqrt(0.5);
    EXPECT_LT((t.linear() - Matrix3(Eigen::AngleAxis<real>(kPi / 4, Vector3::UnitZ()))).norm(), 1e-12);
    float gl[16];
    stepper.glTransform(box, gl);
    EXPECT_NEAR(gl[0], c, 1e-7);   // column 0 = R e_x = (cos 45, sin 45, 0)
    EXPECT_NEAR(gl[1], c, 1e-7);
    EXPECT_NEAR(gl[4], -c, 1e-7);  // column 1 = R e_y = (-sin 45, cos 45, 0)
    EXPECT_EQ(gl[12], 1.0f);       // column 3 = translation
    EXPECT_EQ(gl[15], 1.0f);
    // After resetInterpolation the body is drawn where it is.
    stepper.resetInterpolation();
    EXPECT_NEAR(stepper.transform(box).translation().x(), 2, 1e-12);
}

// A body new since the last step, or a new body in a reused slot, is drawn where it is.
TEST(FixedStepper, NewBodiesAreNotInterpolated) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    const BodyId old = f.box(Vector3::Zero());
    FixedStepper stepper(f.world, quarterSecond());
    stepper.resetInterpolation();
    f.world.removeBody(old);
    const BodyId reused = f.box(Vector3(5, 0, 0));
    ASSERT_EQ(reused.index, old.index);
    const BodyId fresh = f.box(Vector3(0, 0, 7));
    stepper.advance(0.125);
    EXPECT_EQ(stepper.transform(reused).translation(), Vector3(5, 0, 0));
    EXPECT_EQ(stepper.transform(fresh).translation(), Vector3(0, 0, 7));
    try {
        stepper.transform(old);
        FAIL() << "accepted a stale handle";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "FixedStepper::transform");
        EXPECT_EQ(e.field(), "id");
    }
}

TEST(FixedStepper, RefusesBadInput) {
    WorldFixture f;
    auto expectRefusedSettings = [&](const FixedStepSettings &s, const std::string &field) {
        try {
            FixedStepper stepper(f.world, s);
            FAIL() << "accepted a bad " << field;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "FixedStepper::FixedStepper");
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    FixedStepSettings s;
    s.stepSeconds = 0;
    expectRefusedSettings(s, "stepSeconds");
    s.stepSeconds = std::numeric_limits<double>::quiet_NaN();
    expectRefusedSettings(s, "stepSeconds");
    s.stepSeconds = 2;
    expectRefusedSettings(s, "stepSeconds");
    s = FixedStepSettings();
    s.maxStepsPerFrame = 0;
    expectRefusedSettings(s, "maxStepsPerFrame");

    FixedStepper stepper(f.world, quarterSecond());
    stepper.advance(0.125);
    for (double bad : {-0.1, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
        try {
            stepper.advance(bad);
            FAIL() << "accepted frameSeconds " << bad;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "FixedStepper::advance");
            EXPECT_EQ(e.field(), "frameSeconds");
        }
    }
    EXPECT_EQ(stepper.accumulatedSeconds(), 0.125);  // unchanged
    FixedStepSettings bad = quarterSecond();
    bad.maxStepsPerFrame = 1001;
    EXPECT_THROW(stepper.setSettings(bad), InvalidArgument);
    EXPECT_EQ(stepper.settings().maxStepsPerFrame, 5);
}

// A smaller step keeps the fraction of the new step and drops the whole steps.
TEST(FixedStepper, SetSettingsKeepsLessThanAStep) {
    WorldFixture f;
    FixedStepper stepper(f.world, quarterSecond());
    stepper.advance(0.1875);  // 3/16 s left
    FixedStepSettings eighth;
    eighth.stepSeconds = 0.125;
    stepper.setSettings(eighth);
    EXPECT_EQ(stepper.accumulatedSeconds(), 0.0625);
    EXPECT_EQ(stepper.droppedSeconds(), 0.125);
}

}  // namespace
}  // namespace cyclone::test
