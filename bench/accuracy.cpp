// cyclone-accuracy: the error of the simulation against what it costs. Reference scenes
// with a closed form or a converged reference are run at a sweep of step sizes, solver
// settings and integrators; each run is timed and its error measured. Writes a CSV, a
// Markdown report and one gnuplot script per scene and measure (scripts/accuracy.sh runs
// them and keeps the outputs in docs/accuracy/).
//
//   cyclone-accuracy --out DIR --plots DIR [--quick]
//
// Every scene is deterministic; only the wall times vary from machine to machine.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cyclone/world.h"
#include "scene_loader.h"

namespace cyclone::accuracy {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;
// Errors beyond this are a divergence, shown as such (and kept out of the plots' range).
constexpr double kDiverged = 1e9;

// --- What a run gives ----------------------------------------------------------------------

// Schemes the bench runs on a bare RigidBody, for comparison with the World's.
enum class CoreScheme {
    None,           // the World with Config::integrator
    BackwardEuler,  // GyroscopicStep::BackwardEuler once per step, then integrate (Bullet's and Jolt's form)
    Splitting,      // the free rigid body split into exact rotations about the body axes (below)
};

struct Config {
    Integrator integrator = Integrator::NewtonEuler;
    CoreScheme core = CoreScheme::None;
    std::string integratorName;  // overrides the scene-file name (reference schemes)
    SpringForce springForce = SpringForce::Automatic;
    double dt = 1.0 / 60;
    int iterations = 3;
    int substeps = 4;
    std::string parameter;       // scene-specific, e.g. "omega dt = 2.5"
};

struct Row {
    std::string scene;
    std::string key;
    std::string measure;
    Config config;
    double wallMsPerSimSecond = 0;
    double error = 0;
};

struct Measure {
    std::string key;   // short, for file names
    std::string name;  // what it is, with its unit
    double value;
};

struct Outcome {
    double simulatedSeconds = 0;
    double wallSeconds = 0;
    std::vector<Measure> measures;
};

std::string integratorName(const Config &c) {
    if (!c.integratorName.empty()) return c.integratorName;
    for (const scene::IntegratorName &entry : scene::kIntegrators)
        if (entry.integrator == c.integrator)
            return std::string(entry.name) + (c.springForce == SpringForce::Explicit ? " (explicit springs)" : "");
    return "?";
}

WorldSettings worldSettings(const Config &c, bool gravity = true) {
    WorldSettings s;
    s.sleep = false;
    s.integrator = c.integrator;
    s.velocityIterations = c.iterations;
    s.substeps = c.substeps;
    if (!gravity) s.gravity = Vector3::Zero();
    return s;
}

int stepsFor(double seconds, double dt) { return static_cast<int>(std::lround(seconds / dt)); }

// Times `steps` calls of `step`, calling `after` (not timed) after each.
double timed(int steps, const std::function<void()> &step, const std::function<void(int)> &after) {
    double seconds = 0;
    for (int i = 0; i < steps; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        step();
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        after(i);
    }
    return seconds;
}

BodyId addGround(World &world, double friction) {
    BodySettings g;
    g.isStatic = true;
    g.shape = Shape::plane(Vector3::UnitY(), 0);
    g.material.friction = friction;
    return world.addBody(g);
}

// --- Scenes ----------------------------------------------------------------------------------

// A ball thrown at (10, 10, 0) m/s, no contacts, 2 s. Without damping the closed form is
// x0 + v0 t + g t^2 / 2. The World's damping keeps a fraction d of the velocity per second:
// dv/dt = g + ln(d) v, so v = v_inf + (v0 - v_inf) e^(lambda t) with lambda = ln d and
// v_inf = -g / lambda, and x = x0 + v_inf t + (v0 - v_inf) (e^(lambda t) - 1) / lambda.
Outcome projectile(const Config &c, double damping) {
    World world(worldSettings(c));
    BodySettings s;
    s.shape = Shape::sphere(0.1);
    s.velocity = Vector3(10, 10, 0);
    s.linearDamping = damping;
    const BodyId ball = world.addBody(s);
    const double seconds = 2;
    const int steps = stepsFor(seconds, c.dt);
    Outcome o;
    o.wallSeconds = timed(steps, [&] { world.step(c.dt); }, [](int) {});
    o.simulatedSeconds = steps * c.dt;
    const double t = o.simulatedSeconds;
    const Vector3 g(0, -kG, 0), v0(10, 10, 0);
    Vector3 exact;
    if (damping == 1) {
        exact = v0 * t + 0.5 * g * t * t;
    } else {
        const double lambda = std::log(damping);
        const Vector3 vInf = -g / lambda;
        exact = vInf * t + (v0 - vInf) * (std::exp(lambda * t) - 1) / lambda;
    }
    o.measures.push_back({"position", "position error at 2 s (m)", (world.body(ball).getPosition() - exact).norm()});
    return o;
}

// Torque-free rigid body, the converged reference: RK4 on the body-frame angular velocity
// (Euler's equations) and the orientation quaternion (dq/dt = q (0, w) / 2).
struct SpinState {
    Quaternion q;
    Vector3 w;  // body frame
};

SpinState spinDerivative(const SpinState &s, const Vector3 &inertia) {
    const Vector3 momentum = inertia.cwiseProduct(s.w);
    SpinState d;
    d.w = -(s.w.cross(momentum)).cwiseQuotient(inertia);
    const Quaternion dq = s.q * Quaternion(0, s.w.x(), s.w.y(), s.w.z());
    d.q.coeffs() = 0.5 * dq.coeffs();
    return d;
}

SpinState rk4Spin(SpinState s, const Vector3 &inertia, double seconds, double h) {
    const int steps = stepsFor(seconds, h);
    auto add = [](const SpinState &a, const SpinState &b, double k) {
        SpinState r;
        r.q.coeffs() = a.q.coeffs() + k * b.q.coeffs();
        r.w = a.w + k * b.w;
        return r;
    };
    for (int i = 0; i < steps; ++i) {
        const SpinState k1 = spinDerivative(s, inertia);
        const SpinState k2 = spinDerivative(add(s, k1, h / 2), inertia);
        const SpinState k3 = spinDerivative(add(s, k2, h / 2), inertia);
        const SpinState k4 = spinDerivative(add(s, k3, h), inertia);
        s.q.coeffs() += h / 6 * (k1.q.coeffs() + 2 * k2.q.coeffs() + 2 * k3.q.coeffs() + k4.q.coeffs());
        s.w += h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w);
        s.q.normalize();
    }
    return s;
}

