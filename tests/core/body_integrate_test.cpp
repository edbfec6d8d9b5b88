// RigidBody::integrate: the semi-implicit Newton-Euler step, checked against numbers
// worked out by hand for single steps and against closed forms over several step sizes.
#include <gtest/gtest.h>

#include <cmath>

#include "body_test_support.h"
#include "cyclone/body.h"

namespace cyclone_test {
namespace {



// --- Linear motion -----------------------------------------------------------------------

TEST(RigidBodyIntegrate, FallsUnderGravity) {
    RigidBody body;
    body.setAcceleration(0, -10, 0);
    body.integrate(0.5);
    // v = 0 + (-10)(0.5) = -5; the position moves with the new velocity: -5 * 0.5 = -2.5.
    EXPECT_EQ(body.getVelocity(), Vector3(0, -5, 0));
    EXPECT_EQ(body.getPosition(), Vector3(0, -2.5, 0));
    Vector3 a;
    body.getLastFrameAcceleration(&a);
    EXPECT_EQ(a, Vector3(0, -10, 0));
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3(0, -10, 0));
}

TEST(RigidBodyIntegrate, ForceDividedByMassAddsToTheConstantAcceleration) {
    RigidBody body;
    body.setMass(2);
    body.setAcceleration(0, -10, 0);
    body.addForce(Vector3(4, 0, 0));
    body.integrate(0.5);
    // a = (0,-10,0) + (4,0,0)/2 = (2,-10,0); v = a * 0.5 = (1,-5,0); x = v * 0.5.
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3(2, -10, 0));
    EXPECT_EQ(body.getVelocity(), Vector3(1, -5, 0));
    EXPECT_EQ(body.getPosition(), Vector3(0.5, -2.5, 0));
    EXPECT_EQ(body.getTransform().translation(), Vector3(0.5, -2.5, 0));
}

TEST(RigidBodyIntegrate, LastFrameAccelerationIsThatOfTheLastStep) {
    RigidBody body;
    body.setAcceleration(0, -10, 0);
    body.addForce(Vector3(3, 0, 0));
    body.integrate(0.25);
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3(3, -10, 0));
    // The force was used up by the first step; the second sees gravity alone.
    body.integrate(0.25);
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3(0, -10, 0));
    // v = (3,-10,0)(0.25) + (0,-10,0)(0.25) = (0.75, -5, 0).
    EXPECT_EQ(body.getVelocity(), Vector3(0.75, -5, 0));
}

TEST(RigidBodyIntegrate, InfiniteMassIgnoresForces) {
    RigidBody body;
    body.setInverseMass(0);
    body.addForce(Vector3(100, -50, 25));
    body.integrate(1);
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3::Zero());
    EXPECT_EQ(body.getVelocity(), Vector3::Zero());
    EXPECT_EQ(body.getPosition(), Vector3::Zero());
}

TEST(RigidBodyIntegrate, ConstantVelocityMovesInAStraightLine) {
    RigidBody body;
    body.setCanSleep(false);
    body.setPosition(1, 1, 1);
    body.setVelocity(2, -1, 0.5);
    body.integrate(0.5);
    body.integrate(1.5);
    // No force: x = x0 + v t with t = 2 s.
    EXPECT_EQ(body.getVelocity(), Vector3(2, -1, 0.5));
    EXPECT_EQ(body.getPosition(), Vector3(5, -1, 2));
}

// --- Angular motion ----------------------------------------------------------------------

TEST(RigidBodyIntegrate, TorqueAboutZ) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 1, 4));
    body.addTorque(Vector3(0, 0, 2));
    body.integrate(0.5);
    // w_z = (2 N m / 4 kg m^2)(0.5 s) = 0.25 rad/s.
    EXPECT_TRUE(near(body.getRotation(), Vector3(0, 0, 0.25)));
    // q + 1/2 dt (0,w) q with q = 1: (1,0,0,0) + 1/2 (0, 0,0,0.125) = (1, 0, 0, 0.0625),
    // then divided by its length sqrt(1 + 0.0625^2).
    const real length = std::sqrt(1 + 0.0625 * 0.0625);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(1 / length, 0, 0, 0.0625 / length)));
    // No force: no linear motion.
    EXPECT_EQ(body.getVelocity(), Vector3::Zero());
    EXPECT_EQ(body.getPosition(), Vector3::Zero());
}

