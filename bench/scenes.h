// The benchmark scenes, each described once as World settings plus a list of bodies;
// every engine of the benchmark builds its own world from this description.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cyclone/world/settings.h"

namespace cyclone::bench {

/// Velocity passes of the contact solver per frame in every scene and engine: cyclone's
/// substeps x velocityIterations, Bullet's m_numIterations.
inline constexpr int kVelocityPassesPerFrame = 10;

/// One benchmark scene.
struct Scene {
    /// Short name used on the command line, e.g. "pyramid20".
    std::string name;
    /// One line saying what the scene is.
    std::string description;
    /// Gravity, solver iterations, sleep, ... of the scene: the World's defaults except
    /// sleep and one sub-step of kVelocityPassesPerFrame velocity iterations.
    WorldSettings world;
    /// Every body, static ones included, in the order they are added.
    std::vector<BodySettings> bodies;
    /// Index in `bodies` of the body whose drift is reported (a pyramid's top box), or
    /// -1 when drift means nothing for the scene (bodies that fall or bounce by design).
    int tracked = -1;
};

/// Names of every scene, in the order the benchmark runs them.
std::vector<std::string> sceneNames();

/// The names in a comma-separated list ("pyramid10,pyramid20"), empty entries skipped.
std::vector<std::string> splitSceneList(const std::string &list);

/// Reads an option the scene tools share into its place: --scene (names added to
/// `scenes`, comma-separated, repeatable), --steps or --threads. False for any other.
bool readSceneOption(const std::string &option, const std::string &value, std::vector<std::string> &scenes,
                     int &steps, int &threads);

/// The scene called `name`; throws std::invalid_argument for an unknown name. `seed`
/// picks mixed1000's shapes, sizes and orientations (0: the scene the tables show); the
/// other scenes have no randomness.
Scene makeScene(const std::string &name, std::uint64_t seed = 0);

/// Sets `settings`' sub-steps and velocity and position passes to WorldSettings' defaults
/// (the `--defaults` of the benchmark tools) instead of the benchmark's 1 x 10.
void useWorldDefaults(WorldSettings &settings);

/// Splits the scene's velocity passes per frame over `substeps` sub-steps of cyclone's
/// World (Bullet still takes one step with all of them). Throws std::invalid_argument
/// unless `substeps` divides the passes.
void splitSubsteps(Scene &scene, int substeps);

}  // namespace cyclone::bench