struct Dzhanibekov {
    // Box 0.1 x 0.4 x 0.9 m, 1 kg: I = m (b^2 + c^2) / 12, ...; spun near its intermediate
    // (y) axis at w0 = (0.1, 5, 0.1) rad/s (or tumbling about no principal axis), no
    // gravity, for 10 s.
    Vector3 halfExtents{0.05, 0.2, 0.45};
    Vector3 w0{0.1, 5, 0.1};
    double seconds = 10;
    Vector3 inertia() const {
        const Vector3 full = 2 * halfExtents;
        return Vector3(full.y() * full.y() + full.z() * full.z(), full.x() * full.x() + full.z() * full.z(),
                       full.x() * full.x() + full.y() * full.y()) /
               12;
    }
    Quaternion reference(double h) const {
        return rk4Spin({Quaternion::Identity(), w0}, inertia(), seconds, h).q;
    }
};

double angleBetween(const Quaternion &a, const Quaternion &b) { return a.angularDistance(b); }

// The splitting of the free rigid body's kinetic energy T = sum L_i^2 / (2 I_i) into its
// three terms, each an exact rotation about one body axis at rate L_i / I_i (which that
// rotation keeps), composed symmetrically (Strang): axis 1 for h/2, axis 2 for h/2, axis 3
// for h, axis 2 for h/2, axis 1 for h/2 (Dullweber, Leimkuhler and McLachlan; Touma and
// Wisdom). Second order; it keeps L and |L| exactly, the energy only to O(h^2). The
// candidate the World's "momentum-conserving" step was measured against.
struct SplitBody {
    Quaternion q = Quaternion::Identity();
    Vector3 momentum;  // body frame
    Vector3 inertia;   // principal moments

    void rotate(int axis, double h) {
        Vector3 unit = Vector3::Zero();
        unit[axis] = 1;
        const Quaternion turn(Eigen::AngleAxis<real>(h * momentum[axis] / inertia[axis], unit));
        q = (q * turn).normalized();
        momentum = turn.conjugate() * momentum;
    }
    void step(double h) {
        rotate(0, h / 2);
        rotate(1, h / 2);
        rotate(2, h);
        rotate(1, h / 2);
        rotate(0, h / 2);
    }
    void copyTo(RigidBody &body) const {
        body.setOrientation(q);
        body.setRotation(q * momentum.cwiseQuotient(inertia));
    }
};

// The World with one of its integrators, or a bare RigidBody given a core scheme: the
// backward-Euler gyroscopic step once per step before its sub-steps, as the World does, or
// the splitting over each sub-step.
Outcome dzhanibekov(const Dzhanibekov &d, const Config &c, const Quaternion &reference) {
    World world(worldSettings(c, false));
    BodySettings s;
    s.shape = Shape::box(d.halfExtents);
    s.rotation = d.w0;
    const BodyId id = world.addBody(s);
    RigidBody core = world.body(id);
    SplitBody split;
    split.inertia = d.inertia();
    split.momentum = split.inertia.cwiseProduct(d.w0);

    const bool onCore = c.core != CoreScheme::None;
    const RigidBody &body = onCore ? core : world.body(id);
    auto momentum = [&] { return Vector3(body.getInertiaTensorWorld() * body.getRotation()); };
    auto energy = [&] { return 0.5 * body.getRotation().dot(body.getInertiaTensorWorld() * body.getRotation()); };
    const Vector3 l0 = momentum();
    const double e0 = energy();
    double momentumDrift = 0, energyDrift = 0;
    const int steps = stepsFor(d.seconds, c.dt);
    Outcome o;
    o.wallSeconds = timed(
        steps,
        [&] {
            switch (c.core) {
                case CoreScheme::None: world.step(c.dt); return;
                case CoreScheme::BackwardEuler:
                    core.applyGyroscopicStep(GyroscopicStep::BackwardEuler, c.dt);
                    for (int k = 0; k < c.substeps; ++k) core.integrate(c.dt / c.substeps, false);
                    return;
                case CoreScheme::Splitting:
                    for (int k = 0; k < c.substeps; ++k) split.step(c.dt / c.substeps);
                    return;
            }
        },
        [&](int) {
            if (c.core == CoreScheme::Splitting) split.copyTo(core);
            momentumDrift = std::max(momentumDrift, (momentum() - l0).norm() / l0.norm());
            energyDrift = std::max(energyDrift, std::abs(energy() - e0) / e0);
        });
    o.simulatedSeconds = steps * c.dt;
    o.measures.push_back({"momentum", "momentum drift, max |L - L0| / |L0|", momentumDrift});
    o.measures.push_back({"energy", "energy drift, max |E - E0| / E0", energyDrift});
    o.measures.push_back({"attitude", "attitude error at 10 s (rad)", angleBetween(body.getOrientation(), reference)});
    return o;
}