TEST(RigidBodyIntegrate, TorqueUsesTheWorldInertiaTensor) {
    RigidBody body;
    body.setInertiaTensor(diag(2, 4, 8));
    body.setOrientation(0.5, 0.5, 0.5, 0.5);  // body x -> world y, y -> z, z -> x
    // In world space the tensor is diag(8, 2, 4): torque (8, 2, 4) for 1 s gives (1, 1, 1).
    // (The body-space tensor would give (4, 0.5, 0.5).)
    body.addTorque(Vector3(8, 2, 4));
    body.integrate(1);
    EXPECT_TRUE(near(body.getRotation(), Vector3(1, 1, 1)));
}

TEST(RigidBodyIntegrate, OrientationOfARotatedSpinningBody) {
    RigidBody body;
    body.setOrientation(kHalfSqrt2, 0, 0, kHalfSqrt2);  // 90 deg about z
    body.setRotation(0, 0, 1);
    body.integrate(0.5);
    // With c = 1/sqrt2: (0,0,0,0.5)(c,0,0,c) = (-0.5c, 0, 0, 0.5c), so
    // q' = (c,0,0,c) + 1/2 (-0.5c,0,0,0.5c) = c (0.75, 0, 0, 1.25), normalised
    // (0.75, 0, 0, 1.25) / sqrt(2.125).
    const real length = std::sqrt(2.125);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(0.75 / length, 0, 0, 1.25 / length)));
    // Its rotation matrix: cos = w^2 - z^2 = -1/2.125, sin = 2 w z = 1.875/2.125.
    const real cosine = -1 / 2.125, sine = 1.875 / 2.125;
    Matrix3 expected;
    expected << cosine, -sine, 0, sine, cosine, 0, 0, 0, 1;
    Matrix3 m;
    body.getOrientation(&m);
    EXPECT_TRUE(near(m, expected));
    EXPECT_TRUE(near(body.getTransform().linear(), expected));
}

TEST(RigidBodyIntegrate, AngularVelocityIsInWorldSpace) {
    RigidBody body;
    body.setOrientation(kHalfSqrt2, kHalfSqrt2, 0, 0);  // 90 deg about x
    body.setRotation(0, 0, 1);
    body.integrate(1);
    // (0,0,0,1)(c,c,0,0) = (0, (0,0,c) + (0,0,1)x(c,0,0)) = (0, 0, c, c), so
    // q' = c (1, 1, 0.5, 0.5), normalised by sqrt(2.5). (A body-space w, q (0,w),
    // would give y = -0.5 instead.)
    const real length = std::sqrt(2.5);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(1 / length, 1 / length, 0.5 / length, 0.5 / length)));
}

TEST(RigidBodyIntegrate, OrientationStaysUnitLength) {
    RigidBody body;
    body.setCanSleep(false);
    body.setRotation(3, -2, 5);
    for (int i = 0; i < 100; ++i) body.integrate(0.1);
    EXPECT_NEAR(body.getOrientation().norm(), 1, 1e-12);
}

// --- Damping and order -------------------------------------------------------------------

TEST(RigidBodyIntegrate, LinearDampingHalvesTheVelocityOverOneSecond) {
    RigidBody body;
    body.setLinearDamping(0.5);
    body.setVelocity(2, 0, 0);
    body.integrate(1);
    // v = 2 * 0.5^1 = 1; the position moves with the damped velocity.
    EXPECT_EQ(body.getVelocity(), Vector3(1, 0, 0));
    EXPECT_EQ(body.getPosition(), Vector3(1, 0, 0));
}

TEST(RigidBodyIntegrate, AngularDampingIsAPowerOfTheDuration) {
    RigidBody body;
    body.setAngularDamping(0.25);
    body.setRotation(0, 0, 4);
    body.integrate(0.5);
    // w = 4 * 0.25^0.5 = 2.
    EXPECT_TRUE(near(body.getRotation(), Vector3(0, 0, 2)));
}

