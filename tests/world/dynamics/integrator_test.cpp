// The World's integrators: the gyroscopic step applied once per sub-step (prediction and
// integration agree), only to bodies that need it, and springs that never gain energy.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

WorldSettings noGravity(Integrator integrator, int substeps = 4) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    settings.sleep = false;
    settings.integrator = integrator;
    settings.substeps = substeps;
    return settings;
}

BodySettings elongatedBox(const Vector3 &rotation) {
    BodySettings s;
    s.shape = Shape::box(Vector3(0.05, 0.2, 0.45));
    s.rotation = rotation;
    return s;
}

// A free body in a gyroscopic world moves exactly as a RigidBody given the midpoint step
// over each step, then integrated over the sub-steps: the World applies it once, in its
// prediction, and integrate does not repeat it.
TEST(Integrators, GyroscopicWorldMatchesTheCoreStep) {
    for (Integrator integrator : {Integrator::NewtonEulerGyroscopic, Integrator::NewtonEulerImplicit}) {
        WorldFixture f(noGravity(integrator));
        const BodyId id = f.world.addBody(elongatedBox(Vector3(0.1, 5, 0.1)));
        RigidBody reference = f.world.body(id);
        for (int i = 0; i < 120; ++i) {
            f.world.step(kDt);
            reference.applyGyroscopicStep(GyroscopicStep::Midpoint, kDt);
            for (int k = 0; k < 4; ++k) reference.integrate(kDt / 4, false);
        }
        const RigidBody &body = f.world.body(id);
        EXPECT_LT((body.getRotation() - reference.getRotation()).norm(), 1e-12);
        EXPECT_LT((body.getOrientation().coeffs() - reference.getOrientation().coeffs()).norm(), 1e-12);
    }
}

// The seed keeps a torque-free body's world angular velocity exactly.
TEST(Integrators, SeedKeepsWorldAngularVelocity) {
    WorldFixture f(noGravity(Integrator::NewtonEuler));
    const BodyId id = f.world.addBody(elongatedBox(Vector3(0.1, 5, 0.1)));
    f.simulate(2);
    EXPECT_EQ(f.world.body(id).getRotation(), Vector3(0.1, 5, 0.1));
}

// Spheres and cubes (isotropic inertia) and sleeping bodies cost nothing: only the
// elongated box is given the gyroscopic step.
TEST(Integrators, OnlyAnisotropicBodiesPayForTheGyroscopicStep) {
    WorldFixture f(noGravity(Integrator::NewtonEulerGyroscopic));
    f.sphere(Vector3(3, 0, 0));
    f.box(Vector3(-3, 0, 0));
    f.world.addBody(elongatedBox(Vector3(1, 2, 3)));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().gyroscopicBodies, 1);
    WorldFixture seed(noGravity(Integrator::NewtonEuler));
    seed.world.addBody(elongatedBox(Vector3(1, 2, 3)));
    seed.world.step(kDt);
    EXPECT_EQ(seed.world.stats().gyroscopicBodies, 0);
}

// A box whose mass is not aligned with its shape (off-diagonal inertia) spins about the
// vertical on a frictionless floor: w x I w is not zero, so the gyroscopic step tries to
// tip it and the contacts hold it down. Were the prediction and the integration to
// disagree, the contact impulses would be computed for the wrong velocity and the box
// would sink or hop; normal forces do no work on a resting box, so its kinetic energy
// cannot grow either.
TEST(Integrators, GyroscopicStepAgreesWithContacts) {
    WorldSettings settings;
    settings.sleep = false;
    settings.integrator = Integrator::NewtonEulerGyroscopic;
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
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        EXPECT_LE(f.world.kineticEnergy(), energy * (1 + 1e-9));
        EXPECT_NEAR(f.position(id).y(), 0.1, 0.001);
        EXPECT_LT(std::abs(f.world.body(id).getVelocity().y()), 0.01);
    }
    EXPECT_EQ(f.world.stats().gyroscopicBodies, 1);
}

// --- Springs ------------------------------------------------------------------------------

struct Oscillator {
    WorldFixture f;
    BodyId ball;
    real stiffness;

    // A 1 kg ball on a spring of rest length 1 m to the origin, stretched by `stretch`
    // along x; no gravity, no damping, omega = sqrt(k).
    Oscillator(Integrator integrator, real k, real stretch, int substeps,
               SpringForce force = SpringForce::Automatic)
        : f(noGravity(integrator, substeps)), stiffness(k) {
        ball = f.sphere(Vector3(1 + stretch, 0, 0), 0.1, 1);
        SpringSettings spring;
        spring.a = ball;
        spring.bPoint = Vector3::Zero();
        spring.stiffness = k;
        spring.restLength = 1;
        spring.force = force;
        f.world.addSpring(spring);
    }