// A unit box sliding at 5 m/s on a plane, friction 0.5 (both): it stops after
// v0^2 / (2 mu g) = 2.548 m.
Outcome slidingBox(const Config &c) {
    const double mu = 0.5, v0 = 5;
    World world(worldSettings(c));
    addGround(world, mu);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = Vector3(0, 0.5 - 0.0001, 0);
    s.velocity = Vector3(v0, 0, 0);
    s.material.friction = mu;
    const BodyId box = world.addBody(s);
    const int steps = stepsFor(3, c.dt);
    Outcome o;
    o.wallSeconds = timed(steps, [&] { world.step(c.dt); }, [](int) {});
    o.simulatedSeconds = steps * c.dt;
    const double exact = v0 * v0 / (2 * mu * kG);
    o.measures.push_back({"distance", "stopping distance error (m)", std::abs(world.body(box).getPosition().x() - exact)});
    return o;
}

// A 0.25 m ball on a 30 degree ramp (friction 0.6, more than the 2/7 tan 30 = 0.165 that
// rolling needs) rolls without slipping at a = 5/7 g sin 30 = 3.504 m/s^2: its mean
// acceleration from 0.25 s (settled on the ramp) to 1.25 s.
Outcome rollingSphere(const Config &c) {
    World world(worldSettings(c));
    const double angle = kPi / 6;
    const Quaternion tilt(Eigen::AngleAxis<real>(angle, Vector3::UnitZ()));
    BodySettings ramp;
    ramp.isStatic = true;
    ramp.shape = Shape::box(Vector3(20, 0.25, 3));
    ramp.orientation = tilt;
    world.addBody(ramp);
    const Vector3 up = tilt * Vector3::UnitY();
    const Vector3 downhill = tilt * -Vector3::UnitX();
    BodySettings s;
    s.shape = Shape::sphere(0.25);
    s.position = up * (0.5 - 0.0001) + downhill * -10.0;
    const BodyId ball = world.addBody(s);
    const int settle = stepsFor(0.25, c.dt), measured = stepsFor(1, c.dt);
    Outcome o;
    double v0 = 0;
    o.wallSeconds = timed(settle + measured, [&] { world.step(c.dt); }, [&](int i) {
        if (i == settle - 1) v0 = world.body(ball).getVelocity().dot(downhill);
    });
    o.simulatedSeconds = (settle + measured) * c.dt;
    const double a = (world.body(ball).getVelocity().dot(downhill) - v0) / (measured * c.dt);
    o.measures.push_back({"acceleration", "acceleration error (m/s^2)", std::abs(a - 5.0 / 7.0 * kG * std::sin(angle))});
    return o;
}

// A 0.1 m ball dropped from 1 m (its bottom) with restitution 0.8: the apex after bounce n
// is e^(2n) h. Error: the worst of the first three apexes.
Outcome bouncingBall(const Config &c) {
    const double e = 0.8, h = 1;
    World world(worldSettings(c));
    addGround(world, 0.6);
    BodySettings s;
    s.shape = Shape::sphere(0.1);
    s.position = Vector3(0, h + 0.1, 0);
    s.material.restitution = e;
    const BodyId ball = world.addBody(s);
    std::vector<double> apex;
    double highest = -1;
    bool rising = false;
    const int steps = stepsFor(3.5, c.dt);
    Outcome o;
    o.wallSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int) {
        const double vy = world.body(ball).getVelocity().y();
        const double y = world.body(ball).getPosition().y() - 0.1;
        if (vy > 0) rising = true;
        if (rising) highest = std::max(highest, y);
        if (rising && vy <= 0 && highest > 0) {
            apex.push_back(highest);
            rising = false;
            highest = -1;
        }
    });
    o.simulatedSeconds = steps * c.dt;
    double error = 0;
    for (int n = 1; n <= 3; ++n) {
        const double expected = std::pow(e, 2 * n) * h;
        error = std::max(error, n <= static_cast<int>(apex.size()) ? std::abs(apex[n - 1] - expected) : expected);
    }
    o.measures.push_back({"apex", "apex height error, first 3 bounces (m)", error});
    return o;
}

// A 1 kg ball on a spring of k = omega^2 (omega = 150 rad/s) to a fixed point, rest length
// 1 m, released 0.1 m stretched, no gravity, no damping: x = 1 + 0.1 cos(omega t). The
// step sweep covers omega dt from 0.1 to 10.
constexpr double kSpringOmega = 150;