TEST(RigidBodyIntegrate, DampingFollowsChangesOfDampingAndDuration) {
    // integrate() keeps its damping factors while duration and damping stay the same;
    // each change must give the new power. (Awake throughout: slow, it would fall asleep.)
    RigidBody body;
    body.setCanSleep(false);
    body.setDamping(0.5, 0.25);
    body.setVelocity(16, 0, 0);
    body.setRotation(0, 0, 16);
    body.integrate(1);
    // v = 16 * 0.5 = 8, w = 16 * 0.25 = 4.
    EXPECT_EQ(body.getVelocity(), Vector3(8, 0, 0));
    EXPECT_EQ(body.getRotation(), Vector3(0, 0, 4));
    body.integrate(2);
    // A longer step: v = 8 * 0.5^2 = 2, w = 4 * 0.25^2 = 0.25.
    EXPECT_EQ(body.getVelocity(), Vector3(2, 0, 0));
    EXPECT_EQ(body.getRotation(), Vector3(0, 0, 0.25));
    body.setLinearDamping(0.25);
    body.integrate(2);
    // New linear damping, same duration: v = 2 * 0.25^2 = 0.125; w = 0.25 * 0.25^2.
    EXPECT_EQ(body.getVelocity(), Vector3(0.125, 0, 0));
    EXPECT_EQ(body.getRotation(), Vector3(0, 0, 0.015625));
    body.setAngularDamping(1);
    body.integrate(2);
    // New angular damping: w = 0.015625 * 1 = 0.015625; v = 0.125 * 0.0625.
    EXPECT_EQ(body.getVelocity(), Vector3(0.0078125, 0, 0));
    EXPECT_EQ(body.getRotation(), Vector3(0, 0, 0.015625));
}

TEST(RigidBodyIntegrate, DampingZeroStopsTheBodyAtOnce) {
    RigidBody body;
    body.setDamping(0, 0);
    body.setVelocity(3, 0, 0);
    body.setRotation(0, 2, 0);
    body.setAcceleration(0, -10, 0);
    body.integrate(0.1);
    // 0^0.1 = 0: nothing moves.
    EXPECT_EQ(body.getVelocity(), Vector3::Zero());
    EXPECT_EQ(body.getRotation(), Vector3::Zero());
    EXPECT_EQ(body.getPosition(), Vector3::Zero());
}

TEST(RigidBodyIntegrate, VelocityThenDampingThenPosition) {
    RigidBody body;
    body.setDamping(0.5, 0.25);
    body.setAcceleration(10, 0, 0);
    body.addTorque(Vector3(0, 0, 8));
    body.integrate(1);
    // Velocity first, then damping: (0 + 10 * 1) * 0.5 = 5 (damping first would give 10).
    EXPECT_EQ(body.getVelocity(), Vector3(5, 0, 0));
    // Position from the new velocity: 5 * 1 (the old velocity would give 0).
    EXPECT_EQ(body.getPosition(), Vector3(5, 0, 0));
    // Angular likewise: (0 + 8/1 * 1) * 0.25 = 2.
    EXPECT_TRUE(near(body.getRotation(), Vector3(0, 0, 2)));
    // The acceleration reported is before damping.
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3(10, 0, 0));
}

// --- Accumulators and zero duration ------------------------------------------------------

TEST(RigidBodyIntegrate, AccumulatorsAreClearedAfterEachStep) {
    RigidBody body;
    body.addForce(Vector3(1, 0, 0));
    body.addTorque(Vector3(0, 1, 0));
    body.integrate(1);
    EXPECT_EQ(body.getAccumulatedForce(), Vector3::Zero());
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3::Zero());
    EXPECT_EQ(body.getVelocity(), Vector3(1, 0, 0));
    // The second step adds nothing: the velocities are kept and the body coasts.
    body.integrate(1);
    EXPECT_EQ(body.getVelocity(), Vector3(1, 0, 0));
    EXPECT_TRUE(near(body.getRotation(), Vector3(0, 1, 0)));
    EXPECT_EQ(body.getPosition(), Vector3(2, 0, 0));
}

TEST(RigidBodyIntegrate, ZeroDurationChangesNothing) {
    RigidBody body = busyBody();
    const Snapshot before(body);
    body.integrate(0);
    EXPECT_TRUE(identical(before, Snapshot(body)));
    body.integrate(0, true);
    body.integrate(0, false);
    EXPECT_TRUE(identical(before, Snapshot(body)));
}

