// The human-readable report of `cyclone-world report`: what a person wants to know after
// running a stacking scene.
#pragma once

#include <ostream>
#include <string>

#include "run_loop.h"
#include "scene.h"
#include "scene_world.h"

namespace cyclone::scene {

/// Writes the report: bodies, steps, ms per step (median, mean, max), when everything
/// fell asleep (step and time) or that it never did, the drift of the highest dynamic body
/// from where it started, and the deepest penetration.
void writeReport(std::ostream &out, const std::string &file, const Scene &scene, const SceneWorld &world,
                 const RunResult &result);

/// The one-line result `cyclone-world run` prints.
std::string resultLine(const Scene &scene, const SceneWorld &world, const RunResult &result);

}  // namespace cyclone::scene
