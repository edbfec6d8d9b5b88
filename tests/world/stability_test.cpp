// Stability on stiff and extreme cases: each case bounds energy, penetration and drift,
// with the reason for each bound next to it.
//
// The bounds shared by the resting cases, for a step dt of S sub-steps of h = dt / S:
//  - settled depth: a converged resting contact sits one slop deep, plus what gravity
//    moves a body in one sub-step before the solver sees it, g h^2;
//  - deepest contact: at most one step of free fall, g h^2 S (S + 1) / 2, beyond the
//    slop: more means something fell through the solver for longer than a step;
//  - sideways drift: nothing pushes a symmetric stack sideways; 1 mm is the residue of
//    the order in which points are solved;
//  - kinetic energy once settled: at most that of every body moving at g h, the speed
//    one sub-step of gravity gives before the contacts answer.
#include <cmath>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


struct Bounds {
    double settledDepth;
    double deepest;
    double drift = 0.001;
    double energy;
};

Bounds restingBounds(const WorldSettings &settings, double dt, double totalMass) {
    const double h = dt / settings.substeps;
    const int s = settings.substeps;
    Bounds b;
    b.settledDepth = settings.penetrationSlop + kG * h * h + 1e-6;
    b.deepest = settings.penetrationSlop + kG * h * h * s * (s + 1) / 2;
    b.energy = 0.5 * totalMass * (kG * h) * (kG * h);
    return b;
}

struct Measured {
    double settledDepth = 0;  // deepest contact after the first second
    double deepest = 0;       // deepest contact of the run
    double drift = 0;         // largest sideways move of any tracked body
    double energy = 0;        // largest kinetic energy after the first second
};

// Steps `f` for `seconds` at `dt` and measures the tracked bodies against their start.
Measured run(WorldFixture &f, const std::vector<BodyId> &tracked, double seconds, double dt) {
    std::vector<Vector3> start;
    for (BodyId id : tracked) start.push_back(f.position(id));
    Measured m;
    const int steps = static_cast<int>(std::lround(seconds / dt));
    for (int i = 0; i < steps; ++i) {
        f.world.step(dt);
        const double depth = f.world.stats().maxPenetration;
        m.deepest = std::max(m.deepest, depth);
        if ((i + 1) * dt > 1) {
            m.settledDepth = std::max(m.settledDepth, depth);
            m.energy = std::max(m.energy, f.world.kineticEnergy());
        }
        for (std::size_t k = 0; k < tracked.size(); ++k) {
            const Vector3 moved = f.position(tracked[k]) - start[k];
            m.drift = std::max(m.drift, std::hypot(moved.x(), moved.z()));
        }
    }
    return m;
}

void expectWithin(const Measured &m, const Bounds &b, const std::string &what) {
    EXPECT_LE(m.settledDepth, b.settledDepth) << what;
    EXPECT_LE(m.deepest, b.deepest) << what;
    EXPECT_LE(m.drift, b.drift) << what;
    EXPECT_LE(m.energy, b.energy) << what;
}

// A column of boxes of half size `half` and the given masses, bottom first, each placed
// 0.1 mm into the one below so that every contact exists from the first step (the
// narrowphase reports overlapping shapes only).
std::vector<BodyId> column(WorldFixture &f, double half, const std::vector<double> &masses,
                           const Vector3 &base = Vector3::Zero()) {
    std::vector<BodyId> ids;
    for (std::size_t i = 0; i < masses.size(); ++i)
        ids.push_back(f.box(base + Vector3(0, half + i * (2 * half - 0.0001) - 0.0001, 0), Vector3::Constant(half),
                            masses[i]));
    return ids;
}

double sum(const std::vector<double> &values) {
    double total = 0;
    for (double v : values) total += v;
    return total;
}

// --- Mass ratios ------------------------------------------------------------------------

// A heavy box between light ones: 1, 100, 1 kg and 1, 1000, 1 kg unit boxes. Plain
// Gauss-Seidel converges ever slower as a heavy body rests on a light one (measured
// before the carrier pass: 1:100:1 sank 13.6 mm, 1:1000:1 pushed the light box out);
// the carrier pass (DebugSettings::carrierPass) holds both
// within the bounds of a unit-mass stack.
TEST(Stability, MassRatiosStacked) {
    for (double ratio : {100.0, 1000.0}) {
        const std::vector<double> masses{1, ratio, 1};
        WorldFixture f(noSleep());
        f.ground();
        const Measured m = run(f, column(f, 0.5, masses), 5, kDt);
        expectWithin(m, restingBounds(f.world.settings(), kDt, sum(masses)), "1:" + std::to_string(ratio) + ":1");
    }
}

// --- Sizes --------------------------------------------------------------------------------

