// RigidBody::applyGyroscopicStep: implicit steps of Euler's torque-free equations
// (backward Euler as Bullet, the implicit midpoint rule), checked against steps worked
// out by hand, against the cases where the gyroscopic term vanishes, and against the
// conservation laws of a torque-free body.
#include <gtest/gtest.h>

#include <cmath>

#include "body_test_support.h"
#include "cyclone/body.h"

namespace cyclone_test {
namespace {

using cyclone::GyroscopicStep;




// I = diag(1, 2, 3), w = (1, 1, 0), h = 0.1, body frame = world frame.
// I w = (1, 2, 0); w x I w = (0, 0, 1); residual f = h w x I w = (0, 0, 0.1).
// [w]x I - [I w]x = [0 0 3; 0 0 -3; -1 2 0] - [0 0 2; 0 0 -1; -2 1 0] = [0 0 1; 0 0 -2; 1 1 0],
// so J = I + 0.1 (that) = [1 0 0.1; 0 2 -0.2; 0.1 0.1 3].
// J d = f: d_x = -0.1 d_z, d_y = 0.1 d_z, (-0.01 + 0.01 + 3) d_z = 0.1, so d = (-1/300, 1/300, 1/30)
// and w' = w - d = (301/300, 299/300, -1/30). Energy 2E: 3 before, 2.9967 after: no rescale.
TEST(RigidBodyGyroscopic, BackwardEulerNewtonStepWorkedByHand) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 2, 3));
    body.setRotation(1, 1, 0);
    body.applyGyroscopicStep(GyroscopicStep::BackwardEuler, 0.1);
    EXPECT_TRUE(near(body.getRotation(), Vector3(301.0 / 300, 299.0 / 300, -1.0 / 30), 1e-14));
    // Only the angular velocity changes.
    EXPECT_EQ(body.getPosition(), Vector3::Zero());
    EXPECT_EQ(body.getOrientation().coeffs(), cyclone::Quaternion::Identity().coeffs());
}

// The same step in a body turned 90 degrees about z (body x -> world y, body y -> world -x):
// world w = R (1, 1, 0) = (-1, 1, 0), and w' = R (301/300, 299/300, -1/30)
// = (-299/300, 301/300, -1/30).
TEST(RigidBodyGyroscopic, WorksInBodySpace) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 2, 3));
    body.setOrientation(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
    body.setRotation(-1, 1, 0);
    body.applyGyroscopicStep(GyroscopicStep::BackwardEuler, 0.1);
    EXPECT_TRUE(near(body.getRotation(), Vector3(-299.0 / 300, 301.0 / 300, -1.0 / 30), 1e-14));
}

// Spinning about a principal axis, w x I w = 0: the residual is zero and w stays exactly.
TEST(RigidBodyGyroscopic, PrincipalAxisSpinIsUnchanged) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 2, 3));
    body.setRotation(0, 5, 0);
    body.applyGyroscopicStep(GyroscopicStep::BackwardEuler, 0.5);
    EXPECT_EQ(body.getRotation(), Vector3(0, 5, 0));
}

// A sphere or a cube: I = c 1, so w x I w = c w x w = 0; nothing to do.
TEST(RigidBodyGyroscopic, IsotropicInertiaIsUnchanged) {
    RigidBody body;
    body.setInertiaTensor(diag(0.4, 0.4, 0.4));
    EXPECT_TRUE(body.hasIsotropicInertia());
    body.setRotation(1, -2, 3);
    body.applyGyroscopicStep(GyroscopicStep::BackwardEuler, 1);
    EXPECT_EQ(body.getRotation(), Vector3(1, -2, 3));
    body.setInertiaTensor(diag(0.4, 0.4, 0.41));
    EXPECT_FALSE(body.hasIsotropicInertia());
}

TEST(RigidBodyGyroscopic, SleepingBodyAndZeroStepAreUnchanged) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 2, 3));
    body.setRotation(1, 1, 0);
    body.applyGyroscopicStep(GyroscopicStep::BackwardEuler, 0);
    EXPECT_EQ(body.getRotation(), Vector3(1, 1, 0));
    body.setAwake(false);
    body.applyGyroscopicStep(GyroscopicStep::BackwardEuler, 0.1);
    EXPECT_EQ(body.getRotation(), Vector3::Zero());
}

// Axisymmetric body I = diag(1, 1, 2), w = (1, 0, 1): Euler's equations give w_z constant
// and (w_x, w_y) turning at Omega = (2 - 1) / 1 * w_z = 1 rad/s, counter-clockwise
// (dw_x/dt = -w_y, dw_y/dt = w_x). The midpoint rule on this linear rotation is the Cayley
// transform: an angle of 2 atan(h Omega / 2) per step, pi/2 for h = 2. So w' = (0, 1, 1).
// Check: m = (0.5, 0.5, 1), I (w' - w) = (-1, 1, 0), h m x I m = 2 (0.5, 0.5, 1) x (0.5, 0.5, 2)
// = 2 (0.5, -0.5, 0) = (1, -1, 0): they cancel.
TEST(RigidBodyGyroscopic, MidpointStepWorkedByHand) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 1, 2));
    body.setRotation(1, 0, 1);
    body.applyGyroscopicStep(GyroscopicStep::Midpoint, 2);
    EXPECT_TRUE(near(body.getRotation(), Vector3(0, 1, 1), 1e-13));
}

