// cyclone-accuracy's scenes of what the World added to the seed: impacts (penetration on
// landing, with and without speculative contacts), joints (chains and a pendulum against
// its closed form) and rolling resistance (a ball's deceleration against its closed form).
// The drops and chains are the shipped scene files (examples/scenes), loaded as the
// runner loads them, with the sweep's settings put over theirs.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "accuracy.h"
#include "scene_loader.h"
#include "scene_world.h"

namespace cyclone::accuracy {

std::string scenesDirectory() { return CYCLONE_ACCURACY_SCENES; }

namespace {

// A shipped scene with `c`'s settings (integrator, sub-steps, iterations, speculative
// contacts; sleep off) over the file's.
scene::Scene shippedScene(const std::string &file, const Config &c) {
    const std::string path = scenesDirectory() + "/" + file;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cyclone-accuracy: cannot read " + path);
    std::stringstream text;
    text << in.rdbuf();
    scene::Scene s = scene::loadScene(text.str(), file);
    applyConfig(c, s.world);
    return s;
}

std::size_t bodyIndex(const scene::Scene &s, const std::string &name) {
    for (std::size_t i = 0; i < s.bodies.size(); ++i)
        if (s.bodies[i].settings.name == name) return i;
    throw std::runtime_error("cyclone-accuracy: no body '" + name + "' in scene " + s.name);
}

// --- Impacts ---------------------------------------------------------------------------------

// examples/scenes/drops.json: a 0.25 m ball dropped from 5 m (its bottom) and a unit crate
// from 10 m onto the ground plane, a unit box from 6 m onto a unit box resting on it. The
// deepest each gets into what it lands on over 3 s (the crate lands at 1.43 s), from the
// positions after each step: ball 0.25 - y, crate 0.5 - y, box (base top) - (its bottom).
// Exact: 0 (rigid bodies stop at the surface).
Outcome drops(const Config &c) {
    scene::Scene s = shippedScene("drops.json", c);
    const std::size_t ballIndex = bodyIndex(s, "ball"), crateIndex = bodyIndex(s, "crate"),
                      baseIndex = bodyIndex(s, "base"), droppedIndex = bodyIndex(s, "dropped");
    scene::SceneWorld built = scene::buildWorld(s);
    World &world = built.world;
    const BodyId ball = built.ids[ballIndex], crate = built.ids[crateIndex], base = built.ids[baseIndex],
                 dropped = built.ids[droppedIndex];
    double ballDepth = 0, crateDepth = 0, boxDepth = 0;
    const int steps = stepsFor(3, c.dt);
    Outcome o;
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int) {
        ballDepth = std::max(ballDepth, 0.25 - world.body(ball).getPosition().y());
        crateDepth = std::max(crateDepth, 0.5 - world.body(crate).getPosition().y());
        boxDepth = std::max(boxDepth, (world.body(base).getPosition().y() + 0.5) -
                                          (world.body(dropped).getPosition().y() - 0.5));
    });
    o.simulatedSeconds = steps * c.dt;
    o.measures.push_back({"ball", "ball (0.25 m) from 5 m: deepest penetration (m)", ballDepth});
    o.measures.push_back({"crate", "crate (1 m) from 10 m: deepest penetration (m)", crateDepth});
    o.measures.push_back({"box-on-box", "box (1 m) from 6 m onto a box: deepest penetration (m)", boxDepth});
    return o;
}

// --- Joints ----------------------------------------------------------------------------------

// A chain of examples/scenes (chain-20*.json: 20 links of 0.5 m, 1 kg, joined by ball
// joints, hanging from a fixed point, a 100 kg ball at the end of the heavy ones), 10 s:
// the largest gap of any joint after any step (World::jointState().error). Exact: 0.
Outcome chain(const std::string &file, const Config &c) {
    scene::Scene s = shippedScene(file, c);
    scene::SceneWorld built = scene::buildWorld(s);
    World &world = built.world;
    double gap = 0;
    const int steps = stepsFor(10, c.dt);
    Outcome o;
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int) {
        for (const JointId &j : built.joints) gap = std::max(gap, double(world.jointState(j).error));
    });
    o.simulatedSeconds = steps * c.dt;
    o.measures.push_back({"gap", "largest joint gap over 10 s (m)", gap});
    return o;
}

// Complete elliptic integral of the first kind, K(k) = integral over [0, pi/2] of
// 1 / sqrt(1 - k^2 sin^2 t): pi / (2 AGM(1, sqrt(1 - k^2))), the arithmetic-geometric
// mean converging quadratically.
double ellipticK(double k) {
    double a = 1, b = std::sqrt(1 - k * k);
    while (std::abs(a - b) > 1e-15 * a) {
        const double mean = (a + b) / 2;
        b = std::sqrt(a * b);
        a = mean;
    }
    return kPi / (2 * a);
}