// Three boxes of 1 cm and of 10 m (density 1000 kg/m^3): the bounds do not depend on size
// (the slop is absolute), so a 1 cm box rests 2% of its size deep at the default slop.
TEST(Stability, SmallAndLargeBoxesRest) {
    for (double size : {0.01, 10.0}) {
        const double mass = 1000 * size * size * size;
        const std::vector<double> masses(3, mass);
        WorldFixture f(noSleep());
        f.ground();
        const Measured m = run(f, column(f, size / 2, masses), 3, kDt);
        Bounds b = restingBounds(f.world.settings(), kDt, sum(masses));
        b.drift = 0.001 * std::max(size, 1.0);  // 1 mm, or 0.1% of a 10 m box
        expectWithin(m, b, "size " + std::to_string(size));
    }
}

// --- Far from the origin ------------------------------------------------------------------

// A 4-level pyramid (10 unit boxes) at the origin and 10 km away: at 1e4 m a double
// resolves 2e-12 m, far below every tolerance of the solver, so both rest within the
// bounds and move alike (to 0.1 mm).
TEST(Stability, PyramidTenKilometresAway) {
    std::vector<Measured> results;
    for (const Vector3 &base : {Vector3(0, 0, 0), Vector3(1e4, 0, -1e4)}) {
        WorldFixture f(noSleep());
        BodySettings ground;
        ground.motion = Motion::Static;
        ground.shape = Shape::box(Vector3(10, 0.5, 10));
        ground.position = base + Vector3(0, -0.5, 0);
        f.world.addBody(ground);
        std::vector<BodyId> boxes;
        for (int level = 0; level < 4; ++level)
            for (int i = 0; i < 4 - level; ++i)
                boxes.push_back(f.box(base + Vector3((i - (3 - level) / 2.0) * 1.05, 0.5 + level * 0.9999, 0)));
        results.push_back(run(f, boxes, 3, kDt));
        expectWithin(results.back(), restingBounds(f.world.settings(), kDt, 10), "pyramid at " +
                                                                                     std::to_string(base.x()));
    }
    EXPECT_NEAR(results[0].drift, results[1].drift, 1e-4);
    EXPECT_NEAR(results[0].deepest, results[1].deepest, 1e-4);
}

// --- Step sizes ---------------------------------------------------------------------------

// Three unit boxes stacked, stepped at 1/1000 s to 1/15 s. Before the carrier pass the
// stack crept sideways at 1/30 s and 1/15 s though nothing pushes it (1.8 mm and 7.5 mm in
// 3 s): point by point, the normal and friction impulses left each box turning a little
// each sub-step.
TEST(Stability, StepsFromMillisecondToFifteenHertz) {
    for (double dt : {1.0 / 1000, 1.0 / 240, 1.0 / 60, 1.0 / 30, 1.0 / 15}) {
        const std::vector<double> masses{1, 1, 1};
        WorldFixture f(noSleep());
        f.ground();
        const Measured m = run(f, column(f, 0.5, masses), 3, dt);
        expectWithin(m, restingBounds(f.world.settings(), dt, sum(masses)), "dt " + std::to_string(dt));
    }
}

// A box dropped from 1 m at each step size never bounces higher than it fell from
// (restitution 0): the energy of the fall is lost, not gained.
TEST(Stability, DropNeverGainsEnergyAtAnyStep) {
    for (double dt : {1.0 / 1000, 1.0 / 60, 1.0 / 15}) {
        WorldFixture f(noSleep());
        f.ground();
        const BodyId box = f.box(Vector3(0, 1.5, 0));
        double highest = 0;
        for (int i = 0; i < static_cast<int>(std::lround(3 / dt)); ++i) {
            f.world.step(dt);
            if (i * dt > 0.5) highest = std::max(highest, f.position(box).y());
        }
        EXPECT_LT(highest, 0.5 + 0.01) << "dt " << dt;  // back at rest, within the slop and a sub-step
    }
}

// --- Continuous collision -----------------------------------------------------------------

// A 0.1 m ball at 200 m/s against a 0.1 m wall: 3.3 m per 60 Hz step. Its box grown by
// the step's reach finds the wall, and the speculative contact stops it on the near side
// (its centre a radius before the face, less 2 mm for the slop and the contact
// tolerance), with ccd or without; its kinetic energy does not grow.
TEST(Stability, FastSphereAgainstThinWall) {
    for (bool ccd : {false, true}) {
        WorldSettings settings = noSleep();
        settings.gravity = Vector3::Zero();
        WorldFixture f(settings);
        f.staticBox(Vector3::Zero(), Vector3(0.05, 2, 2));
        BodySettings s;
        s.shape = Shape::sphere(0.05);
        s.position = Vector3(-2, 0, 0);
        s.velocity = Vector3(200, 0, 0);
        s.ccd = ccd;
        const BodyId ball = f.world.addBody(s);
        const double energy = f.world.kineticEnergy();
        for (int i = 0; i < 60; ++i) {
            f.world.step(kDt);
            EXPECT_LE(f.world.kineticEnergy(), energy * (1 + 1e-12));
        }
        EXPECT_LT(f.position(ball).x(), -0.1 + 0.002) << "ccd " << ccd;
        EXPECT_LT(f.world.body(ball).getVelocity().x(), 0.01) << "ccd " << ccd;
    }
}