Outcome stiffSpring(const Config &c) {
    World world(worldSettings(c, false));
    BodySettings s;
    s.shape = Shape::sphere(0.05);
    s.position = Vector3(1.1, 0, 0);
    const BodyId ball = world.addBody(s);
    SpringSettings spring;
    spring.a = ball;
    spring.stiffness = kSpringOmega * kSpringOmega;
    spring.restLength = 1;
    spring.force = c.springForce;
    world.addSpring(spring);
    auto energy = [&] {
        const double stretch = world.body(ball).getPosition().norm() - 1;
        return world.kineticEnergy() + 0.5 * spring.stiffness * stretch * stretch;
    };
    const double e0 = energy();
    double error = 0, gain = 1;
    const int steps = stepsFor(2, c.dt);
    Outcome o;
    o.wallSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int i) {
        const double t = (i + 1) * c.dt;
        const double x = world.body(ball).getPosition().x();
        error = std::max(error, std::abs(x - (1 + 0.1 * std::cos(kSpringOmega * t))) / 0.1);
        gain = std::max(gain, energy() / e0);
    });
    o.simulatedSeconds = steps * c.dt;
    const auto capped = [](double v) { return std::isfinite(v) ? std::min(v, kDiverged) : kDiverged; };
    o.measures.push_back({"position", "position error / amplitude", capped(error)});
    o.measures.push_back({"energy", "energy gain, max E / E0", capped(gain)});
    o.measures.push_back({"kept", "energy kept at 2 s, E / E0", capped(energy() / e0)});
    return o;
}

// A 10-level pyramid of unit boxes (55, friction 0.6) resting on a plane, 5 s: how far the
// top box moves from its initial pose, and the deepest contact.
Outcome restingPyramid(const Config &c) {
    World world(worldSettings(c));
    addGround(world, 0.6);
    BodyId top;
    const int levels = 10;
    for (int level = 0; level < levels; ++level)
        for (int i = 0; i < levels - level; ++i) {
            BodySettings s;
            s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            s.position = Vector3((i - (levels - 1 - level) / 2.0) * 1.05, 0.5 + level * 0.9999, 0);
            top = world.addBody(s);
        }
    const Vector3 start = world.body(top).getPosition();
    double deepest = 0;
    const int steps = stepsFor(5, c.dt);
    Outcome o;
    o.wallSeconds = timed(steps, [&] { world.step(c.dt); },
                          [&](int) { deepest = std::max(deepest, double(world.stats().maxPenetration)); });
    o.simulatedSeconds = steps * c.dt;
    o.measures.push_back({"drift", "top box drift (m)", (world.body(top).getPosition() - start).norm()});
    o.measures.push_back({"penetration", "deepest penetration (m)", deepest});
    return o;
}

std::string number(double v, int digits = 3);

// --- The sweep -------------------------------------------------------------------------------

struct Scene {
    std::string name;
    std::string description;
    std::vector<Config> configs;
    std::function<Outcome(const Config &)> run;
};

std::string fraction(double dt) { return "1/" + std::to_string(static_cast<int>(std::lround(1 / dt))); }

std::vector<double> steps(bool quick) {
    if (quick) return {1.0 / 15, 1.0 / 60, 1.0 / 240};
    return {1.0 / 15, 1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480, 1.0 / 960};
}

std::vector<Config> sweep(const std::vector<Integrator> &integrators, const std::vector<int> &iterations,
                          const std::vector<int> &substeps, bool quick) {
    std::vector<Config> configs;
    for (Integrator integrator : integrators)
        for (int it : iterations)
            for (int sub : substeps)
                for (double dt : steps(quick)) {
                    Config c;
                    c.integrator = integrator;
                    c.iterations = it;
                    c.substeps = sub;
                    c.dt = dt;
                    configs.push_back(c);
                }
    return configs;
}

