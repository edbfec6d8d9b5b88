// The World's "momentum-conserving" integrator: a torque-free body keeps its angular
// momentum and energy, its attitude converges at second order to the torque-free motion
// (a converged RK4 reference, and the symmetric top's closed form), contacts still hold
// it, and bad settings are refused.
#include <algorithm>
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

WorldSettings conserving(int substeps = 4) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    settings.sleep = false;
    settings.integrator = Integrator::MomentumConserving;
    settings.substeps = substeps;
    return settings;
}

// The Dzhanibekov box: 0.1 x 0.4 x 0.9 m, 1 kg, spun near its intermediate (y) axis.
const Vector3 kHalfExtents(0.05, 0.2, 0.45);
const Vector3 kSpin(0.1, 5, 0.1);

Vector3 boxInertia() { return Vector3(0.16 + 0.81, 0.01 + 0.81, 0.01 + 0.16) / 12; }

BodySettings spinningBox(const Vector3 &rotation) {
    BodySettings s;
    s.shape = Shape::box(kHalfExtents);
    s.rotation = rotation;
    return s;
}

Vector3 angularMomentum(const RigidBody &body) { return body.getInertiaTensorWorld() * body.getRotation(); }

real kineticEnergy(const RigidBody &body) {
    const Vector3 w = body.getRotation();
    return 0.5 * w.dot(body.getInertiaTensorWorld() * w);
}

// Euler's equations I dw/dt = -w x I w in body space and dq/dt = q (0, w) / 2, by RK4: a
// fourth-order reference, converged at h = 1e-4 s far below the errors measured here.
Quaternion torqueFreeReference(const Vector3 &inertia, const Vector3 &w0, real seconds) {
    struct State {
        Quaternion q;
        Vector3 w;
    };
    const auto derivative = [&](const State &s) {
        State d;
        d.w = -(s.w.cross(inertia.cwiseProduct(s.w))).cwiseQuotient(inertia);
        d.q.coeffs() = 0.5 * (s.q * Quaternion(0, s.w.x(), s.w.y(), s.w.z())).coeffs();
        return d;
    };
    const auto plus = [](const State &s, const State &d, real k) {
        State r;
        r.q.coeffs() = s.q.coeffs() + k * d.q.coeffs();
        r.w = s.w + k * d.w;
        return r;
    };
    const real h = 1e-4;
    State s{Quaternion::Identity(), w0};
    for (int i = 0; i < static_cast<int>(std::lround(seconds / h)); ++i) {
        const State k1 = derivative(s), k2 = derivative(plus(s, k1, h / 2)), k3 = derivative(plus(s, k2, h / 2)),
                    k4 = derivative(plus(s, k3, h));
        s.q.coeffs() += h / 6 * (k1.q.coeffs() + 2 * k2.q.coeffs() + 2 * k3.q.coeffs() + k4.q.coeffs());
        s.w += h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w);
        s.q.normalize();
    }
    return s.q;
}

// 10 s at 60 and 120 Hz (4 sub-steps): |dL| / |L| and |dE| / E stay below 1e-9 at every
// step, while the box flips about its intermediate axis.
TEST(MomentumConserving, DzhanibekovBoxKeepsMomentumAndEnergy) {
    for (real dt : {1.0 / 60, 1.0 / 120}) {
        WorldFixture f(conserving());
        const BodyId id = f.world.addBody(spinningBox(kSpin));
        const Vector3 l0 = angularMomentum(f.world.body(id));
        const real e0 = kineticEnergy(f.world.body(id));
        real momentumDrift = 0, energyDrift = 0, lowestY = 1;
        for (int i = 0; i < static_cast<int>(std::lround(10 / dt)); ++i) {
            f.world.step(dt);
            const RigidBody &body = f.world.body(id);
            momentumDrift = std::max(momentumDrift, (angularMomentum(body) - l0).norm() / l0.norm());
            energyDrift = std::max(energyDrift, std::abs(kineticEnergy(body) - e0) / e0);
            lowestY = std::min(lowestY, body.getDirectionInWorldSpace(Vector3::UnitY()).y());
        }
        EXPECT_LE(momentumDrift, 1e-9) << "dt = " << dt;
        EXPECT_LE(energyDrift, 1e-9) << "dt = " << dt;
        EXPECT_LT(lowestY, -0.9) << "dt = " << dt;  // it flipped
    }
}

real attitudeError(real dt, const Quaternion &reference) {
    WorldFixture f(conserving());
    const BodyId id = f.world.addBody(spinningBox(kSpin));
    f.simulate(10, dt);
    return f.world.body(id).getOrientation().angularDistance(reference);
}

// Against the converged reference after 10 s: within 0.01 rad at 60 Hz, and second order,
// so halving the step divides the error by about 4.
TEST(MomentumConserving, AttitudeConvergesAtSecondOrder) {
    const Quaternion reference = torqueFreeReference(boxInertia(), kSpin, 10);
    const real e60 = attitudeError(1.0 / 60, reference);
    const real e120 = attitudeError(1.0 / 120, reference);
    const real e240 = attitudeError(1.0 / 240, reference);
    EXPECT_LE(e60, 0.01);
    EXPECT_NEAR(e60 / e120, 4, 0.5);
    EXPECT_NEAR(e120 / e240, 4, 0.5);
}