// --- Fast spin ----------------------------------------------------------------------------

// A 1 m x 1 cm x 0.5 m plate spun at 100 rad/s about an axis off its principal ones,
// without gravity: a torque-free body cannot gain energy, whatever the integrator
// (the seed keeps world w, the gyroscopic step keeps the energy or lowers it).
TEST(Stability, ThinPlateSpunFastNeverGainsEnergy) {
    for (Integrator integrator : {Integrator::NewtonEuler, Integrator::NewtonEulerGyroscopic}) {
        WorldSettings settings = noSleep();
        settings.gravity = Vector3::Zero();
        settings.integrator = integrator;
        WorldFixture f(settings);
        BodySettings s;
        s.shape = Shape::box(Vector3(0.5, 0.005, 0.25));
        s.rotation = 100 * Vector3(0.3, 1, 0.2).normalized();
        const BodyId plate = f.world.addBody(s);
        const double energy = f.world.kineticEnergy();
        for (int i = 0; i < 300; ++i) {
            f.world.step(kDt);
            ASSERT_LE(f.world.kineticEnergy(), energy * (1 + 1e-12)) << static_cast<int>(integrator) << " step " << i;
        }
        EXPECT_TRUE(f.world.body(plate).getRotation().allFinite());
    }
}

// The same plate lying on the ground spinning about the vertical at 100 rad/s: friction
// can only take energy away, and the plate stays on the ground (its centre within the
// slop and a sub-step of its resting height).
TEST(Stability, ThinPlateSpinningOnTheGroundNeverGainsEnergy) {
    for (Integrator integrator : {Integrator::NewtonEuler, Integrator::NewtonEulerGyroscopic}) {
        WorldSettings settings = noSleep();
        settings.integrator = integrator;
        WorldFixture f(settings);
        f.ground();
        BodySettings s;
        s.shape = Shape::box(Vector3(0.5, 0.005, 0.25));
        s.position = Vector3(0, 0.005 - 0.0001, 0);
        s.rotation = Vector3(0, 100, 0);
        const BodyId plate = f.world.addBody(s);
        double last = f.world.kineticEnergy();
        for (int i = 0; i < 180; ++i) {
            f.world.step(kDt);
            const double now = f.world.kineticEnergy();
            ASSERT_LE(now, last * (1 + 1e-9) + 1e-12) << static_cast<int>(integrator) << " step " << i;
            last = now;
            EXPECT_NEAR(f.position(plate).y(), 0.005, 0.0002 + kG * kDt * kDt / 16);
        }
    }
}

// --- Stiff springs ------------------------------------------------------------------------

// Three 1 kg balls hanging in a chain of springs with omega dt = 10 (k = 360000 N/m at
// 60 Hz), released 5 cm below their rest: with backward-Euler springs the mechanical
// energy (kinetic, elastic, gravitational) never rises above where it started, and the
// chain settles where each spring carries the weight below it: stretches 3, 2 and 1
// times m g / k.
TEST(Stability, StiffSpringChain) {
    WorldSettings settings = noSleep();
    settings.integrator = Integrator::NewtonEulerImplicit;
    WorldFixture f(settings);
    const double k = std::pow(10 / kDt, 2);
    std::vector<BodyId> balls;
    std::vector<SpringSettings> springs;
    for (int i = 0; i < 3; ++i) {
        balls.push_back(f.sphere(Vector3(0, -(i + 1) * 1.0 - 0.05, 0), 0.1, 1));
        SpringSettings spring;
        spring.a = balls.back();
        if (i == 0) spring.bPoint = Vector3::Zero();
        else spring.b = balls[i - 1];
        spring.stiffness = k;
        spring.restLength = 1;
        f.world.addSpring(spring);
        springs.push_back(spring);
    }
    auto energy = [&] {
        double e = f.world.kineticEnergy();
        Vector3 above = Vector3::Zero();
        for (BodyId id : balls) {
            const Vector3 p = f.position(id);
            const double stretch = (p - above).norm() - 1;
            e += 0.5 * k * stretch * stretch + kG * p.y();
            above = p;
        }
        return e;
    };
    const double start = energy();
    for (int i = 0; i < 300; ++i) {
        f.world.step(kDt);
        ASSERT_LE(energy(), start + 1e-9) << "step " << i;
    }
    const double weightStretch = kG / k;
    EXPECT_NEAR(f.position(balls[0]).y(), -1 - 3 * weightStretch, 1e-9);
    EXPECT_NEAR(f.position(balls[1]).y(), -2 - 5 * weightStretch, 1e-9);
    EXPECT_NEAR(f.position(balls[2]).y(), -3 - 6 * weightStretch, 1e-9);
}

}  // namespace
}  // namespace cyclone::test