std::vector<Scene> scenes(bool quick) {
    std::vector<Scene> all;
    const std::vector<Integrator> seed{Integrator::NewtonEuler};
    const std::vector<Integrator> rotating{Integrator::NewtonEuler, Integrator::NewtonEulerGyroscopic,
                                           Integrator::MomentumConserving};

    all.push_back({"projectile", "ball thrown at (10, 10, 0) m/s, 2 s; closed form x0 + v0 t + g t^2 / 2",
                   sweep(seed, {3}, {1, 4}, quick), [](const Config &c) { return projectile(c, 1); }});
    all.push_back({"projectile-damped",
                   "the same with linear damping 0.5 (half the velocity kept per second); closed form of "
                   "dv/dt = g + ln(0.5) v",
                   sweep(seed, {3}, {1, 4}, quick), [](const Config &c) { return projectile(c, 0.5); }});

    const Dzhanibekov d;
    const Quaternion reference = d.reference(1e-4);
    // The reference's own error: RK4 is fourth order, so halving its step shows it.
    const double referenceError = angleBetween(reference, d.reference(5e-5));
    // newton-euler-implicit turns bodies as newton-euler-gyroscopic does (it differs in
    // its springs only): not repeated here.
    std::vector<Config> spin = sweep(rotating, {3}, {1, 4}, quick);
    for (Config c : sweep(seed, {3}, {1, 4}, quick)) {
        c.core = CoreScheme::BackwardEuler;
        c.integratorName = "rigidbody-backward-euler";
        spin.push_back(c);
    }
    for (Config c : sweep(seed, {3}, {1, 4}, quick)) {
        c.core = CoreScheme::Splitting;
        c.integratorName = "splitting (bench only)";
        spin.push_back(c);
    }
    const auto spinScene = [](const Dzhanibekov &scene, const Quaternion &reference) {
        return [scene, reference](const Config &c) { return dzhanibekov(scene, c, reference); };
    };
    all.push_back({"dzhanibekov",
                   "box 0.1 x 0.4 x 0.9 m, w0 = (0.1, 5, 0.1) rad/s about its intermediate axis, no gravity, 10 s; "
                   "L and E are constant; attitude against RK4 at h = 1e-4 s (which differs from RK4 at "
                   "5e-5 s by " + number(referenceError, 2) + " rad). rigidbody-backward-euler is "
                   "Bullet's and Jolt's form (GyroscopicStep::BackwardEuler, core only), once per step as the "
                   "World does; splitting (bench only) is the free body split into exact rotations about its "
                   "axes (1, 2, 3, 2, 1; Dullweber-Leimkuhler-McLachlan), per sub-step, the alternative to "
                   "momentum-conserving's implicit midpoint rule",
                   spin, spinScene(d, reference)});
    Dzhanibekov tumbling;
    tumbling.w0 = Vector3(1, 2, 3);
    all.push_back({"tumbling-box",
                   "the same box tumbling at w0 = (1, 2, 3) rad/s, about no principal axis; attitude against RK4 "
                   "at h = 1e-4 s",
                   spin, spinScene(tumbling, tumbling.reference(1e-4))});

    all.push_back({"sliding-box", "unit box at 5 m/s on a plane, friction 0.5: stops after v0^2 / (2 mu g) = 2.548 m",
                   sweep(seed, {3, 10}, {1, 4}, quick), slidingBox});
    all.push_back({"rolling-sphere", "0.25 m ball on a 30 degree ramp, friction 0.6: a = 5/7 g sin 30 = 3.504 m/s^2",
                   sweep(seed, {3, 10}, {1, 4}, quick), rollingSphere});
    all.push_back({"bouncing-ball", "0.1 m ball dropped from 1 m, restitution 0.8: apexes e^(2n) h",
                   sweep(seed, {3, 10}, {1, 4}, quick), bouncingBall});

    std::vector<Config> springs = sweep({Integrator::NewtonEuler, Integrator::NewtonEulerImplicit}, {3}, {1, 4}, quick);
    for (Config c : sweep(seed, {3}, {1, 4}, quick)) {
        c.springForce = SpringForce::Explicit;
        springs.push_back(c);
    }
    std::vector<Config> extra;
    for (Config c : springs) {
        if (c.dt != 1.0 / 960) continue;
        c.dt = 1.0 / 1500;  // omega dt = 0.1
        extra.push_back(c);
    }
    springs.insert(springs.end(), extra.begin(), extra.end());
    for (Config &c : springs) {
        std::ostringstream p;
        p.precision(3);
        p << "ωdt " << kSpringOmega * c.dt;
        c.parameter = p.str();
    }
    all.push_back({"stiff-spring",
                   "1 kg on a spring of omega = 150 rad/s, 0.1 m amplitude, no damping, 2 s; closed form "
                   "1 + 0.1 cos(omega t); omega dt from 0.1 to 10. newton-euler: the defaults (SpringForce::"
                   "Automatic: explicit while omega h <= WorldSettings::explicitSpringLimit = 0.8, backward Euler "
                   "beyond, h = dt / sub-steps); newton-euler (explicit springs): SpringForce::Explicit, the "
                   "seed's force whatever omega h; newton-euler-implicit: backward Euler always",
                   springs, stiffSpring});

    // Contacts and joints: impacts (penetration on landing), joint error (chain, heavy chain,
    // pendulum period) and rolling resistance go here, with the features they measure.
    all.push_back({"resting-pyramid", "10-level pyramid of unit boxes (55) on a plane, 5 s: drift of the top box, "
                                      "deepest contact",
                   sweep(seed, {3, 10}, {1, 4}, quick), restingPyramid});
    return all;
}

// --- Output ----------------------------------------------------------------------------------

std::string number(double v, int digits) {
    if (v >= kDiverged) return "diverged";
    std::ostringstream out;
    out.precision(digits);
    out << v;
    return out.str();
}

std::string configLabel(const Config &c, bool withSolver) {
    std::string label = integratorName(c) + ", " + std::to_string(c.substeps) + " sub-step" + (c.substeps > 1 ? "s" : "");
    if (withSolver) label += " x " + std::to_string(c.iterations) + " it";
    return label;
}

bool contactScene(const std::string &scene) {
    return scene == "sliding-box" || scene == "rolling-sphere" || scene == "bouncing-ball" || scene == "resting-pyramid";
}

void writeCsv(const std::string &path, const std::vector<Row> &rows) {
    std::ofstream out(path);
    out << "scene,measure,integrator,dt,iterations,substeps,parameter,wall_ms_per_simulated_s,error\n";
    out.precision(9);
    for (const Row &r : rows)
        out << r.scene << ",\"" << r.measure << "\"," << integratorName(r.config) << "," << r.config.dt << ","
            << r.config.iterations << "," << r.config.substeps << ",\"" << r.config.parameter << "\","
            << r.wallMsPerSimSecond << "," << r.error << "\n";
}