// The midpoint rule keeps the quadratic invariants w.I w and |I w| whatever the step.
TEST(RigidBodyGyroscopic, MidpointKeepsEnergyAndMomentumSize) {
    RigidBody body;
    body.setInertiaTensor(diag(0.08, 0.068, 0.014));
    body.setOrientation(0.9, 0.1, -0.3, 0.2);
    body.setRotation(0.3, 5, -0.2);
    const real energy = kineticEnergy(body);
    const real momentum = angularMomentum(body).norm();
    for (int i = 0; i < 100; ++i) body.applyGyroscopicStep(GyroscopicStep::Midpoint, 1.0 / 60);
    EXPECT_NEAR(kineticEnergy(body), energy, 1e-12 * energy);
    EXPECT_NEAR(angularMomentum(body).norm(), momentum, 1e-12 * momentum);
}

TEST(RigidBodyGyroscopic, RefusesBadInputAndChangesNothing) {
    RigidBody body;
    body.setInertiaTensor(diag(1, 2, 3));
    body.setRotation(1, 1, 0);
    for (real bad : {real(-0.1), real(NAN), real(INFINITY)}) {
        try {
            body.applyGyroscopicStep(GyroscopicStep::Midpoint, bad);
            FAIL() << "accepted duration " << bad;
        } catch (const cyclone::InvalidArgument &e) {
            EXPECT_EQ(e.function(), "RigidBody::applyGyroscopicStep");
            EXPECT_EQ(e.field(), "duration");
        }
    }
    const auto unknown = static_cast<GyroscopicStep>(7);
    try {
        body.applyGyroscopicStep(unknown, 0.1);
        FAIL() << "accepted step 7";
    } catch (const cyclone::InvalidArgument &e) {
        EXPECT_EQ(e.field(), "step");
        EXPECT_NE(e.problem().find("7"), std::string::npos);
    }
    EXPECT_THROW(body.setGyroscopicStep(unknown), cyclone::InvalidArgument);
    EXPECT_EQ(body.getGyroscopicStep(), GyroscopicStep::None);
    EXPECT_EQ(body.getRotation(), Vector3(1, 1, 0));
}

// integrate() with a step set is that step followed by the seed's integration.
TEST(RigidBodyGyroscopic, IntegrateAppliesTheStepFirst) {
    for (GyroscopicStep step : {GyroscopicStep::BackwardEuler, GyroscopicStep::Midpoint}) {
        RigidBody a;
        a.setInertiaTensor(diag(1, 2, 3));
        a.setRotation(1, 1, 0.5);
        a.addTorque(Vector3(0.3, 0, -0.2));
        RigidBody b = a;
        EXPECT_EQ(a.getGyroscopicStep(), GyroscopicStep::None);
        a.setGyroscopicStep(step);
        EXPECT_EQ(a.getGyroscopicStep(), step);
        a.integrate(0.1);
        b.applyGyroscopicStep(step, 0.1);
        b.integrate(0.1);
        EXPECT_EQ(a.getRotation(), b.getRotation());
        EXPECT_EQ(a.getOrientation().coeffs(), b.getOrientation().coeffs());
    }
}

// Neither form ever gains energy: steps up to h |w| = 1700 in random directions and
// orientations of an elongated body (where a single Newton step can overshoot).
TEST(RigidBodyGyroscopic, NeverGainsEnergy) {
    unsigned seed = 12345;
    auto uniform = [&seed]() {
        seed = seed * 1103515245u + 12345u;
        return real((seed >> 8) & 0xffff) / 0xffff * 2 - 1;
    };
    for (GyroscopicStep step : {GyroscopicStep::BackwardEuler, GyroscopicStep::Midpoint}) {
        for (int i = 0; i < 2000; ++i) {
            RigidBody body;
            body.setInertiaTensor(diag(0.02, 0.5, 0.9));
            body.setOrientation(uniform(), uniform(), uniform(), uniform());
            body.setRotation(10 * uniform(), 10 * uniform(), 10 * uniform());
            const real h = std::pow(10.0, 2 * uniform());  // 0.01 .. 100 s
            const real before = kineticEnergy(body);
            body.applyGyroscopicStep(step, h);
            EXPECT_LE(kineticEnergy(body), before * (1 + 1e-12)) << "case " << i << ", h " << h;
        }
    }
}

