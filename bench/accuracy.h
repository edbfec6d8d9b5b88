// cyclone-accuracy's shared parts: what a configuration is, what a run gives, the sweep
// of step sizes, and the scene lists (accuracy_motion.cpp: free motion, springs and the
// first contact scenes; accuracy_contacts.cpp: impacts, joints, rolling resistance).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cyclone/world.h"

namespace cyclone::accuracy {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kG = 9.81;
// Errors beyond this are a divergence, shown as such (and kept out of the plots' range).
inline constexpr double kDiverged = 1e9;
// The stiff spring's angular frequency, rad/s (accuracy_motion.cpp).
inline constexpr double kSpringOmega = 150;

// Schemes the bench runs on a bare RigidBody, for comparison with the World's.
enum class CoreScheme {
    None,           // the World with Config::integrator
    BackwardEuler,  // GyroscopicStep::BackwardEuler once per step, then integrate (Bullet's and Jolt's form)
    Splitting,      // the free rigid body split into exact rotations about the body axes
};

struct Config {
    Integrator integrator = Integrator::NewtonEuler;
    CoreScheme core = CoreScheme::None;
    std::string integratorName;  // overrides the scene-file name (reference schemes)
    SpringForce springForce = SpringForce::Automatic;
    bool speculativeContacts = true;  // DebugSettings::speculativeContacts
    double dt = 1.0 / 60;
    int iterations = 3;
    int substeps = 4;
    std::string parameter;  // scene-specific, e.g. "omega dt = 2.5"
};

struct Row {
    std::string scene;
    std::string key;
    std::string measure;
    Config config;
    double cpuMsPerSimSecond = 0;
    double error = 0;
};

struct Measure {
    std::string key;   // short, for file names
    std::string name;  // what it is, with its unit
    double value;
};

struct Outcome {
    double simulatedSeconds = 0;
    double cpuSeconds = 0;  // the stepping's, on the process's CPU clock
    std::vector<Measure> measures;
};

struct Scene {
    std::string name;
    std::string description;
    std::vector<Config> configs;
    std::function<Outcome(const Config &)> run;
};

/// The scheme's name as scene files spell it, with what sets the configuration apart
/// ("newton-euler (explicit springs)", "newton-euler (no speculative contacts)").
std::string integratorName(const Config &c);
/// The World's settings for `c`: sleep off, gravity -9.81 in y unless `gravity` is false.
WorldSettings worldSettings(const Config &c, bool gravity = true);
/// `c`'s fields copied onto settings made elsewhere (a scene file's).
void applyConfig(const Config &c, WorldSettings &s);
int stepsFor(double seconds, double dt);
/// The CPU time of `steps` calls of `step`, calling `after` (not timed) after each; s.
double timed(int steps, const std::function<void()> &step, const std::function<void(int)> &after);
BodyId addGround(World &world, double friction);

std::string number(double v, int digits = 3);
std::string fraction(double dt);
/// The step sizes of the sweep: seven from 1/15 s to 1/960 s, or three for --quick.
std::vector<double> steps(bool quick);
std::vector<Config> sweep(const std::vector<Integrator> &integrators, const std::vector<int> &iterations,
                          const std::vector<int> &substeps, bool quick);

/// Scenes of free motion, springs, and contacts with a closed form (accuracy_motion.cpp).
void addMotionScenes(std::vector<Scene> &all, bool quick);
/// Impacts, joints and rolling resistance (accuracy_contacts.cpp).
void addContactScenes(std::vector<Scene> &all, bool quick);

/// Where the shipped scene files are (examples/scenes).
std::string scenesDirectory();

}  // namespace cyclone::accuracy