TEST(RigidBodyIntegrate, ZeroDurationOnADefaultBodyWithForces) {
    RigidBody body;
    body.setAcceleration(0, -10, 0);
    body.addForce(Vector3(1, 2, 3));
    body.addTorque(Vector3(3, 2, 1));
    const Snapshot before(body);
    body.integrate(0);
    EXPECT_TRUE(identical(before, Snapshot(body)));
}

// --- Several step sizes ------------------------------------------------------------------

// Runs `total` seconds in equal steps of the parameter.
class RigidBodyStepSize : public ::testing::TestWithParam<real> {
protected:
    static constexpr real total = 2;
    real dt() const { return GetParam(); }
    int steps() const { return static_cast<int>(std::lround(total / dt())); }
    void simulate(RigidBody &body) const {
        for (int i = 0; i < steps(); ++i) body.integrate(dt());
    }
};

TEST_P(RigidBodyStepSize, FreeFall) {
    RigidBody body;
    body.setAcceleration(0, -10, 0);
    simulate(body);
    // v_n = -10 n dt; x_n = -10 dt^2 (1 + ... + n) = -10 T (T + dt) / 2 with T = n dt.
    EXPECT_NEAR(body.getVelocity().y(), -10 * total, 1e-9);
    EXPECT_NEAR(body.getPosition().y(), -5 * total * (total + dt()), 1e-9);
    EXPECT_EQ(body.getPosition().x(), 0);
    EXPECT_EQ(body.getPosition().z(), 0);
}

TEST_P(RigidBodyStepSize, DampingDependsOnElapsedTimeOnly) {
    RigidBody body;
    body.setLinearDamping(0.5);
    body.setVelocity(4, 0, 0);
    simulate(body);
    // v = 4 * 0.5^2 = 1 whatever the step; x = sum_k 4 r^k dt with r = 0.5^dt.
    EXPECT_NEAR(body.getVelocity().x(), 1, 1e-11);
    const real r = std::pow(0.5, dt());
    EXPECT_NEAR(body.getPosition().x(), 4 * dt() * r * (1 - std::pow(r, steps())) / (1 - r), 1e-9);
}

TEST_P(RigidBodyStepSize, ConstantTorque) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 1, 4));
    real angle = 0;
    for (int i = 1; i <= steps(); ++i) {
        body.addTorque(Vector3(0, 0, 2));
        body.integrate(dt());
        // alpha = 2/4 = 0.5 rad/s^2; each step turns by 2 atan(w_i dt / 2) about z
        // (q' = q (1, 0, 0, w dt / 2), normalised).
        angle += 2 * std::atan(0.5 * i * dt() * dt() / 2);
    }
    EXPECT_NEAR(body.getRotation().z(), 0.5 * total, 1e-9);
    EXPECT_NEAR(body.getRotation().head<2>().norm(), 0, 1e-15);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(std::cos(angle / 2), 0, 0, std::sin(angle / 2)), 1e-9));
}

TEST_P(RigidBodyStepSize, ConstantSpin) {
    RigidBody body;
    body.setRotation(0, 0, 1);
    simulate(body);
    // Each step turns by 2 atan(dt / 2) (the first-order update slightly undershoots).
    const real angle = 2 * steps() * std::atan(dt() / 2);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(std::cos(angle / 2), 0, 0, std::sin(angle / 2)), 1e-9));
    EXPECT_NEAR(angle, total, total * dt() * dt() / 12 + 1e-12);
}

TEST_P(RigidBodyStepSize, MotionAverageOfABodyAtRest) {
    RigidBody body;
    body.setCanSleep(false);  // the average is kept even when the body may not sleep
    simulate(body);
    // b = 0.5^dt per step: the start value 0.02 becomes 0.02 * 0.5^T = 0.005.
    EXPECT_NEAR(body.getSleepAverage(), 0.02 * 0.25, 1e-14);
    EXPECT_TRUE(body.getAwake());
}

INSTANTIATE_TEST_SUITE_P(Steps, RigidBodyStepSize, ::testing::Values(0.001, 1.0 / 60, 0.02, 0.1, 0.25, 0.5),
                         [](const ::testing::TestParamInfo<real> &info) {
                             return "dt" + std::to_string(static_cast<int>(std::lround(info.param * 1e4)));
                         });

}  // namespace
}  // namespace cyclone_test
