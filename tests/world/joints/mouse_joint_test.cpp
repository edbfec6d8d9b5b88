// The mouse joint against the damped spring it stands for: the approach to a target with
// the time constant of its frequency, the sag of a hanging body, the force bound as a
// length, and the API's refusals and waking.
#include <cmath>
#include <cstdio>

#include "joints/joint_fixture.h"

namespace cyclone::test {
namespace {

constexpr real kG = 9.81;

BodyId addSphere(World &world, const Vector3 &position, real mass) {
    BodySettings s;
    s.shape = Shape::sphere(0.1);
    s.position = position;
    s.mass = mass;
    s.collidesWith = 0;
    return world.addBody(s);
}

JointSettings mouseAt(BodyId body, const Vector3 &anchor, const Vector3 &target, const JointPull &pull) {
    JointSettings j;
    j.type = JointType::Mouse;
    j.a = body;
    j.anchor = anchor;
    j.anchorB = target;
    j.pull = pull;
    return j;
}

// A 2 kg sphere held at its centre, no gravity, the target 1 m away along x; the pull at
// f = 1 Hz, critically damped. With omega = 2 pi f the gap e = x - target follows
// e'' = -omega^2 e - 2 omega e', so from rest e(t) = -d (1 + omega t) exp(-omega t):
// 0.534 d at 0.25 s, 0.179 d at 0.5 s, 0.0136 d at 1 s, 4.7e-5 d at 2 s. The solver takes
// the spring implicitly (backward Euler on each sub-step h): v' = (v - h omega^2 e) /
// (1 + 2 omega h + omega^2 h^2), e' = e + h v'; that recurrence is met to rounding, and
// it stays within 0.4 % of d of the closed form at h = 1/240 s (its damping error is of
// order omega h = 0.026), so 1 % of d is the tolerance against the closed form.
TEST(MouseJoint, ApproachesItsTargetWithTheTimeConstantOfItsFrequency) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    World world(settings);
    const BodyId ball = addSphere(world, Vector3(0, 5, 0), 2);
    JointPull pull;
    pull.frequency = 1;
    pull.dampingRatio = 1;
    const JointId mouse = world.addJoint(mouseAt(ball, Vector3(0, 5, 0), Vector3(1, 5, 0), pull));
    EXPECT_NEAR(world.jointState(mouse).error, 1, 1e-12);

    const real omega = 2 * kPi;
    const real h = kDt / settings.substeps;
    real e = -1, v = 0;
    int checked = 0;
    for (int step = 1; step <= 120; ++step) {
        world.step(kDt);
        for (int k = 0; k < settings.substeps; ++k) {
            v = (v - h * omega * omega * e) / (1 + 2 * omega * h + omega * omega * h * h);
            e += h * v;
        }
        const real x = world.body(ball).getPosition().x() - 1;
        ASSERT_NEAR(x, e, 1e-9) << "step " << step;
        const real t = step * kDt;
        if (step == 15 || step == 30 || step == 60) {
            const real closed = -(1 + omega * t) * std::exp(-omega * t);
            std::printf("mouse: t = %.2f s, gap %.6f m, closed form %.6f m\n", t, -x, -closed);
            EXPECT_NEAR(x, closed, 0.01) << "t = " << t;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 3);
    EXPECT_LT(world.jointState(mouse).error, 1e-4);  // 4.7e-5 m by the closed form at 2 s
    EXPECT_NEAR(world.body(ball).getPosition().y(), 5, 1e-12);
}

// The same pull holds a hanging body below its target by the spring's stretch under the
// weight: m g = m omega^2 s, so s = g / omega^2 = 9.81 / (4 pi)^2 = 0.0621 m at 2 Hz,
// whatever the mass. A 3 kg box held at the middle of its top face, 3 s after release
// (the oscillation decays as exp(-zeta omega t) = exp(-26)).
TEST(MouseJoint, AHangingBodySagsByGravityOverOmegaSquared) {
    World world(noSleep());
    BodySettings s;
    s.shape = Shape::box(Vector3(0.3, 0.2, 0.1));
    s.position = Vector3(0, 3, 0);
    s.mass = 3;
    const BodyId box = world.addBody(s);
    JointPull pull;
    pull.frequency = 2;
    pull.dampingRatio = 0.7;
    const JointId mouse = world.addJoint(mouseAt(box, Vector3(0, 3.2, 0), Vector3(0, 3.2, 0), pull));
    for (int i = 0; i < 180; ++i) world.step(kDt);
    const real omega = 2 * kPi * 2;
    const real sag = kG / (omega * omega);
    EXPECT_NEAR(world.jointState(mouse).error, sag, 1e-6);
    EXPECT_NEAR(world.body(box).getPosition().y(), 3 - sag, 1e-6);
    // The joint carries the weight.
    EXPECT_NEAR(world.jointState(mouse).force.y(), 3 * kG, 1e-6);
}

// A 2 kg sphere pulled at a target 100 m away along (1, 1, 1), no gravity, with at most
// 10 N: the spring asks for far more, so the pull is 10 N along the gap all the way and
// the sphere accelerates at 10 / 2 = 5 m/s^2, reaching 5 m/s after 1 s. The bound is on
// the force's length: component by component, 10 N on each axis would be 17.3 N.
TEST(MouseJoint, ItsForceNeverExceedsMaxForce) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    World world(settings);
    const BodyId ball = addSphere(world, Vector3::Zero(), 2);
    const Vector3 direction = Vector3(1, 1, 1).normalized();
    JointPull pull;
    pull.maxForce = 10;
    const JointId mouse = world.addJoint(mouseAt(ball, Vector3::Zero(), 100 * direction, pull));
    for (int i = 0; i < 60; ++i) {
        world.step(kDt);
        ASSERT_NEAR(world.jointState(mouse).force.norm(), 10, 1e-9) << "step " << i;
    }
    const Vector3 v = world.body(ball).getVelocity();
    EXPECT_NEAR(v.norm(), 5, 1e-9);
    EXPECT_NEAR(v.dot(direction), 5, 1e-9);  // straight at the target
    EXPECT_NEAR(world.jointState(mouse).force.dot(direction), 10, 1e-9);
}

// Moving the target drags the body along: a target moved 1 m further along x each
// second (setMouseTarget every step) is followed, after the start, with the lag of a
// critically damped spring chasing a ramp: 2 zeta / omega * speed = 2 / (2 pi 2) m at 2 Hz.
TEST(MouseJoint, FollowsAMovingTargetWithTheSpringsLag) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    World world(settings);
    const BodyId ball = addSphere(world, Vector3::Zero(), 1);
    JointPull pull;
    pull.frequency = 2;
    pull.dampingRatio = 1;
    const JointId mouse = world.addJoint(mouseAt(ball, Vector3::Zero(), Vector3::Zero(), pull));
    for (int i = 1; i <= 180; ++i) {
        world.setMouseTarget(mouse, Vector3(i * kDt, 0, 0));
        world.step(kDt);
    }
    const real lag = 2 / (2 * kPi * 2);
    // The target moves in steps of dt while the spring sees it at the step's start: the
    // body lags half a step more on average (1/120 m); 2 mm covers the discretisation.
    EXPECT_NEAR(180 * kDt - world.body(ball).getPosition().x(), lag, 0.002 + kDt);
    EXPECT_NEAR(world.body(ball).getVelocity().x(), 1, 0.01);
}