// A configuration's look, the same in every plot: a colour per scheme and sub-step count
// (a strong shade for 4 sub-steps, a lighter, dashed one for 1), open points for 10
// iterations.
std::string lineStyle(const Config &c) {
    static const std::map<std::string, std::pair<const char *, const char *>> colours = {
        {"newton-euler", {"#1f4e9c", "#6fa8dc"}},
        {"newton-euler (explicit springs)", {"#7f7f7f", "#b0b0b0"}},
        {"newton-euler-gyroscopic", {"#b8860b", "#e6b800"}},
        {"newton-euler-implicit", {"#2e7d32", "#81c784"}},
        {"momentum-conserving", {"#c62828", "#ef7f7f"}},
        {"rigidbody-backward-euler", {"#6a1b9a", "#b39ddb"}},
        {"splitting (bench only)", {"#00838f", "#80deea"}},
    };
    const auto found = colours.find(integratorName(c));
    const auto shades = found != colours.end() ? found->second : std::make_pair("#000000", "#555555");
    const bool one = c.substeps == 1;
    std::string style = std::string("lc rgb '") + (one ? shades.second : shades.first) + "' lw 2 dt " +
                        (one ? "2" : "1") + " pt " + (c.iterations > 3 ? "6" : "7") + " ps 0.8";
    return style;
}

// One gnuplot script per scene and measure: error against wall time, log-log, one line per
// configuration through its step sizes.
std::string writePlot(const std::string &plotsDir, const std::string &outDir, const std::string &scene,
                      const std::string &key, const std::string &measure, const std::vector<const Row *> &rows) {
    const std::string name = scene + "-" + key;
    std::map<std::string, std::vector<const Row *>> series;
    std::vector<std::string> order;
    std::map<std::string, std::string> styles;
    for (const Row *r : rows) {
        const std::string label = configLabel(r->config, contactScene(scene));
        if (!series.count(label)) order.push_back(label);
        series[label].push_back(r);
        styles[label] = lineStyle(r->config);
    }
    std::ofstream data(plotsDir + "/" + name + ".dat");
    data.precision(9);
    for (const std::string &label : order) {
        data << "# " << label << "\n";
        for (const Row *r : series[label]) {
            if (r->error >= kDiverged || !(r->error > 0)) continue;
            const std::string label = r->config.parameter.empty() ? fraction(r->config.dt) : r->config.parameter;
            data << r->wallMsPerSimSecond << " " << r->error << " \"" << label << "\"\n";
        }
        data << "\n\n";
    }
    std::ofstream gp(plotsDir + "/" + name + ".gp");
    // Legend below the plot, outside it, so it never covers a line.
    const int legendRows = static_cast<int>((order.size() + 1) / 2);
    gp << "set terminal svg size 900," << 560 + 22 * legendRows << " dynamic font 'sans,12' background rgb 'white'\n"
       << "set output '" << outDir << "/" << name << ".svg'\n"
       << "set title \"" << scene << ": " << measure << "\"\n"
       << "set xlabel 'wall time per simulated second (ms)'\n"
       << "set ylabel \"" << measure << "\"\n"
       << "set logscale xy\nset format y '10^{%L}'\nset grid\nset key outside below left maxcols 2 noenhanced\n"
       << "plot ";
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (i) gp << ", \\\n     ";
        gp << "'" << plotsDir << "/" << name << ".dat' index " << i << " using 1:2 with linespoints "
           << styles[order[i]] << " title \"" << order[i] << "\"";
        if (i == 0) gp << ", '' index 0 using 1:2:3 with labels offset 1.2,0.6 font ',8' notitle";
    }
    gp << "\n";
    return name + ".svg";
}

// The result of one configuration, or nullptr (a --quick run has fewer step sizes).
const Row *lookup(const std::vector<Row> &rows, const std::string &scene, const std::string &key,
                  const std::string &scheme, int substeps, double dt, int iterations = 3) {
    for (const Row &r : rows)
        if (r.scene == scene && r.key == key && integratorName(r.config) == scheme && r.config.substeps == substeps &&
            r.config.iterations == iterations && std::abs(r.config.dt - dt) < 1e-12)
            return &r;
    return nullptr;
}

std::string value(const Row *r) { return r ? number(r->error, 3) : "n/a"; }
std::string cost(const Row *r) { return r ? number(r->wallMsPerSimSecond, 2) + " ms" : "n/a"; }

