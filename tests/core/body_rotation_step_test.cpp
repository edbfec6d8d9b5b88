// RigidBody's momentum-conserving rotation step (RotationStep::MomentumConserving,
// applyTorqueFreeRotation): the conservation laws of a torque-free body at any step, the
// closed-form motion of a symmetric top, and the order of convergence with and without a
// torque.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "body_test_support.h"
#include "cyclone/body.h"

namespace cyclone_test {
namespace {

using cyclone::RotationStep;


// The box of the Dzhanibekov scene, 0.1 x 0.4 x 0.9 m and 1 kg: I = m (b^2 + c^2) / 12, ...
Vector3 boxInertia() { return Vector3(0.16 + 0.81, 0.01 + 0.81, 0.01 + 0.16) / 12; }

RigidBody spinningBody(const Vector3 &principal, const Vector3 &rotation) {
    RigidBody body;
    body.setInertiaTensor(principal.asDiagonal());
    body.setRotation(rotation);
    body.setRotationStep(RotationStep::MomentumConserving);
    return body;
}



struct Drift {
    real momentum = 0;  // max |L - L0| / |L0|
    real energy = 0;    // max |E - E0| / E0
};

Drift integrateFor(RigidBody &body, real seconds, real h) {
    const Vector3 l0 = angularMomentum(body);
    const real e0 = kineticEnergy(body);
    Drift drift;
    const int steps = static_cast<int>(std::lround(seconds / h));
    for (int i = 0; i < steps; ++i) {
        body.integrate(h, false);
        drift.momentum = std::max(drift.momentum, (angularMomentum(body) - l0).norm() / l0.norm());
        drift.energy = std::max(drift.energy, std::abs(kineticEnergy(body) - e0) / e0);
    }
    return drift;
}

TEST(RigidBodyRotationStep, SeedIsTheDefault) {
    RigidBody body;
    EXPECT_EQ(body.getRotationStep(), RotationStep::Seed);
}

// A torque-free body keeps L and E: the box spun near its intermediate axis, which flips
// over every few seconds, for 10 s at 60 and 120 Hz.
TEST(RigidBodyRotationStep, TorqueFreeBoxKeepsMomentumAndEnergy) {
    for (real h : {1.0 / 60, 1.0 / 120}) {
        RigidBody body = spinningBody(boxInertia(), Vector3(0.1, 5, 0.1));
        const Drift drift = integrateFor(body, 10, h);
        EXPECT_LE(drift.momentum, 1e-9) << "h = " << h;
        EXPECT_LE(drift.energy, 1e-9) << "h = " << h;
        // It did flip: the body's y axis, along L at the start, turned away from it.
        EXPECT_LT(body.getDirectionInWorldSpace(Vector3::UnitY()).y(), 0.9) << "h = " << h;
    }
}

// Whatever the step: at h |w| of about 6 and 60 (steps of 1 s and 10 s), where Newton's
// method from L_b may fail and the step is then split, both are still kept.
TEST(RigidBodyRotationStep, HugeStepsKeepMomentumAndEnergy) {
    for (real h : {1.0, 10.0}) {
        RigidBody body = spinningBody(boxInertia(), Vector3(1, 5, -3));
        const Drift drift = integrateFor(body, 10 * h, h);
        EXPECT_LE(drift.momentum, 1e-9) << "h = " << h;
        EXPECT_LE(drift.energy, 1e-9) << "h = " << h;
    }
}

// A torque-free symmetric top, I = diag(a, a, c), moves in closed form: with L the world
// angular momentum and L3 its (constant) component on the body's symmetry axis,
// R(t) = Rot(L, |L| t / a) R0 Rot(e3, (1/c - 1/a) L3 t): the body's angular velocity in
// body space is L_b / a + (1/c - 1/a) L3 e3 = I^-1 L_b, as it must be.
Quaternion symmetricTop(const Vector3 &principal, const Quaternion &q0, const Vector3 &worldMomentum, real t) {
    const real a = principal.x(), c = principal.z();
    const real l3 = (q0.conjugate() * worldMomentum).z();
    const Quaternion precession(Eigen::AngleAxis<real>(worldMomentum.norm() * t / a, worldMomentum.normalized()));
    const Quaternion spin(Eigen::AngleAxis<real>((1 / c - 1 / a) * l3 * t, Vector3::UnitZ()));
    return precession * q0 * spin;
}

real topError(real h) {
    const Vector3 principal(1, 1, 2.5);
    const Quaternion q0(Eigen::AngleAxis<real>(0.4, Vector3(1, 2, 0.5).normalized()));
    RigidBody body = spinningBody(principal, Vector3::Zero());
    body.setOrientation(q0);
    body.setRotation(q0 * Vector3(0.7, -0.2, 2));  // world space
    const Vector3 momentum = angularMomentum(body);
    const real seconds = 4;
    const int steps = static_cast<int>(std::lround(seconds / h));
    for (int i = 0; i < steps; ++i) body.integrate(h, false);
    return body.getOrientation().angularDistance(symmetricTop(principal, q0, momentum, seconds));
}

// Second order: halving the step divides the error by 4 (by 2^2, to within 10%). The
// body precesses by |L| t / a = 20.2 rad in the 4 s; at h = 1/60 it is within a
// thousandth of that (an error in the closed form would show as one of order 1).
TEST(RigidBodyRotationStep, SymmetricTopFollowsItsClosedFormAtSecondOrder) {
    const real e60 = topError(1.0 / 60), e120 = topError(1.0 / 120), e240 = topError(1.0 / 240);
    EXPECT_LT(e60, 0.0202);
    EXPECT_NEAR(e60 / e120, 4, 0.4);
    EXPECT_NEAR(e120 / e240, 4, 0.4);
}

// Torque as half kicks around the torque-free motion. A body of isotropic inertia I = 1
// under a constant torque 1 N m about z from w0 = 1 rad/s turns by w0 t + t^2 / 2: 4 rad
// after 2 s. The seed gives the whole impulse before turning, the error first order
// (halving the step halves it); the half kicks make it second order.
real turnError(RotationStep step, real h) {
    RigidBody body;
    body.setRotationStep(step);
    body.setRotation(0, 0, 1);
    const real seconds = 2;
    const int steps = static_cast<int>(std::lround(seconds / h));
    for (int i = 0; i < steps; ++i) {
        body.addTorque(Vector3(0, 0, 1));
        body.integrate(h, false);
    }
    const real expected = 1 * seconds + seconds * seconds / 2;
    const Quaternion exact(Eigen::AngleAxis<real>(expected, Vector3::UnitZ()));
    return body.getOrientation().angularDistance(exact);
}

TEST(RigidBodyRotationStep, ConstantTorqueIsSecondOrder) {
    const real h = 1.0 / 60;
    EXPECT_NEAR(turnError(RotationStep::MomentumConserving, h) / turnError(RotationStep::MomentumConserving, h / 2), 4,
                0.4);
    EXPECT_NEAR(turnError(RotationStep::Seed, h) / turnError(RotationStep::Seed, h / 2), 2, 0.2);
    // And the angular velocity is the exact w0 + t.
    RigidBody body;
    body.setRotationStep(RotationStep::MomentumConserving);
    body.setRotation(0, 0, 1);
    for (int i = 0; i < 120; ++i) {
        body.addTorque(Vector3(0, 0, 1));
        body.integrate(h, false);
    }
    EXPECT_NEAR(body.getRotation().z(), 3, 1e-12);
}

// The linear motion is the seed's: a thrown body under gravity moves as with RotationStep::Seed.
TEST(RigidBodyRotationStep, LinearMotionIsTheSeeds) {
    RigidBody seed, conserving;
    conserving.setRotationStep(RotationStep::MomentumConserving);
    for (RigidBody *body : {&seed, &conserving}) {
        body->setAcceleration(0, -9.81, 0);
        body->setVelocity(3, 4, 0);
        body->setDamping(0.9, 1);
        for (int i = 0; i < 60; ++i) body->integrate(1.0 / 60, false);
    }
    EXPECT_EQ(seed.getPosition(), conserving.getPosition());
    EXPECT_EQ(seed.getVelocity(), conserving.getVelocity());
}

// A principal-axis spin of a cube-like body turns it by w t about that axis; the Cayley
// rotation of each step turns it by 2 atan(h w / 2) instead, whose error after n steps is
// n (h w)^3 / 12 to leading order: at w = 2, h = 0.01, 100 steps, 2/3 of a microradian.
TEST(RigidBodyRotationStep, PrincipalSpinTurnsAtItsRate) {
    RigidBody body = spinningBody(Vector3(1, 2, 3), Vector3(0, 2, 0));
    body.applyTorqueFreeRotation(0.5);  // one call, split into no parts: h w = 1
    const real angle = 2 * std::atan(0.5);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(Eigen::AngleAxis<real>(angle, Vector3::UnitY())), 1e-15));
    EXPECT_TRUE(near(body.getRotation(), Vector3(0, 2, 0), 1e-15));
    RigidBody many = spinningBody(Vector3(1, 2, 3), Vector3(0, 2, 0));
    for (int i = 0; i < 100; ++i) many.integrate(0.01, false);
    const real error = many.getOrientation().angularDistance(Quaternion(Eigen::AngleAxis<real>(2, Vector3::UnitY())));
    EXPECT_NEAR(error, 100 * std::pow(0.02, 3) / 12, 1e-8);
}