// A torque-free box 0.1 x 0.4 x 0.9 m (1 kg) spun at 5 rad/s about its intermediate axis
// (y) with a 0.1 rad/s disturbance: the Dzhanibekov effect. Linearising Euler's equations
// about the y spin, the disturbance grows at lambda = w_y sqrt((Ix - Iy)(Iy - Iz) / (Ix Iz))
// = 3.85 /s, so from 0.1 / 5 it reaches order one within ln(50) / 3.85 = 1 s and the body
// turns upside down (its y axis against world y) several times in 10 s. The seed keeps
// world w constant, so the body keeps spinning about world y and never turns over.
struct Spin {
    real minimumUpright = 1;  // least (body y).(world y) over the run
    real momentumDrift = 0;   // largest |L(t) - L(0)| / |L(0)|
    real energyDrift = 0;     // largest |E(t) - E(0)| / E(0)
};

Spin dzhanibekov(GyroscopicStep step, real h) {
    RigidBody body;
    body.setInertiaTensor(diag((0.16 + 0.81) / 12, (0.01 + 0.81) / 12, (0.01 + 0.16) / 12));
    body.setCanSleep(false);
    body.setGyroscopicStep(step);
    body.setRotation(0.1, 5, 0.1);
    const Vector3 momentum = angularMomentum(body);
    const real energy = kineticEnergy(body);
    Spin spin;
    const int steps = static_cast<int>(std::lround(10 / h));
    for (int i = 0; i < steps; ++i) {
        body.integrate(h);
        spin.minimumUpright = std::min(spin.minimumUpright, body.getDirectionInWorldSpace(Vector3::UnitY()).y());
        spin.momentumDrift = std::max(spin.momentumDrift, (angularMomentum(body) - momentum).norm() / momentum.norm());
        spin.energyDrift = std::max(spin.energyDrift, std::abs(kineticEnergy(body) - energy) / energy);
    }
    return spin;
}

TEST(RigidBodyGyroscopic, IntermediateAxisFlipsOnlyWithAGyroscopicStep) {
    EXPECT_GT(dzhanibekov(GyroscopicStep::None, 1.0 / 240).minimumUpright, 0.99);
    EXPECT_LT(dzhanibekov(GyroscopicStep::BackwardEuler, 1.0 / 240).minimumUpright, -0.9);
    EXPECT_LT(dzhanibekov(GyroscopicStep::Midpoint, 1.0 / 240).minimumUpright, -0.9);
}

// A box tumbling about no principal axis, w0 = (1, 2, 3) rad/s. The seed keeps world w, so
// the body turns about w and L = R I R^T w turns about w with it: the part of L0 across w,
// L0 - (L0.n) n with n = w / |w|, is reversed after half a turn, and L has moved by twice
// its length. The gyroscopic step keeps L, at first order: at 240 Hz within a tenth of
// that.
TEST(RigidBodyGyroscopic, SeedTurnsTheMomentumOfATumblingBody) {
    const Matrix3 inertia = diag((0.16 + 0.81) / 12, (0.01 + 0.81) / 12, (0.01 + 0.16) / 12);
    const Vector3 w0(1, 2, 3);
    const Vector3 l0 = inertia * w0;
    const Vector3 n = w0.normalized();
    const real expected = 2 * (l0 - l0.dot(n) * n).norm() / l0.norm();
    auto drift = [&](GyroscopicStep step) {
        RigidBody body;
        body.setInertiaTensor(inertia);
        body.setCanSleep(false);
        body.setGyroscopicStep(step);
        body.setRotation(w0);
        real worst = 0;
        for (int i = 0; i < 2400; ++i) {
            body.integrate(1.0 / 240);
            worst = std::max(worst, (angularMomentum(body) - l0).norm() / l0.norm());
        }
        return worst;
    };
    EXPECT_NEAR(drift(GyroscopicStep::None), expected, 0.01 * expected);
    EXPECT_LT(drift(GyroscopicStep::Midpoint), 0.1 * expected);
}

// Both forms are first order in the world angular momentum: halving the step halves the
// drift (within 25%). The midpoint keeps the energy to roundoff; backward Euler loses it
// at first order too.
TEST(RigidBodyGyroscopic, AngularMomentumConvergesAtFirstOrder) {
    for (GyroscopicStep step : {GyroscopicStep::BackwardEuler, GyroscopicStep::Midpoint}) {
        const Spin coarse = dzhanibekov(step, 1.0 / 240);
        const Spin fine = dzhanibekov(step, 1.0 / 480);
        EXPECT_NEAR(coarse.momentumDrift / fine.momentumDrift, 2, 0.5) << static_cast<int>(step);
    }
    EXPECT_LT(dzhanibekov(GyroscopicStep::Midpoint, 1.0 / 60).energyDrift, 1e-10);
    const Spin coarse = dzhanibekov(GyroscopicStep::BackwardEuler, 1.0 / 240);
    const Spin fine = dzhanibekov(GyroscopicStep::BackwardEuler, 1.0 / 480);
    EXPECT_NEAR(coarse.energyDrift / fine.energyDrift, 2, 0.5);
}

}  // namespace
}  // namespace cyclone_test