// Which setting to pick for what, with the figures that say why, from this run.
void writeSummary(std::ostream &md, const std::vector<Row> &rows) {
    const double dt = 1.0 / 60;
    const auto at = [&](const std::string &scene, const std::string &key, const std::string &scheme, int substeps = 4,
                        double step = 1.0 / 60, int iterations = 3) {
        return lookup(rows, scene, key, scheme, substeps, step, iterations);
    };
    const std::string ne = "newton-euler", gyro = "newton-euler-gyroscopic", mc = "momentum-conserving",
                      implicit = "newton-euler-implicit", split = "splitting (bench only)",
                      explicitSprings = "newton-euler (explicit springs)";
    md << "\n## Which setting to pick\n\n"
       << "Figures at 1/60 s steps, 4 sub-steps and 3 iterations unless said; cost is wall time per simulated "
       << "second.\n\n"
       << "| you simulate | pick | why (measured below) |\n|---|---|---|\n";
    md << "| most scenes: stacks, sliding, rolling, bouncing, thrown things | the defaults (`newton-euler`, 4 "
       << "sub-steps, 3 iterations) | first order (projectile " << value(at("projectile", "position", ne))
       << " m off after 2 s, " << value(at("projectile", "position", ne, 4, dt / 2))
       << " m at 1/120 s); sliding box " << value(at("sliding-box", "distance", ne, 1)) << " m short with 1 sub-step ("
       << cost(at("sliding-box", "distance", ne, 1)) << "), " << value(at("sliding-box", "distance", ne))
       << " m with 4 (" << cost(at("sliding-box", "distance", ne)) << "), "
       << value(at("sliding-box", "distance", ne, 4, dt, 10)) << " m with 4 and 10 iterations ("
       << cost(at("sliding-box", "distance", ne, 4, dt, 10)) << "); resting pyramid top box "
       << value(at("resting-pyramid", "drift", ne)) << " m from its start after 5 s |\n";
    md << "| asymmetric bodies spinning freely (tools, debris, satellites, the Dzhanibekov effect) | `" << mc << "` | "
       << "Dzhanibekov box over 10 s: angular momentum drift " << value(at("dzhanibekov", "momentum", mc))
       << " and energy drift " << value(at("dzhanibekov", "energy", mc)) << " (`" << gyro << "`: "
       << value(at("dzhanibekov", "momentum", gyro)) << " and " << value(at("dzhanibekov", "energy", gyro))
       << "); attitude error " << value(at("dzhanibekov", "attitude", mc)) << " rad, "
       << value(at("dzhanibekov", "attitude", mc, 4, dt / 2)) << " at 1/120 s (second order; `" << gyro << "`: "
       << value(at("dzhanibekov", "attitude", gyro)) << ", `" << ne << "`: "
       << value(at("dzhanibekov", "attitude", ne)) << "); cost " << cost(at("dzhanibekov", "attitude", mc))
       << " against " << cost(at("dzhanibekov", "attitude", gyro)) << " and " << cost(at("dzhanibekov", "attitude", ne))
       << " |\n";
    md << "| stiff springs, with the defaults | nothing to do | a spring beyond omega h = 0.8 gets the backward-Euler "
       << "force by itself: at omega dt = 10 the largest E / E0 is " << value(at("stiff-spring", "energy", ne, 4, 1.0 / 15))
       << " (explicit: " << value(at("stiff-spring", "energy", explicitSprings, 4, 1.0 / 15))
       << "); springs below it are untouched: at omega dt = 0.31 the energy kept after 2 s is "
       << value(at("stiff-spring", "kept", ne, 4, 1.0 / 480)) << ", as with explicit springs ("
       << value(at("stiff-spring", "kept", explicitSprings, 4, 1.0 / 480)) << ") |\n";
    md << "| springs that must hold still rather than ring | `" << implicit << "` | every spring backward Euler: "
       << "never gains energy, and damps: at omega dt = 2.5 it keeps " << value(at("stiff-spring", "kept", implicit))
       << " of its energy after 2 s |\n";
    md << "| an undamped oscillation that must keep its amplitude | explicit springs (`SpringSettings::force = "
       << "Explicit`) and sub-steps enough for omega h well below 2 | symplectic Euler keeps a modified energy: "
       << "largest E / E0 " << value(at("stiff-spring", "energy", explicitSprings, 4, 1.0 / 480))
       << " at omega dt = 0.31 |\n";
    md << "\nWhy `" << mc << "` uses the implicit midpoint rule rather than a splitting into rotations about the "
       << "body axes (`" << split << "` in the tables, run on its own, without a World around it): the "
       << "splitting keeps the energy only to O(h^2), a drift of " << value(at("dzhanibekov", "energy", split))
       << " on the Dzhanibekov box (" << mc << ": " << value(at("dzhanibekov", "energy", mc))
       << "). At the same step its attitude error is "
       << value(at("dzhanibekov", "attitude", split)) << " rad there (" << mc << ": "
       << value(at("dzhanibekov", "attitude", mc)) << ") and " << value(at("tumbling-box", "attitude", split))
       << " rad on the tumbling box (" << value(at("tumbling-box", "attitude", mc)) << "). It is cheaper: "
       << cost(at("dzhanibekov", "energy", split)) << " per simulated second alone, where " << mc
       << " costs " << cost(at("dzhanibekov", "energy", mc)) << " in the World against "
       << cost(at("dzhanibekov", "energy", ne)) << " for the seed's step.\n";
    md << "\n## Impacts, joints, rolling resistance\n\n"
       << "Not measured yet: the scenes for penetration on landing, joint error (chain, heavy chain, "
       << "pendulum period) and rolling resistance come with the features they measure, added to "
       << "`scenes()` in bench/accuracy.cpp under \"Contacts and joints\" the same way as the scenes below.\n";
}