    real energy() const {
        const real stretch = f.position(ball).norm() - 1;
        return f.world.kineticEnergy() + 0.5 * stiffness * stretch * stretch;
    }
};

// One step of 0.1 s, k = 100, m = 1, stretch 0.1 m, at rest, one sub-step (omega h = 1:
// an automatic spring would be implicit, so the explicit one is asked for).
// Explicit: F = -k x = -10 N, v = -1 m/s, x = 1.1 - 0.1 = 1.0 m.
// Backward Euler: v' = (v - h k x / m) / (1 + h^2 k / m) = -1 / 2, x' = 1.1 + 0.1 v' = 1.05 m.
TEST(Integrators, OneSpringStepWorkedByHand) {
    Oscillator explicitSpring(Integrator::NewtonEuler, 100, 0.1, 1, SpringForce::Explicit);
    explicitSpring.f.world.step(0.1);
    EXPECT_NEAR(explicitSpring.f.world.body(explicitSpring.ball).getVelocity().x(), -1, 1e-12);
    EXPECT_NEAR(explicitSpring.f.position(explicitSpring.ball).x(), 1.0, 1e-12);

    Oscillator implicitSpring(Integrator::NewtonEulerImplicit, 100, 0.1, 1);
    implicitSpring.f.world.step(0.1);
    EXPECT_NEAR(implicitSpring.f.world.body(implicitSpring.ball).getVelocity().x(), -0.5, 1e-12);
    EXPECT_NEAR(implicitSpring.f.position(implicitSpring.ball).x(), 1.05, 1e-12);
    EXPECT_EQ(implicitSpring.f.world.stats().springs, 1);
}

// Backward Euler shrinks an oscillator's energy by 1 / (1 + (omega h)^2) every sub-step,
// whatever omega h: it never gains energy, up to omega dt = 10 (omega h = 2.5 with 4
// sub-steps) and beyond.
TEST(Integrators, ImplicitSpringNeverGainsEnergy) {
    for (real omegaDt : {0.1, 1.0, 2.0, 5.0, 10.0, 100.0}) {
        const real omega = omegaDt / kDt;
        Oscillator o(Integrator::NewtonEulerImplicit, omega * omega, 0.1, 4);
        const real start = o.energy();
        real last = start;
        for (int i = 0; i < 300; ++i) {
            o.f.world.step(kDt);
            const real now = o.energy();
            // Relative 1e-12, and roundoff of the position (1e-16 m) once the energy is spent.
            EXPECT_LE(now, last * (1 + 1e-12) + 1e-20 * start) << "omega dt " << omegaDt << ", step " << i;
            last = now;
        }
    }
}

// The seed's explicit force makes each sub-step symplectic Euler: past omega h = 2 an
// eigenvalue of the step leaves the unit circle (at omega h = 10 the trace is
// 2 - 100 = -98), and the energy grows by orders of magnitude within a few steps.
TEST(Integrators, ExplicitSpringExplodesBeyondOmegaHTwo) {
    Oscillator o(Integrator::NewtonEuler, std::pow(10 / kDt, 2), 0.1, 1, SpringForce::Explicit);
    const real start = o.energy();
    for (int i = 0; i < 5; ++i) o.f.world.step(kDt);
    EXPECT_GT(o.energy(), 1e4 * start);
}

// Below omega h = 2 symplectic Euler keeps a modified energy exactly: with y = omega x
// and u = omega h, Q = y^2 + v^2 - u y v. Along a circle of radius r in (y, v),
// Q = r^2 (1 - u/2 sin 2phi), so the true energy r^2 / 2 only oscillates, and from rest
// (Q = 2 E0) it never exceeds E0 / (1 - u/2). With 4 sub-steps at omega dt = 2,
// u = 0.5: within 4/3 of the start, over 100 periods.
TEST(Integrators, ExplicitSpringStaysBoundedBelowOmegaHTwo) {
    Oscillator o(Integrator::NewtonEuler, std::pow(2 / kDt, 2), 0.1, 4);
    const real start = o.energy();
    for (int i = 0; i < 315; ++i) {
        o.f.world.step(kDt);
        EXPECT_LE(o.energy(), start * 4 / 3 * (1 + 1e-9)) << "step " << i;
    }
}