TEST(RigidBodyRotationStep, SleepingBodyAndZeroDurationAreUnchanged) {
    RigidBody body = spinningBody(boxInertia(), Vector3(1, 2, 3));
    const Snapshot before(body);
    body.applyTorqueFreeRotation(0);
    EXPECT_TRUE(identical(before, Snapshot(body)));
    body.setAwake(false);
    body.setRotation(1, 2, 3);
    const Snapshot asleep(body);
    body.applyTorqueFreeRotation(0.1);
    EXPECT_TRUE(identical(asleep, Snapshot(body)));
}

TEST(RigidBodyRotationStep, BadInputIsRefusedAndChangesNothing) {
    RigidBody body = spinningBody(boxInertia(), Vector3(1, 2, 3));
    const Snapshot before(body);
    for (real bad : {real(-1), real(NAN), real(INFINITY)}) {
        try {
            body.applyTorqueFreeRotation(bad);
            FAIL() << "accepted duration " << bad;
        } catch (const cyclone::InvalidArgument &e) {
            EXPECT_EQ(e.function(), "RigidBody::applyTorqueFreeRotation");
            EXPECT_EQ(e.field(), "duration");
        }
    }
    try {
        body.setRotationStep(static_cast<RotationStep>(7));
        FAIL() << "accepted step 7";
    } catch (const cyclone::InvalidArgument &e) {
        EXPECT_EQ(e.function(), "RigidBody::setRotationStep");
        EXPECT_EQ(e.field(), "step");
        EXPECT_NE(e.problem().find("7"), std::string::npos);
    }
    EXPECT_TRUE(identical(before, Snapshot(body)));
    EXPECT_EQ(body.getRotationStep(), RotationStep::MomentumConserving);
}

}  // namespace
}  // namespace cyclone_test