void writeMarkdown(const std::string &path, const std::vector<Scene> &all, const std::vector<Row> &rows,
                   const std::map<std::string, std::vector<std::string>> &plots, double seconds, bool quick) {
    std::ofstream md(path);
    md << "# Accuracy against cost\n\n"
       << "Generated by `bash scripts/accuracy.sh` (bench/accuracy.cpp" << (quick ? ", --quick" : "")
       << "); every number below is measured, the wall times on the machine that ran it. The whole sweep took "
       << number(seconds, 3) << " s. Full data: [results.csv](results.csv).\n\n"
       << "Each scene runs at step sizes from 1/15 s to 1/960 s and the solver settings shown; \"it\" is "
       << "velocity iterations per sub-step. Errors are against the closed form or converged reference "
       << "named. Wall time is per simulated second (ms), stepping only, the fastest of up to five "
       << "identical runs when a run is short. In the plots each configuration has one colour "
       << "throughout: a strong shade for 4 sub-steps, a lighter dashed one for 1, open points for 10 "
       << "iterations.\n";
    writeSummary(md, rows);
    for (const Scene &scene : all) {
        md << "\n## " << scene.name << "\n\n" << scene.description << ".\n";
        std::vector<std::string> measures;
        for (const Row &r : rows)
            if (r.scene == scene.name && std::find(measures.begin(), measures.end(), r.measure) == measures.end())
                measures.push_back(r.measure);
        for (const std::string &measure : measures) {
            md << "\n### " << measure << "\n\n";
            const auto found = plots.find(scene.name + "|" + measure);
            if (found != plots.end()) md << "![" << scene.name << ": " << measure << "](" << found->second[0] << ")\n\n";
            // Pivot: one line per configuration, one column per step size; cells "error (ms/s)".
            std::vector<double> dts;
            std::vector<std::string> labels;
            std::map<std::string, std::map<double, const Row *>> cells;
            for (const Row &r : rows) {
                if (r.scene != scene.name || r.measure != measure) continue;
                const std::string label = configLabel(r.config, contactScene(scene.name));
                if (std::find(labels.begin(), labels.end(), label) == labels.end()) labels.push_back(label);
                if (std::find(dts.begin(), dts.end(), r.config.dt) == dts.end()) dts.push_back(r.config.dt);
                cells[label][r.config.dt] = &r;
            }
            std::sort(dts.begin(), dts.end(), std::greater<>());
            md << "| configuration |";
            for (double dt : dts) {
                md << " " << fraction(dt);
                if (scene.name == "stiff-spring") md << " (ωdt " << number(kSpringOmega * dt, 2) << ")";
                md << " |";
            }
            md << "\n|---|";
            for (std::size_t i = 0; i < dts.size(); ++i) md << "--:|";
            md << "\n";
            for (const std::string &label : labels) {
                md << "| " << label << " |";
                for (double dt : dts) {
                    const auto cell = cells[label].find(dt);
                    if (cell == cells[label].end()) {
                        md << " |";
                        continue;
                    }
                    md << " " << number(cell->second->error) << " <sub>(" << number(cell->second->wallMsPerSimSecond, 2)
                       << " ms)</sub> |";
                }
                md << "\n";
            }
        }
    }
}

int run(int argc, char **argv) {
    std::string outDir = "docs/accuracy", plotsDir = ".";
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out" && i + 1 < argc) outDir = argv[++i];
        else if (arg == "--plots" && i + 1 < argc) plotsDir = argv[++i];
        else if (arg == "--quick") quick = true;
        else {
            std::cerr << "usage: cyclone-accuracy [--out DIR] [--plots DIR] [--quick]\n"
                         "  --out DIR    results.csv, README.md and (through the scripts) the plots; default docs/accuracy\n"
                         "  --plots DIR  gnuplot data and scripts, one per scene and measure; default .\n"
                         "  --quick      three step sizes instead of seven\n";
            return 2;
        }
    }
    const auto start = std::chrono::steady_clock::now();
    const std::vector<Scene> all = scenes(quick);
    std::vector<Row> rows;
    for (const Scene &scene : all) {
        const auto t0 = std::chrono::steady_clock::now();
        for (const Config &c : scene.configs) {
            // Runs are deterministic: repeating a short one and keeping its fastest time
            // only removes interference from the rest of the machine.
            Outcome o = scene.run(c);
            for (int repeat = 1; repeat < 5 && o.wallSeconds < 0.05; ++repeat)
                o.wallSeconds = std::min(o.wallSeconds, scene.run(c).wallSeconds);
            for (const Measure &m : o.measures)
                rows.push_back({scene.name, m.key, m.name, c, 1000 * o.wallSeconds / o.simulatedSeconds, m.value});
        }
        std::cerr << scene.name << ": " << scene.configs.size() << " runs, "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::map<std::string, std::vector<std::string>> plots;
    for (const Scene &scene : all) {
        std::map<std::string, std::vector<const Row *>> byMeasure;
        std::vector<std::string> measures;
        for (const Row &r : rows) {
            if (r.scene != scene.name) continue;
            if (!byMeasure.count(r.measure)) measures.push_back(r.measure);
            byMeasure[r.measure].push_back(&r);
        }
        for (const std::string &m : measures)
            plots[scene.name + "|" + m].push_back(
                writePlot(plotsDir, outDir, scene.name, byMeasure[m].front()->key, m, byMeasure[m]));
    }
    writeCsv(outDir + "/results.csv", rows);
    writeMarkdown(outDir + "/README.md", all, rows, plots, seconds, quick);
    std::cerr << rows.size() << " results in " << seconds << " s: " << outDir << "/results.csv, " << outDir
              << "/README.md\n";
    return 0;
}

}  // namespace
}  // namespace cyclone::accuracy

int main(int argc, char **argv) { return cyclone::accuracy::run(argc, argv); }