// The pendulum of examples/scenes/pendulum.json: a 1 kg ball of radius r = 0.05 m whose
// centre hangs L = 1 m below a ball joint to the world, released at rest th0 = 10 degrees
// from the vertical, 10 s. The joint makes the ball turn with the rod, so it is a physical
// pendulum: I th'' = -m g L sin th with I = m L^2 + (2/5) m r^2 about the pivot, i.e. a
// simple pendulum of length Leq = I / (m L) = L + 0.4 r^2 / L = 1.001 m. Its exact period
// (energy: th'^2 = 2 (g / Leq) (cos th - cos th0); substituting sin(th/2) = k sin(phi),
// k = sin(th0/2), turns the quarter period into sqrt(Leq/g) K(k)):
//   T = 4 sqrt(Leq / g) K(sin(th0 / 2)) = 2.010897 s
// (the small-angle 2 pi sqrt(Leq/g) is 2.007 s, 0.19 % short). Measured: the mean time
// between the ball's crossings of the vertical from +x to -x (linear interpolation between
// steps); the energy (kinetic, with rotation, plus m g times the height above the lowest
// point), which stays m g L (1 - cos th0) exactly; the joint's gap.
Outcome pendulum(const Config &c) {
    const double length = 1, radius = 0.05, th0 = 10 * kPi / 180;
    const Vector3 pivot(0, 10, 0);
    World world(worldSettings(c));
    BodySettings s;
    s.shape = Shape::sphere(radius);
    s.mass = 1;
    s.position = pivot + length * Vector3(std::sin(th0), -std::cos(th0), 0);
    const BodyId bob = world.addBody(s);
    JointSettings j;
    j.type = JointType::Ball;
    j.a = bob;
    j.anchor = pivot;
    const JointId joint = world.addJoint(j);
    const RigidBody &body = world.body(bob);
    const double lowest = pivot.y() - length;
    auto energy = [&] {
        const Vector3 v = body.getVelocity(), w = body.getRotation();
        return 0.5 * body.getMass() * v.squaredNorm() + 0.5 * w.dot(body.getInertiaTensorWorld() * w) +
               body.getMass() * kG * (body.getPosition().y() - lowest);
    };
    const double e0 = energy();
    double drift = 0, gap = 0, previousX = body.getPosition().x() - pivot.x();
    std::vector<double> crossings;
    const int steps = stepsFor(10, c.dt);
    Outcome o;
    o.cpuSeconds = timed(steps, [&] { world.step(c.dt); }, [&](int i) {
        const double x = body.getPosition().x() - pivot.x();
        if (previousX > 0 && x <= 0) crossings.push_back((i + previousX / (previousX - x)) * c.dt);
        previousX = x;
        drift = std::max(drift, std::abs(energy() - e0) / e0);
        gap = std::max(gap, double(world.jointState(joint).error));
    });
    o.simulatedSeconds = steps * c.dt;
    const double equivalent = length + 0.4 * radius * radius / length;
    const double exact = 4 * std::sqrt(equivalent / kG) * ellipticK(std::sin(th0 / 2));
    const double period = crossings.size() >= 2 ? (crossings.back() - crossings.front()) / (crossings.size() - 1) : 0;
    o.measures.push_back({"period", "period error, |T - T_exact| / T_exact", std::abs(period - exact) / exact});
    o.measures.push_back({"energy", "energy drift, max |E - E0| / E0", drift});
    o.measures.push_back({"gap", "largest joint gap over 10 s (m)", gap});
    return o;
}

// --- Rolling resistance ----------------------------------------------------------------------

