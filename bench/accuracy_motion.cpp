// cyclone-accuracy's scenes of free motion, springs and the first contact scenes: each
// has a closed form or a converged reference (accuracy.h).
#include <algorithm>
#include <ctime>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "accuracy.h"
#include "scene_loader.h"

namespace cyclone::accuracy {

std::string integratorName(const Config &c) {
    if (!c.integratorName.empty()) return c.integratorName;
    for (const scene::IntegratorName &entry : scene::kIntegrators)
        if (entry.integrator == c.integrator)
            return std::string(entry.name) + (c.springForce == SpringForce::Explicit ? " (explicit springs)" : "") +
                   (c.speculativeContacts ? "" : " (no speculative contacts)");
    return "?";
}

void applyConfig(const Config &c, WorldSettings &s) {
    s.sleep = false;
    s.integrator = c.integrator;
    s.velocityIterations = c.iterations;
    s.substeps = c.substeps;
    s.debug.speculativeContacts = c.speculativeContacts;
}

WorldSettings worldSettings(const Config &c, bool gravity) {
    WorldSettings s;
    applyConfig(c, s);
    if (!gravity) s.gravity = Vector3::Zero();
    return s;
}

int stepsFor(double seconds, double dt) { return static_cast<int>(std::lround(seconds / dt)); }

// The process's CPU time, s (the World steps on this thread: WorldSettings::threads is 1).
double cpuNow() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double timed(int steps, const std::function<void()> &step, const std::function<void(int)> &after) {
    double seconds = 0;
    for (int i = 0; i < steps; ++i) {
        const double t0 = cpuNow();
        step();
        seconds += cpuNow() - t0;
        after(i);
    }
    return seconds;
}

BodyId addGround(World &world, double friction) {
    BodySettings g;
    g.motion = Motion::Static;
    g.shape = Shape::plane(Vector3::UnitY(), 0);
    g.material.friction = friction;
    return world.addBody(g);
}

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

namespace {

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
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [](int) {});
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
    o.cpuSeconds = timed(
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
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [](int) {});
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
    ramp.motion = Motion::Static;
    ramp.shape = Shape::box(Vector3(20, 0.25, 3));
    ramp.orientation = tilt;
    // No rolling resistance (a pair takes the larger of its two): the closed form is that
    // of rolling without it; the rolling-resistance scene measures the resistance.
    ramp.material.rollingFriction = 0;
    world.addBody(ramp);
    const Vector3 up = tilt * Vector3::UnitY();
    const Vector3 downhill = tilt * -Vector3::UnitX();
    BodySettings s;
    s.shape = Shape::sphere(0.25);
    s.material.rollingFriction = 0;
    s.position = up * (0.5 - 0.0001) + downhill * -10.0;
    const BodyId ball = world.addBody(s);
    const int settle = stepsFor(0.25, c.dt), measured = stepsFor(1, c.dt);
    Outcome o;
    double v0 = 0;
    o.cpuSeconds = timed(settle + measured, [&] { world.step(c.dt); }, [&](int i) {
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
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int) {
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
// step sweep covers omega dt from 0.1 to 10 (kSpringOmega).
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
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int i) {
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
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); },
                          [&](int) { deepest = std::max(deepest, double(world.stats().maxPenetration)); });
    o.simulatedSeconds = steps * c.dt;
    o.measures.push_back({"drift", "top box drift (m)", (world.body(top).getPosition() - start).norm()});
    o.measures.push_back({"penetration", "deepest penetration (m)", deepest});
    return o;
}

}  // namespace

void addMotionScenes(std::vector<Scene> &all, bool quick) {
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
    all.push_back({"rolling-sphere",
                   "0.25 m ball on a 30 degree ramp, friction 0.6, no rolling resistance: a = 5/7 g sin 30 = 3.504 m/s^2",
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

    all.push_back({"resting-pyramid", "10-level pyramid of unit boxes (55) on a plane, 5 s: drift of the top box, "
                                      "deepest contact",
                   sweep(seed, {3, 10}, {1, 4}, quick), restingPyramid});
}

}  // namespace cyclone::accuracy
