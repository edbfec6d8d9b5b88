// The run summary (JSON), field for field as the scene-format contract gives it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "run_loop.h"
#include "scene.h"
#include "scene_world.h"

namespace cyclone::scene {

/// A vector as a JSON array [x, y, z], as the summary and saved scenes write it.
nlohmann::ordered_json jsonVector(const Vector3 &v);

/// Dynamic bodies of the world awake now.
int awakeDynamicBodies(const World &world);

/// The summary of a run: scene, steps, dt, wall_seconds, step_ms, metrics, the bodies
/// still in the world, in scene order, and, for a scene with sensors, sensor_events. Non-finite numbers appear as null.
nlohmann::ordered_json summaryJson(const Scene &scene, const SceneWorld &world, const RunResult &result);

/// The summary as the text of the file: one field per line, one body per line.
std::string summaryText(const nlohmann::ordered_json &summary);

}  // namespace cyclone::scene