// A solid ball (radius R = 0.25 m, 1 kg, I = 2/5 m R^2) rolling at v0 = 2 m/s along +x on
// the ground plane (friction 0.6), rolling friction mu_r = 0.01 m. The model
// (docs/solver.md): the contact's rolling rows resist the rolling with a torque of at most
// mu_r N, N = m g; rolling wants it stopped, so the torque is mu_r m g. With w = -v / R
// about z (rolling without slipping) and the ground's friction force F along x at the
// contact point (0, -R, 0):
//   m dv/dt = F,   I dw_z/dt = R F + mu_r m g   (the contact's torque (-R y) x (F x) = R F z;
//                                                 the resisting torque opposes w_z < 0)
// and dw_z/dt = -a / R, so -I a / R = R m a + mu_r m g, and the deceleration is
//   a = mu_r g / (R (1 + I / (m R^2))) = (5/7) g mu_r / R = 0.2803 m/s^2.
// (F = -(2/7) m g mu_r / R: 0.08 N, far inside the 5.9 N friction allows.) Measured: the
// mean deceleration from 0.25 s to 2.25 s (the ball stops at 7.1 s).
Outcome rollingResistance(const Config &c) {
    const double radius = 0.25, mu = 0.01, v0 = 2;
    World world(worldSettings(c));
    addGround(world, 0.6);
    BodySettings s;
    s.shape = Shape::sphere(radius);
    s.mass = 1;
    s.position = Vector3(0, radius, 0);
    s.velocity = Vector3(v0, 0, 0);
    s.rotation = Vector3(0, 0, -v0 / radius);
    s.material.rollingFriction = mu;
    const BodyId ball = world.addBody(s);
    const int settle = stepsFor(0.25, c.dt), measured = stepsFor(2, c.dt);
    double vStart = 0;
    Outcome o;
    o.cpuSeconds = timed(settle + measured, [&] { world.step(c.dt); }, [&](int i) {
        if (i == settle - 1) vStart = world.body(ball).getVelocity().x();
    });
    o.simulatedSeconds = (settle + measured) * c.dt;
    const double a = (vStart - world.body(ball).getVelocity().x()) / (measured * c.dt);
    const double exact = 5.0 / 7.0 * kG * mu / radius;
    o.measures.push_back({"deceleration", "deceleration error, |a - a_exact| / a_exact", std::abs(a - exact) / exact});
    return o;
}

}  // namespace

void addContactScenes(std::vector<Scene> &all, bool quick) {
    const std::vector<Integrator> seed{Integrator::NewtonEuler};
    std::vector<Config> impacts = sweep(seed, {3}, {1, 4}, quick);
    for (Config c : sweep(seed, {3}, {1, 4}, quick)) {
        c.speculativeContacts = false;
        impacts.push_back(c);
    }
    all.push_back({"drops",
                   "examples/scenes/drops.json, 3 s: a 0.25 m ball from 5 m and a unit crate from 10 m onto the "
                   "ground, a unit box from 6 m onto a unit box; the deepest each gets into what it lands on "
                   "(exact: 0). newton-euler: the defaults, speculative contacts on; (no speculative contacts): "
                   "DebugSettings::speculativeContacts = false, contacts only within speculativeDistance "
                   "(2 cm) at the start of a step. Cost is the whole scene's",
                   impacts, drops});

    const std::vector<Config> joints = sweep(seed, {3}, {1, 4}, quick);
    // The hanging chains start straight, at rest, at equilibrium: they show that nothing
    // drifts, which three step sizes show as well as seven.
    const std::vector<Config> hanging = sweep(seed, {3}, {1, 4}, true);
    all.push_back({"chain-20",
                   "examples/scenes/chain-20.json: 20 links (0.5 m, 1 kg) on ball joints hanging from a fixed "
                   "point, starting straight, 10 s; largest joint gap (exact: 0)",
                   hanging, [](const Config &c) { return chain("chain-20.json", c); }});
    all.push_back({"chain-20-heavy",
                   "examples/scenes/chain-20-heavy.json: the same with a 100 kg ball at its end",
                   hanging, [](const Config &c) { return chain("chain-20-heavy.json", c); }});
    all.push_back({"chain-20-heavy-swing",
                   "examples/scenes/chain-20-heavy-swing.json: the heavy chain released horizontally, swinging",
                   joints, [](const Config &c) { return chain("chain-20-heavy-swing.json", c); }});
    all.push_back({"pendulum",
                   "1 kg ball (r = 0.05 m) 1 m below a ball joint, released at 10 degrees, 10 s; exact period "
                   "4 sqrt(Leq / g) K(sin 5 deg) = 2.010897 s with Leq = L + 0.4 r^2 / L (K the complete "
                   "elliptic integral of the first kind), energy constant",
                   joints, pendulum});

    all.push_back({"rolling-resistance",
                   "0.25 m solid ball rolling at 2 m/s on a plane, rolling friction 0.01 m: decelerates at "
                   "a = (5/7) g mu_r / R = 0.2803 m/s^2 (torque mu_r m g; derivation in bench/accuracy_contacts.cpp); "
                   "mean deceleration from 0.25 s to 2.25 s",
                   sweep(seed, {3, 10}, {1, 4}, quick), rollingResistance});
}

}  // namespace cyclone::accuracy