// A free body in the World moves exactly as a RigidBody given the same rotation step over
// each sub-step: the World adds nothing (no gyroscopic step, no correction).
TEST(MomentumConserving, WorldMatchesTheCoreStep) {
    WorldFixture f(conserving());
    const BodyId id = f.world.addBody(spinningBox(Vector3(1, 2, 3)));
    RigidBody reference = f.world.body(id);
    EXPECT_EQ(reference.getRotationStep(), RotationStep::MomentumConserving);
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        for (int k = 0; k < 4; ++k) reference.integrate(kDt / 4, false);
    }
    const RigidBody &body = f.world.body(id);
    EXPECT_LT((body.getRotation() - reference.getRotation()).norm(), 1e-12);
    EXPECT_LT((body.getOrientation().coeffs() - reference.getOrientation().coeffs()).norm(), 1e-12);
    EXPECT_EQ(f.world.stats().gyroscopicBodies, 0);
}

// A symmetric top (a box 0.4 x 0.4 x 1 m, I = diag(a, a, c)) moves in closed form:
// R(t) = Rot(L, |L| t / a) R0 Rot(e3, (1/c - 1/a) L3 t), L3 the momentum along its axis.
real topError(real dt) {
    const Vector3 half(0.2, 0.2, 0.5);
    const real a = (0.16 + 1.0) / 12, c = (0.16 + 0.16) / 12;
    WorldFixture f(conserving());
    BodySettings s;
    s.shape = Shape::box(half);
    s.rotation = Vector3(0.5, -0.3, 4);
    const BodyId id = f.world.addBody(s);
    const Vector3 l = angularMomentum(f.world.body(id));
    const real seconds = 5;
    f.simulate(seconds, dt);
    const Quaternion precession(Eigen::AngleAxis<real>(l.norm() * seconds / a, l.normalized()));
    const Quaternion spin(Eigen::AngleAxis<real>((1 / c - 1 / a) * l.z() * seconds, Vector3::UnitZ()));
    return f.world.body(id).getOrientation().angularDistance(precession * spin);
}

TEST(MomentumConserving, SymmetricTopPrecessesAsInClosedForm) {
    const real e30 = topError(1.0 / 30), e60 = topError(1.0 / 60);
    // The top precesses |L| t / a = 6.2 rad in 5 s; a wrong closed form would miss by O(1).
    EXPECT_LT(e60, 0.01);
    EXPECT_NEAR(e30 / e60, 4, 0.5);
}

// The box of Integrators.GyroscopicStepAgreesWithContacts (off-diagonal inertia) spinning
// on a frictionless floor: the contacts keep it down, and normal forces on a resting box
// do no work, so its energy cannot grow.
TEST(MomentumConserving, ContactsHoldASpinningBox) {
    WorldSettings settings;
    settings.sleep = false;
    settings.integrator = Integrator::MomentumConserving;
    WorldFixture f(settings);
    f.ground(0);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.45, 0.1, 0.2));
    Matrix3 inertia;
    inertia << 0.2 / 12, 0.01, 0, 0.01, 0.97 / 12, 0, 0, 0, 0.85 / 12;
    s.inertia = inertia;
    s.position = Vector3(0, 0.1, 0);
    s.rotation = Vector3(0, 6, 0);
    s.material.friction = 0;
    const BodyId id = f.world.addBody(s);
    f.simulate(0.1);
    const real energy = f.world.kineticEnergy();
    for (int i = 0; i < 600; ++i) {
        f.world.step(kDt);
        EXPECT_LE(f.world.kineticEnergy(), energy * (1 + 1e-6)) << "step " << i;
        EXPECT_NEAR(f.position(id).y(), 0.1, 0.001) << "step " << i;
    }
}

// Gravity and contacts act as with the seed: a box dropped on the ground comes to rest on it.
TEST(MomentumConserving, DroppedBoxRestsOnTheGround) {
    WorldSettings settings;
    settings.integrator = Integrator::MomentumConserving;
    WorldFixture f(settings);
    f.ground();
    BodySettings s = spinningBox(Vector3(0.3, 0, 0.2));
    s.position = Vector3(0, 1, 0);
    const BodyId id = f.world.addBody(s);
    f.simulate(5);
    EXPECT_FALSE(f.awake(id));
    // Resting on one of its faces: its centre one half-extent above the ground.
    const real y = f.position(id).y();
    const real gap = std::min({std::abs(y - 0.05), std::abs(y - 0.2), std::abs(y - 0.45)});
    EXPECT_LT(gap, 0.001) << "y = " << y;
}

TEST(MomentumConserving, UnknownIntegratorIsRefused) {
    World world(conserving());
    WorldSettings bad = conserving();
    bad.integrator = static_cast<Integrator>(9);
    try {
        world.setSettings(bad);
        FAIL() << "accepted integrator 9";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::setSettings");
        EXPECT_EQ(e.field(), "integrator");
        EXPECT_NE(e.problem().find("9"), std::string::npos);
    }
    EXPECT_EQ(world.settings().integrator, Integrator::MomentumConserving);
    EXPECT_THROW(World{bad}, InvalidArgument);
}

// Switching the integrator switches the bodies' rotation step.
TEST(MomentumConserving, SetSettingsSwitchesTheBodies) {
    WorldFixture f(conserving());
    const BodyId id = f.world.addBody(spinningBox(kSpin));
    EXPECT_EQ(f.world.body(id).getRotationStep(), RotationStep::MomentumConserving);
    WorldSettings seed = conserving();
    seed.integrator = Integrator::NewtonEuler;
    f.world.setSettings(seed);
    EXPECT_EQ(f.world.body(id).getRotationStep(), RotationStep::Seed);
    f.simulate(1);
    EXPECT_EQ(f.world.body(id).getRotation(), kSpin);  // the seed keeps w
}

}  // namespace
}  // namespace cyclone::test