// Hanging on a stiff spring, a body settles where k x = m g: x = 9.81 mm for k = 1000 N/m
// and 1 kg, exactly, since the implicit force accounts for gravity in the sub-step.
TEST(Integrators, ImplicitSpringHangsAtStaticStretch) {
    for (Integrator integrator : {Integrator::NewtonEuler, Integrator::NewtonEulerImplicit}) {
        WorldSettings settings;
        settings.sleep = false;
        settings.integrator = integrator;
        WorldFixture f(settings);
        const BodyId ball = f.sphere(Vector3(0, 0.9, 0), 0.1, 1);
        SpringSettings spring;
        spring.a = ball;
        spring.bPoint = Vector3(0, 2, 0);
        spring.stiffness = 1000;
        spring.damping = 20;  // damping ratio 0.32: decays as exp(-10 t)
        spring.restLength = 1;
        f.world.addSpring(spring);
        f.simulate(5);
        EXPECT_NEAR(f.position(ball).y(), 2 - 1 - 9.81 / 1000, 1e-9) << static_cast<int>(integrator);
    }
}

// A stiff spring on the corner of a spinning box (omega dt = 10 for the box's mass). The
// implicit force is linearised about the sub-step's start, and the attachment point moves
// on a circle rather than along its velocity: a step may gain a little (of order
// k |stretch| (h w)^2 r), but the energy of box and spring never rises above where it
// started, and the spring and the spin lose it over time.
TEST(Integrators, ImplicitSpringOnAnOffsetPointStaysBelowItsStartingEnergy) {
    WorldFixture f(noGravity(Integrator::NewtonEulerImplicit));
    BodySettings s;
    s.shape = Shape::box(Vector3(0.3, 0.2, 0.1));
    s.position = Vector3(0.5, 1.5, 0.2);
    s.rotation = Vector3(1, -2, 3);
    s.mass = 2;
    const BodyId box = f.world.addBody(s);
    SpringSettings spring;
    spring.a = box;
    spring.aPoint = Vector3(0.3, 0.2, 0.1);
    spring.stiffness = 2 * std::pow(10 / kDt, 2);
    spring.restLength = 1;
    f.world.addSpring(spring);
    auto energy = [&] {
        const real stretch = f.world.body(box).getPointInWorldSpace(spring.aPoint).norm() - spring.restLength;
        return f.world.kineticEnergy() + 0.5 * spring.stiffness * stretch * stretch;
    };
    const real start = energy();
    for (int i = 0; i < 600; ++i) {
        f.world.step(kDt);
        EXPECT_LE(energy(), start) << "step " << i;
    }
    EXPECT_LT(energy(), 0.01 * start);
}

// --- Springs at the defaults -----------------------------------------------------------

// With the default integrator and sub-steps, springs of omega dt = 5 and 10 (omega h =
// 1.25 and 2.5, beyond WorldSettings::explicitSpringLimit) get the backward-Euler force,
// whose energy shrinks every sub-step: it never rises above the start, so the stretch
// never exceeds the initial 0.1 m. Also with one sub-step (omega h = 5 and 10).
TEST(Integrators, StiffSpringsAtTheDefaultsNeverGainEnergy) {
    for (int substeps : {4, 1})
        for (real omegaDt : {5.0, 10.0}) {
            const real omega = omegaDt / kDt;
            Oscillator o(Integrator::NewtonEuler, omega * omega, 0.1, substeps);
            const real start = o.energy();
            for (int i = 0; i < 300; ++i) {
                o.f.world.step(kDt);
                ASSERT_LE(o.energy(), start * (1 + 1e-12)) << "omega dt " << omegaDt << ", step " << i;
                ASSERT_LE(std::abs(o.f.position(o.ball).norm() - 1), 0.1 * 1.1) << "omega dt " << omegaDt;
            }
        }
}

