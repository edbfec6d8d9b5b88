// Servo motors: a hinge driven to an angle as a critically damped spring would, a
// torque-limited servo accelerating at tau / I, a vertical slider sagging by g / w^2 under
// its load and following a target moved at run time, and the API's refusals.
#include <cmath>
#include <string>

#include "joints/joint_fixture.h"

namespace cyclone::test {
namespace {

// A door: a 10 kg box 1 m wide (x), 2 m tall (y), 0.1 m thick (z), its edge x = 0 on a
// vertical hinge to the world. Its moment of inertia about the hinge is
// m (w^2 + t^2) / 12 + m (w/2)^2 = 10 (1 + 0.01) / 12 + 10 * 0.25 = 3.341667 kg m^2.
struct Door {
    World world{noSleep()};
    BodyId door;
    JointId hinge;

    explicit Door(const JointServo &servo) {
        door = addBox(world, Vector3(0.5, 1, 0), Vector3(0.5, 1, 0.05), 10);
        JointSettings j = jointSettings(JointType::Hinge, door, Vector3(0, 1, 0), Vector3::UnitY());
        j.servo = servo;
        hinge = world.addJoint(j);
    }
};

JointServo servo(real target, real frequency, real dampingRatio, real maxForce) {
    return JointServo{target, frequency, dampingRatio, maxForce};
}

// A servo of 1 Hz, damping ratio 1, to 1 rad, with torque to spare: a critically damped
// spring (w = 2 pi) started at rest at 0 follows theta(t) = 1 - (1 + w t) e^(-w t):
// 0.4655 rad at 0.25 s, 0.8210 rad at 0.5 s, and never passes 1 rad. The implicit spring
// over 240 Hz sub-steps damps a little more than the continuous one (order w h = 0.026),
// so the trajectory is asked within 0.01 rad; it ends within 0.01 rad of the target
// after 3 s (the closed form's gap is then 1.3e-7 rad), with at most 2 % overshoot.
TEST(Servo, HingeReachesItsTargetAsACriticallyDampedSpring) {
    Door d(servo(1, 1, 1, 1e4));
    const real omega = 2 * kPi;
    real highest = 0;
    for (int step = 1; step <= 180; ++step) {
        d.world.step(kDt);
        const real angle = d.world.jointState(d.hinge).position;
        highest = std::max(highest, angle);
        const real t = step * kDt;
        if (step == 15 || step == 30) {
            EXPECT_NEAR(angle, 1 - (1 + omega * t) * std::exp(-omega * t), 0.01) << t;
        }
    }
    EXPECT_NEAR(d.world.jointState(d.hinge).position, 1, 0.01);
    EXPECT_LE(highest, 1.02);
}

// The same door driven to 2 rad by a stiff servo (5 Hz) allowed only 2 N m: the spring
// asks for far more, so the motor gives its whole 2 N m and the door turns at
// alpha = tau / I = 2 / 3.341667 = 0.59850 rad/s^2, theta = alpha t^2 / 2 = 0.074813 rad
// at 0.5 s (within 1 %).
TEST(Servo, TorqueLimitedServoAcceleratesAtTauOverI) {
    Door d(servo(2, 5, 1, 2));
    for (int step = 0; step < 30; ++step) d.world.step(kDt);
    const real expected = 0.5 * (2 / 3.341667) * 0.25;
    EXPECT_NEAR(d.world.jointState(d.hinge).position, expected, 0.01 * expected);
}

// A 5 kg box on a vertical slider to the world, its servo (2 Hz, damping ratio 1) holding
// the offset 0: as a spring of stiffness k = m w^2 it sags under the weight m g to
// -g / w^2 = -9.81 / (4 pi)^2 = -0.062124 m. At a standstill the implicit step has the
// same fixed point (the spring's impulse m g h per sub-step, its damping idle), so after
// 5 s the offset is that within 1e-5 m. Moved at run time to 0.5 m, it settles at
// 0.5 - 0.062124 m.
TEST(Servo, VerticalSliderSagsAsASpringOfItsFrequencyAndFollowsItsTarget) {
    World world(noSleep());
    const BodyId box = addBox(world, Vector3(0, 2, 0), Vector3(0.2, 0.2, 0.2), 5);
    JointSettings j = jointSettings(JointType::Slider, box, Vector3(0, 2, 0), Vector3::UnitY());
    j.servo = servo(0, 2, 1, 1e4);
    const JointId slider = world.addJoint(j);
    const real sag = kG / std::pow(4 * kPi, 2);
    for (int step = 0; step < 300; ++step) world.step(kDt);
    EXPECT_NEAR(world.jointState(slider).position, -sag, 1e-5);
    world.setServoTarget(slider, 0.5);
    for (int step = 0; step < 300; ++step) world.step(kDt);
    EXPECT_NEAR(world.jointState(slider).position, 0.5 - sag, 1e-5);
    EXPECT_NEAR(world.body(box).getPosition().y(), 2.5 - sag, 1e-5);
}

// A 2 kg arm 1 m long (a box 1 x 0.1 x 0.1 m) held level on a hinge about z at its end,
// both limits at 0 and soft (2 Hz, damping ratio 1): past the limit it is a spring of
// stiffness k = I w^2 with I its moment about the hinge, m (1 + 0.01) / 12 + m / 4 =
// 0.668333 kg m^2, and w = 4 pi. Gravity's torque m g (L/2) cos(theta) = 9.81 cos(theta)
// N m bends it down until k theta balances it: theta = 9.81 cos(theta) / (I w^2), the
// fixed point of that map (0.09255 rad). At a standstill the implicit spring's fixed
// point is the spring's, so after 5 s the angle is -theta within 1e-5 rad.
TEST(SoftLimit, ArmSagsPastItsLimitAsASpringOfItsFrequency) {
    World world(noSleep());
    const BodyId arm = addBox(world, Vector3(0.5, 2, 0), Vector3(0.5, 0.05, 0.05), 2);
    JointSettings j = jointSettings(JointType::Hinge, arm, Vector3(0, 2, 0), Vector3::UnitZ());
    j.limits = JointLimits{0, 0};
    j.limitSpring = JointSpring{2, 1};
    const JointId hinge = world.addJoint(j);
    for (int step = 0; step < 300; ++step) world.step(kDt);
    const real stiffness = (2 * 1.01 / 12 + 2 * 0.25) * std::pow(4 * kPi, 2);
    real theta = 0;
    for (int k = 0; k < 50; ++k) theta = 2 * kG * 0.5 * std::cos(theta) / stiffness;
    EXPECT_NEAR(world.jointState(hinge).position, -theta, 1e-5);
}

TEST(Servo, BadServosAreRefusedAndNothingChanges) {
    Door d(servo(1, 1, 1, 10));
    const auto refused = [&](const JointSettings &j, const std::string &field) { expectJointRefused(d.world, j, field); };
    const JointSettings base = d.world.jointSettings(d.hinge);
    JointSettings j = base;
    j.motor = JointMotor{2, 10};  // a servo and a speed motor
    refused(j, "servo");
    j = base;
    j.type = JointType::Ball;
    refused(j, "servo");
    const auto refusedServo = [&](const JointServo &s, const std::string &field) {
        JointSettings bad = base;
        bad.servo = s;
        refused(bad, field);
    };
    refusedServo(servo(4, 1, 1, 10), "servo.target");  // beyond pi for a hinge
    refusedServo(servo(kNaN, 1, 1, 10), "servo.target");
    refusedServo(servo(1, 0, 1, 10), "servo.frequency");
    refusedServo(servo(1, kInf, 1, 10), "servo.frequency");
    refusedServo(servo(1, 1, -0.5, 10), "servo.dampingRatio");
    refusedServo(servo(1, 1, 1, -1), "servo.maxForce");
    const auto refusedTarget = [&](JointId id, real target, const std::string &field) {
        try {
            d.world.setServoTarget(id, target);
            ADD_FAILURE() << "accepted, expected a refusal of " << field;
        } catch (const InvalidArgument &error) {
            EXPECT_EQ(error.function(), "World::setServoTarget");
            EXPECT_EQ(error.field(), field) << error.what();
        }
    };
    refusedTarget(d.hinge, 4, "target");
    refusedTarget(d.hinge, kNaN, "target");
    EXPECT_EQ(d.world.jointSettings(d.hinge).servo->target, 1);
    JointSettings plain = base;
    plain.servo.reset();
    plain.motor = JointMotor{1, 10};
    refusedTarget(d.world.addJoint(plain), 0.5, "id");  // a speed motor
}

}  // namespace
}  // namespace cyclone::test
