// Joints against physics worked by hand: a pendulum's period, a hinge and a slider
// stopped by their limits, motors reaching their speed (or the speed their torque allows),
// a rope caught at its length, a joint that breaks under a load above its threshold and
// holds below it; and the API's refusals, removal, waking and sleeping.
#include <cmath>
#include <cstdio>

#include "joints/joint_fixture.h"

namespace cyclone::test {
namespace {

// --- Pendulum -----------------------------------------------------------------------------

// A 1 kg sphere of radius r = 0.05 m hung L = 1 m below a ball joint and let go at 10 deg.
// As a physical pendulum, I about the pivot is m (L^2 + 2/5 r^2) and the small-angle period
// T0 = 2 pi sqrt((L^2 + 0.4 r^2) / (g L)); at amplitude th0 the period is longer by
// 1 + th0^2/16 + 11 th0^4/3072 (the series of the complete elliptic integral): 1.0019 at
// 10 deg. The period is measured between upward zero crossings of x over 10 s.
struct PendulumRun {
    real period = 0;
    real firstAmplitude = 0;  ///< Largest |x| in the first period, m.
    real lastAmplitude = 0;   ///< Largest |x| in the last period, m.
    real largestGap = 0;
};

PendulumRun runPendulum(real dt) {
    World world(noSleep());
    const real length = 1;
    const real r = 0.05;
    const real th0 = 10 * kPi / 180;
    const Vector3 pivot(0, 10, 0);
    BodySettings s;
    s.shape = Shape::sphere(r);
    s.mass = 1;
    s.position = pivot + length * Vector3(std::sin(th0), -std::cos(th0), 0);
    const BodyId bob = world.addBody(s);
    JointSettings j;
    j.type = JointType::Ball;
    j.a = bob;
    j.anchor = pivot;
    const JointId joint = world.addJoint(j);

    PendulumRun run;
    std::vector<real> crossings;
    std::vector<real> amplitudes(1, 0);
    real previousX = world.body(bob).getPosition().x();
    const int steps = static_cast<int>(std::lround(10 / dt));
    for (int i = 1; i <= steps; ++i) {
        world.step(dt);
        const real x = world.body(bob).getPosition().x();
        run.largestGap = std::max(run.largestGap, world.jointState(joint).error);
        amplitudes.back() = std::max(amplitudes.back(), std::abs(x));
        if (previousX < 0 && x >= 0) {
            crossings.push_back(dt * (i - 1 + -previousX / (x - previousX)));
            amplitudes.push_back(0);
        }
        previousX = x;
    }
    EXPECT_GE(crossings.size(), 4u);
    if (crossings.size() < 2) return run;
    run.period = (crossings.back() - crossings.front()) / static_cast<real>(crossings.size() - 1);
    run.firstAmplitude = amplitudes[1];
    run.lastAmplitude = amplitudes[amplitudes.size() - 2];
    return run;
}

class Pendulum : public ::testing::TestWithParam<real> {};

TEST_P(Pendulum, PeriodAmplitudeAndGapMatchTheClosedForm) {
    const real dt = GetParam();
    const real th0 = 10 * kPi / 180;
    const real t0 = 2 * kPi * std::sqrt((1 + 0.4 * 0.05 * 0.05) / kG);
    const real expected = t0 * (1 + th0 * th0 / 16 + 11 * std::pow(th0, 4) / 3072);
    const PendulumRun run = runPendulum(dt);
    std::printf("pendulum dt %.5f: period %.6f s (closed form %.6f, %+.3f%%), amplitude %.5f -> %.5f m, gap %.3g m\n",
                dt, run.period, expected, 100 * (run.period / expected - 1), run.firstAmplitude, run.lastAmplitude,
                run.largestGap);
    EXPECT_NEAR(run.period, expected, 0.01 * expected);
    // x amplitude L sin(10 deg) = 0.1736 m, kept within 5 %.
    const real amplitude = std::sin(th0);
    EXPECT_NEAR(run.firstAmplitude, amplitude, 0.05 * amplitude);
    EXPECT_NEAR(run.lastAmplitude, amplitude, 0.05 * amplitude);
    EXPECT_LE(run.largestGap, 0.001);
}

INSTANTIATE_TEST_SUITE_P(StepSizes, Pendulum, ::testing::Values(1.0 / 60, 1.0 / 120, 1.0 / 30));

// --- Hinge ----------------------------------------------------------------------------------

// A door (1 m x 2 m x 0.1 m, 20 kg) hinged to the world along its edge, axis y, limits
// [-1, 1] rad, turned at 3 rad/s: gravity along the axis exerts no torque about it, so the
// door reaches 1 rad after 1/3 s and must stop there (overshoot <= 0.02 rad), and never
// pass it or leave it afterwards.
TEST(Hinge, DoorSwungIntoItsLimitStopsThere) {
    World world(noSleep());
    const BodyId door = addBox(world, Vector3(0.5, 1, 0), Vector3(0.5, 1, 0.05), 20);
    world.setRotation(door, Vector3(0, 3, 0));
    world.setVelocity(door, Vector3(0, 0, -1.5));  // the centre's speed about the hinge, 3 rad/s x 0.5 m
    JointSettings j = jointSettings(JointType::Hinge, door, Vector3(0, 1, 0), Vector3::UnitY());
    j.limits = JointLimits{-1, 1};
    const JointId hinge = world.addJoint(j);
    real largest = -10;
    for (int i = 0; i < 180; ++i) {
        world.step(kDt);
        largest = std::max(largest, world.jointState(hinge).position);
    }
    std::printf("door: largest angle %.5f rad (limit 1)\n", largest);
    EXPECT_GT(largest, 0.98);  // it reached the limit
    EXPECT_LE(largest, 1.02);
    // A limit has no restitution: the door stays at it, it does not swing back.
    EXPECT_GT(world.jointState(hinge).position, 0.98);
    EXPECT_LE(world.jointState(hinge).error, 0.001);
}

// A hinge's motor with torque to spare reaches its speed; one whose torque is the limit
// accelerates at tau / I. The plate (half extents 0.5, 0.5, 0.1 m, 1 kg) turns about z
// through its centre: I_z = m (0.5^2 + 0.5^2) / 3 = 1/6 kg m^2.
TEST(Hinge, MotorReachesItsSpeed) {
    World world(noSleep());
    const BodyId wheel = addBox(world, Vector3(0, 5, 0), Vector3(0.5, 0.5, 0.1), 1);
    JointSettings j = jointSettings(JointType::Hinge, wheel, Vector3(0, 5, 0), Vector3::UnitZ());
    j.motor = JointMotor{2, 50};
    const JointId hinge = world.addJoint(j);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    EXPECT_NEAR(world.body(wheel).getRotation().z(), 2, 0.02);
    world.setMotorSpeed(hinge, -1);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    EXPECT_NEAR(world.body(wheel).getRotation().z(), -1, 0.01);
}

TEST(Hinge, MotorLimitedByItsTorqueAcceleratesAtTorqueOverInertia) {
    World world(noSleep());
    const BodyId wheel = addBox(world, Vector3(0, 5, 0), Vector3(0.5, 0.5, 0.1), 1);
    JointSettings j = jointSettings(JointType::Hinge, wheel, Vector3(0, 5, 0), Vector3::UnitZ());
    j.motor = JointMotor{10, 0.1};  // alpha = 0.1 / (1/6) = 0.6 rad/s^2: 0.6 rad/s after 1 s
    world.addJoint(j);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    EXPECT_NEAR(world.body(wheel).getRotation().z(), 0.6, 0.006);
}

// "A motor reaches its speed within 1 %", under a load it must overcome. A 2 kg arm
// (1 m x 0.1 m x 0.1 m) hinged at one end to the world about z, level at the start, its
// motor at 1 rad/s with 50 N m: gravity's torque about the hinge is at most
// m g L / 2 = 9.81 N m and I about the end is m L^2 / 3 = 2/3 kg m^2, so the motor
// has (50 - 9.81) / (2/3) = 60 rad/s^2 to spare and reaches 1 rad/s within 1/60 s. From
// 0.1 s on, while the arm rises to 1.5 rad (gravity's torque falling from 9.81 N m to
// 9.81 cos 1.5 = 0.7 N m), its speed about the hinge stays within 1 % of 1 rad/s.
TEST(Hinge, MotorHoldsItsSpeedAgainstALoadWithinOnePercent) {
    World world(noSleep());
    const BodyId arm = addBox(world, Vector3(0.5, 5, 0), Vector3(0.5, 0.05, 0.05), 2);
    JointSettings j = jointSettings(JointType::Hinge, arm, Vector3(0, 5, 0), Vector3::UnitZ());
    j.motor = JointMotor{1, 50};
    const JointId hinge = world.addJoint(j);
    real worst = 0;
    for (int i = 1; i <= 90; ++i) {
        world.step(kDt);
        if (i >= 6) worst = std::max(worst, std::abs(world.body(arm).getRotation().z() - 1));
    }
    std::printf("hinge motor under load: largest speed error %.3g (relative), angle %.3f rad\n", worst,
                world.jointState(hinge).position);
    EXPECT_LE(worst, 0.01);
    EXPECT_NEAR(world.jointState(hinge).position, 1.5, 0.02);  // 1 rad/s for 1.5 s
}

// --- Slider ---------------------------------------------------------------------------------

// A 5 kg box on a slider along x with limits [-0.5, 0.5] m, launched at 4 m/s: it reaches
// the limit after 1/8 s and must stop within 1.5 cm past it, while gravity (across the axis)
// is held by the slider.
TEST(Slider, StopsAtItsLimit) {
    World world(noSleep());
    const BodyId box = addBox(world, Vector3(0, 3, 0), Vector3(0.2, 0.2, 0.2), 5);
    world.setVelocity(box, Vector3(4, 0, 0));
    JointSettings j = jointSettings(JointType::Slider, box, Vector3(0, 3, 0), Vector3::UnitX());
    j.limits = JointLimits{-0.5, 0.5};
    const JointId slider = world.addJoint(j);
    real largest = 0;
    for (int i = 0; i < 120; ++i) {
        world.step(kDt);
        largest = std::max(largest, world.jointState(slider).position);
    }
    std::printf("slider: largest offset %.5f m (limit 0.5)\n", largest);
    EXPECT_GT(largest, 0.49);
    EXPECT_LE(largest, 0.515);
    EXPECT_NEAR(world.body(box).getPosition().y(), 3, 0.001);  // held across the axis
}

// A slider motor (1 m/s, 100 N) pushes a 5 kg box along the axis against nothing: at most
// 100 N / 5 kg = 20 m/s^2, so 1 m/s is reached in 0.05 s and kept.
TEST(Slider, MotorReachesItsSpeed) {
    World world(noSleep());
    const BodyId box = addBox(world, Vector3(0, 3, 0), Vector3(0.2, 0.2, 0.2), 5);
    JointSettings j = jointSettings(JointType::Slider, box, Vector3(0, 3, 0), Vector3(1, 0, 0));
    j.motor = JointMotor{1, 100};
    world.addJoint(j);
    for (int i = 0; i < 30; ++i) world.step(kDt);
    EXPECT_NEAR(world.body(box).getVelocity().x(), 1, 0.01);
    EXPECT_NEAR(world.body(box).getVelocity().y(), 0, 1e-6);
}

// The slider's motor lifts a 5 kg box up a vertical axis at 1 m/s with at most 100 N
// against its weight, m g = 49 N: (100 - 49) / 5 = 10.2 m/s^2 to spare, so the speed is
// reached after 1 / 10.2 = 0.098 s; from 0.1 s on it stays within 1 % of 1 m/s, and
// after 1 s the box has risen 1 m less the 0.098 / 2 = 0.049 m the acceleration lost.
TEST(Slider, MotorHoldsItsSpeedAgainstGravityWithinOnePercent) {
    World world(noSleep());
    const BodyId box = addBox(world, Vector3(0, 3, 0), Vector3(0.2, 0.2, 0.2), 5);
    JointSettings j = jointSettings(JointType::Slider, box, Vector3(0, 3, 0), Vector3::UnitY());
    j.motor = JointMotor{1, 100};
    world.addJoint(j);
    real worst = 0;
    for (int i = 1; i <= 60; ++i) {
        world.step(kDt);
        if (i >= 6) worst = std::max(worst, std::abs(world.body(box).getVelocity().y() - 1));
    }
    std::printf("slider motor against gravity: largest speed error %.3g (relative)\n", worst);
    EXPECT_LE(worst, 0.01);
    EXPECT_NEAR(world.body(box).getPosition().y(), 4 - 0.049, 0.005);
}

// --- Distance -------------------------------------------------------------------------------

// A 10 kg ball on a 2 m rope from a world point, let go 1 m below it (the rope slack): it
// falls freely for 1 m, then the rope catches it. The rope never stretches more than 1 %,
// and it pushes nothing while slack (the first 1 m is free fall: y = 9 - g t^2 / 2).
TEST(Distance, RopeCatchesAndNeverStretchesMoreThanOnePercent) {
    World world(noSleep());
    BodySettings s;
    s.shape = Shape::sphere(0.1);
    s.mass = 10;
    s.position = Vector3(0.3, 9, 0);
    s.collidesWith = 0;
    const BodyId ball = world.addBody(s);
    JointSettings j;
    j.type = JointType::Distance;
    j.a = ball;
    j.anchor = Vector3(0.3, 9, 0);
    j.anchorB = Vector3(0, 10, 0);
    j.minDistance = 0;
    j.maxDistance = 2;
    world.addJoint(j);
    // 5 steps: 0.083 s, a fall of about 3.4 cm, well within the slack.
    for (int i = 0; i < 5; ++i) world.step(kDt);
    const real t = 5 * kDt;
    EXPECT_NEAR(world.body(ball).getPosition().y(), 9 - kG * t * t / 2, 0.01);
    real longest = 0;
    for (int i = 0; i < 300; ++i) {
        world.step(kDt);
        longest = std::max(longest, (world.body(ball).getPosition() - Vector3(0, 10, 0)).norm());
    }
    std::printf("rope: longest %.5f m (length 2)\n", longest);
    EXPECT_GT(longest, 1.99);  // it was caught, taut
    EXPECT_LE(longest, 2.02);
}

// --- Breaking -------------------------------------------------------------------------------

// A 2 kg box hung at its centre of mass from a world point: at rest the joint carries m g =
// 19.62 N. A threshold 5 % above holds for 2 s; 5 % below breaks in the first step, which
// reports it, and the box then falls freely.
TEST(Breaking, BreaksWhenTheLoadExceedsTheThresholdAndNotBelow) {
    const real weight = 2 * kG;
    for (const real factor : {1.05, 0.95}) {
        World world(noSleep());
        const BodyId box = addBox(world, Vector3(0, 5, 0), Vector3(0.2, 0.2, 0.2), 2);
        JointSettings j;
        j.type = JointType::Ball;
        j.a = box;
        j.anchor = Vector3(0, 5, 0);
        j.breakForce = factor * weight;
        const JointId joint = world.addJoint(j);
        world.step(kDt);
        if (factor > 1) {
            EXPECT_TRUE(world.contains(joint));
            EXPECT_NEAR(world.jointState(joint).force.y(), weight, 1e-6 * weight);
            for (int i = 0; i < 119; ++i) world.step(kDt);
            EXPECT_TRUE(world.contains(joint));
            EXPECT_NEAR(world.body(box).getPosition().y(), 5, 1e-6);
        } else {
            EXPECT_FALSE(world.contains(joint));
            ASSERT_EQ(world.events().jointsBroken.size(), 1u);
            EXPECT_EQ(world.events().jointsBroken[0].joint, joint);
            EXPECT_NEAR(world.events().jointsBroken[0].force.y(), weight, 1e-6 * weight);
            world.step(kDt);
            EXPECT_LT(world.body(box).getVelocity().y(), -0.1);  // falling
        }
    }
}

// --- API ------------------------------------------------------------------------------------

TEST(JointApi, BadInputIsRefusedAndNothingChanges) {
    World world(noSleep());
    const BodyId a = addBox(world, Vector3(0, 1, 0), Vector3(0.5, 0.5, 0.5), 1);
    BodySettings ground;
    ground.isStatic = true;
    ground.shape = Shape::box(Vector3(1, 0.1, 1));
    const BodyId g = world.addBody(ground);
    const auto refused = [&](const JointSettings &j, const std::string &field) { expectJointRefused(world, j, field); };
    JointSettings base;
    base.a = a;
    base.anchor = Vector3(0, 1.5, 0);
    JointSettings j = base;
    j.type = JointType::Hinge;
    j.axis = Vector3::Zero();
    refused(j, "axis");
    j.axis = Vector3(0, std::nan(""), 0);
    refused(j, "axis");
    j = base;
    j.type = JointType::Slider;
    j.axis = Vector3::UnitX();
    j.limits = JointLimits{1, -1};
    refused(j, "limits");
    j = base;
    j.type = JointType::Hinge;
    j.limits = JointLimits{-4, 0};
    refused(j, "limits");
    j = base;
    j.limits = JointLimits{-1, 1};  // a ball has none
    refused(j, "limits");
    j = base;
    j.type = JointType::Hinge;
    j.motor = JointMotor{1, -1};
    refused(j, "motor.maxForce");
    j = base;
    j.b = a;
    refused(j, "b");
    j = base;
    j.a = g;  // static, joined to the world: nothing moves
    refused(j, "a");
    j = base;
    j.anchor = Vector3(std::nan(""), 0, 0);
    refused(j, "anchor");
    j = base;
    j.type = JointType::Distance;
    j.minDistance = 2;
    j.maxDistance = 1;
    refused(j, "maxDistance");
    j = base;
    j.stiffness = 10;  // a ball has none
    refused(j, "stiffness");
    j = base;
    j.breakForce = 0;
    refused(j, "breakForce");
    j = base;
    j.a = BodyId{7, 0};
    refused(j, "id");
    // Nothing was added: the first joint takes slot 0, generation 0.
    const JointId first = world.addJoint(base);
    EXPECT_EQ(first.index, 0u);
    EXPECT_EQ(first.generation, 0u);
    world.removeJoint(first);
    EXPECT_THROW(world.removeJoint(first), InvalidArgument);
    EXPECT_THROW(world.jointState(first), InvalidArgument);
    EXPECT_THROW(world.setMotorSpeed(world.addJoint(base), 1), InvalidArgument);  // no motor
}

TEST(JointApi, RemovingABodyRemovesItsJointsAndWakesTheOtherBody) {
    World world;
    const BodyId a = addBox(world, Vector3(0, 5, 0), Vector3(0.2, 0.2, 0.2), 1);
    const BodyId b = addBox(world, Vector3(0, 4, 0), Vector3(0.2, 0.2, 0.2), 1);
    JointSettings j;
    j.a = b;
    j.b = a;
    j.anchor = Vector3(0, 4.5, 0);
    const JointId ab = world.addJoint(j);
    j.a = a;
    j.b.reset();
    j.anchor = Vector3(0, 5.5, 0);
    const JointId top = world.addJoint(j);
    world.step(kDt);  // the step that makes the two one island
    world.setAwake(a, false);
    EXPECT_FALSE(world.body(b).getAwake());  // one island: both sleep
    world.removeBody(a);
    EXPECT_FALSE(world.contains(ab));
    EXPECT_FALSE(world.contains(top));
    EXPECT_TRUE(world.body(b).getAwake());
    world.step(kDt);
    EXPECT_LT(world.body(b).getVelocity().y(), 0);  // nothing holds it now
}

// Two boxes hanging at rest, one from the world and one from it, sleep in the same step
// (one island); an impulse on the upper one wakes its island, the lower one with it, and
// they stay awake together while they swing.
TEST(JointApi, JoinedBodiesSleepTogetherAndWakeEachOther) {
    World world;
    const BodyId upper = addBox(world, Vector3(0, 5, 0), Vector3(0.2, 0.2, 0.2), 1);
    const BodyId lower = addBox(world, Vector3(0, 4, 0), Vector3(0.2, 0.2, 0.2), 1);
    JointSettings j;
    j.a = upper;
    j.anchor = Vector3(0, 5.5, 0);
    world.addJoint(j);
    j.a = lower;
    j.b = upper;
    j.anchor = Vector3(0, 4.5, 0);
    world.addJoint(j);
    int steps = 0;
    while (world.body(upper).getAwake() && steps < 600) {
        world.step(kDt);
        ++steps;
        EXPECT_EQ(world.body(upper).getAwake(), world.body(lower).getAwake()) << "step " << steps;
    }
    ASSERT_FALSE(world.body(lower).getAwake());
    world.applyImpulse(upper, Vector3(1, 0, 0));
    EXPECT_TRUE(world.body(lower).getAwake());
    for (int i = 0; i < 30; ++i) {
        world.step(kDt);
        EXPECT_TRUE(world.body(upper).getAwake());
        EXPECT_TRUE(world.body(lower).getAwake());
    }
    EXPECT_GT(std::abs(world.body(lower).getVelocity().x()), 0.01);  // the joint pulls it along
}

// Joined bodies do not collide unless collideConnected: two overlapping boxes.
TEST(JointApi, JoinedBodiesCollideOnlyWhenAskedTo) {
    for (const bool collide : {false, true}) {
        WorldSettings settings = noSleep();
        settings.gravity = Vector3::Zero();
        World world(settings);
        const BodyId a = addBox(world, Vector3(0, 0, 0), Vector3(0.5, 0.5, 0.5), 1, kAllLayers);
        const BodyId b = addBox(world, Vector3(0.8, 0, 0), Vector3(0.5, 0.5, 0.5), 1, kAllLayers);
        JointSettings j;
        j.a = a;
        j.b = b;
        j.anchor = Vector3(0.4, 0, 0);
        j.collideConnected = collide;
        world.addJoint(j);
        world.step(kDt);
        EXPECT_EQ(world.stats().contacts > 0, collide);
    }
}

// A scene without joints does no joint work: no joint, no row, in any step.
TEST(JointApi, AWorldWithoutJointsSolvesNone) {
    World world(noSleep());
    const BodyId a = addBox(world, Vector3(0, 5, 0), Vector3(0.2, 0.2, 0.2), 1);
    world.step(kDt);
    EXPECT_EQ(world.stats().joints, 0);
    EXPECT_EQ(world.stats().jointRows, 0);
    JointSettings j;
    j.a = a;
    j.anchor = Vector3(0, 5, 0);
    const JointId joint = world.addJoint(j);
    world.step(kDt);
    EXPECT_EQ(world.stats().joints, 1);
    EXPECT_EQ(world.stats().jointRows, 3 * world.settings().substeps);  // a ball's 3 rows per sub-step
    world.removeJoint(joint);
    world.step(kDt);
    EXPECT_EQ(world.stats().joints, 0);
    EXPECT_EQ(world.stats().jointRows, 0);
}

// The same heavy chain with 1 and 2 threads: the same bits.
TEST(JointApi, ChainIsThreadCountIndependent) {
    std::vector<Vector3> positions[2];
    for (int threads = 1; threads <= 2; ++threads) {
        WorldSettings settings = noSleep();
        settings.threads = threads;
        World world(settings);
        const Chain chain(world, 10, 0.5, 100, true);
        for (int i = 0; i < 120; ++i) world.step(kDt);
        for (const BodyId id : chain.bodies) positions[threads - 1].push_back(world.body(id).getPosition());
    }
    ASSERT_EQ(positions[0].size(), positions[1].size());
    for (std::size_t k = 0; k < positions[0].size(); ++k) EXPECT_EQ(positions[0][k], positions[1][k]) << k;
}

}  // namespace
}  // namespace cyclone::test