TEST(MouseJoint, BadInputIsRefusedAndNothingChanges) {
    World world(noSleep());
    const BodyId ball = addSphere(world, Vector3(0, 1, 0), 1);
    const BodyId other = addSphere(world, Vector3(0, 3, 0), 1);
    BodySettings ground;
    ground.isStatic = true;
    ground.shape = Shape::box(Vector3(1, 0.1, 1));
    const BodyId g = world.addBody(ground);
    const auto refused = [&](const JointSettings &j, const std::string &field) { expectJointRefused(world, j, field); };
    const JointSettings base = mouseAt(ball, Vector3(0, 1, 0), Vector3(0, 2, 0), JointPull());
    JointSettings j = base;
    j.b = other;
    refused(j, "b");
    j = base;
    j.a = g;
    refused(j, "a");
    j = base;
    j.pull->frequency = 0;
    refused(j, "pull.frequency");
    j.pull->frequency = std::nan("");
    refused(j, "pull.frequency");
    j = base;
    j.pull->dampingRatio = -0.1;
    refused(j, "pull.dampingRatio");
    j = base;
    j.pull->maxForce = 0;
    refused(j, "pull.maxForce");
    j = base;
    j.anchorB = Vector3(0, std::nan(""), 0);
    refused(j, "anchorB");
    j = base;
    j.type = JointType::Ball;  // only mouse joints pull
    refused(j, "anchorB");
    j.anchorB.reset();
    refused(j, "pull");
    // Nothing was added: the first joint takes slot 0, generation 0.
    const JointId mouse = world.addJoint(base);
    EXPECT_EQ(mouse.index, 0u);
    EXPECT_EQ(mouse.generation, 0u);
    EXPECT_EQ(world.jointSettings(mouse).pull->frequency, JointPull().frequency);

    const auto refusedTarget = [&](JointId id, const Vector3 &target, const std::string &field) {
        try {
            world.setMouseTarget(id, target);
            ADD_FAILURE() << "accepted, expected a refusal of " << field;
        } catch (const InvalidArgument &error) {
            EXPECT_EQ(error.function(), "World::setMouseTarget");
            EXPECT_EQ(error.field(), field) << error.what();
        }
    };
    refusedTarget(mouse, Vector3(std::nan(""), 0, 0), "target");
    refusedTarget(mouse, Vector3(0, 2e30, 0), "target");
    JointSettings ball2 = base;
    ball2.type = JointType::Ball;
    ball2.anchorB.reset();
    ball2.pull.reset();
    refusedTarget(world.addJoint(ball2), Vector3::Zero(), "id");
    EXPECT_EQ(*world.jointSettings(mouse).anchorB, Vector3(0, 2, 0));
    world.removeJoint(mouse);
    refusedTarget(mouse, Vector3::Zero(), "id");
}

// A held body at rest falls asleep like any other; the same target again leaves it
// asleep, a new one wakes it; removing the body removes its mouse joint.
TEST(MouseJoint, ANewTargetWakesTheBodyAndTheSameOneDoesNot) {
    World world;
    const BodyId ball = addSphere(world, Vector3(0, 1, 0), 1);
    const JointId mouse = world.addJoint(mouseAt(ball, Vector3(0, 1, 0), Vector3(0, 1, 0), JointPull()));
    int steps = 0;
    while (world.body(ball).getAwake() && steps < 600) {
        world.step(kDt);
        ++steps;
    }
    ASSERT_FALSE(world.body(ball).getAwake());
    world.setMouseTarget(mouse, *world.jointSettings(mouse).anchorB);
    EXPECT_FALSE(world.body(ball).getAwake());
    world.setMouseTarget(mouse, Vector3(0, 2, 0));
    EXPECT_TRUE(world.body(ball).getAwake());
    world.removeBody(ball);
    EXPECT_FALSE(world.contains(mouse));
}

}  // namespace
}  // namespace cyclone::test