// Springs far below the limit (omega dt = 0.1 and 0.5: omega h up to 0.5 with one
// sub-step) stay explicit: their motion is that of SpringForce::Explicit bit for bit, so
// the treatment takes none of their energy. Symplectic Euler keeps the modified energy
// Q = y^2 + v^2 - u y v (y = omega x, u = omega h) exactly: after one second it is where
// it started, to roundoff.
TEST(Integrators, SlowSpringsAtTheDefaultsStayExplicit) {
    for (int substeps : {4, 1})
        for (real omegaDt : {0.1, 0.5}) {
            const real omega = omegaDt / kDt;
            Oscillator automatic(Integrator::NewtonEuler, omega * omega, 0.1, substeps);
            Oscillator explicitOnly(Integrator::NewtonEuler, omega * omega, 0.1, substeps, SpringForce::Explicit);
            const real u = omega * kDt / substeps;
            const auto modified = [&](const Oscillator &o) {
                const real y = omega * (o.f.position(o.ball).x() - 1);
                const real v = o.f.world.body(o.ball).getVelocity().x();
                return y * y + v * v - u * y * v;
            };
            const real start = modified(automatic);
            for (int i = 0; i < 60; ++i) {
                automatic.f.world.step(kDt);
                explicitOnly.f.world.step(kDt);
                ASSERT_EQ(automatic.f.position(automatic.ball), explicitOnly.f.position(explicitOnly.ball));
            }
            EXPECT_NEAR(modified(automatic), start, 1e-9 * start) << "omega dt " << omegaDt;
        }
}

// Two 1 kg balls joined by a spring: omega^2 = k (1/m_a + 1/m_b) = 2 k. At omega dt = 10
// the spring is implicit and the pair's energy never grows.
TEST(Integrators, StiffSpringBetweenTwoBodiesNeverGainsEnergy) {
    WorldFixture f(noGravity(Integrator::NewtonEuler));
    const BodyId a = f.sphere(Vector3(0, 0, 0), 0.1, 1);
    const BodyId b = f.sphere(Vector3(1.1, 0, 0), 0.1, 1);
    SpringSettings spring;
    spring.a = a;
    spring.b = b;
    spring.stiffness = std::pow(10 / kDt, 2) / 2;
    spring.restLength = 1;
    f.world.addSpring(spring);
    const auto energy = [&] {
        const real stretch = (f.position(b) - f.position(a)).norm() - 1;
        return f.world.kineticEnergy() + 0.5 * spring.stiffness * stretch * stretch;
    };
    const real start = energy();
    for (int i = 0; i < 300; ++i) {
        f.world.step(kDt);
        ASSERT_LE(energy(), start * (1 + 1e-12)) << "step " << i;
    }
}

// A ball between two anchored springs along x, each of omega h = 0.7 alone (below the
// limit 0.8) but together omega h = 0.7 sqrt 2 = 0.99: its load is the sum of both, so
// both are implicit and the energy never grows. Explicit, from rest the energy peaks near
// E0 / (1 - u/2) = 2 E0 (Integrators.ExplicitSpringStaysBoundedBelowOmegaHTwo).
TEST(Integrators, SpringsSharingABodyAddTheirLoads) {
    for (SpringForce force : {SpringForce::Automatic, SpringForce::Explicit}) {
        WorldFixture f(noGravity(Integrator::NewtonEuler));
        const BodyId ball = f.sphere(Vector3(0.1, 0, 0), 0.1, 1);
        const real k = std::pow(0.7 * 4 / kDt, 2);
        for (real side : {-1.0, 1.0}) {
            SpringSettings spring;
            spring.a = ball;
            spring.bPoint = Vector3(side, 0, 0);
            spring.stiffness = k;
            spring.restLength = 1;
            spring.force = force;
            f.world.addSpring(spring);
        }
        const auto energy = [&] {
            const real x = f.position(ball).x();
            return f.world.kineticEnergy() + 0.5 * k * (x * x + x * x);
        };
        const real start = energy();
        real highest = start;
        for (int i = 0; i < 300; ++i) {
            f.world.step(kDt);
            highest = std::max(highest, energy());
        }
        if (force == SpringForce::Automatic) EXPECT_LE(highest, start * (1 + 1e-12));
        else EXPECT_GT(highest, 1.5 * start);
    }
}

TEST(Integrators, SpringSettingsAreValidated) {
    WorldFixture f(noGravity(Integrator::NewtonEuler));
    SpringSettings spring;
    spring.a = f.sphere(Vector3::Zero());
    spring.force = static_cast<SpringForce>(5);
    try {
        f.world.addSpring(spring);
        FAIL() << "accepted force 5";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::addSpring");
        EXPECT_EQ(e.field(), "force");
    }
    for (real limit : {0.0, -1.0, std::nan("")}) {
        WorldSettings bad = noGravity(Integrator::NewtonEuler);
        bad.explicitSpringLimit = limit;
        try {
            f.world.setSettings(bad);
            FAIL() << "accepted explicitSpringLimit " << limit;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "World::setSettings");
            EXPECT_EQ(e.field(), "explicitSpringLimit");
        }
    }
    EXPECT_EQ(f.world.settings().explicitSpringLimit, WorldSettings().explicitSpringLimit);
}

}  // namespace
}  // namespace cyclone::test
