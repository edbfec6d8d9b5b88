// --save-scene (v3): the scene file of a world as it is after a run, from which a run
// continues the same motion.
#pragma once

#include <cstdint>
#include <string>

#include "scene.h"
#include "scene_world.h"

namespace cyclone::scene {

/// The scene `text` (loaded as `scene`, built as `built`) rewritten for the world after
/// `stepsDone` steps: each body's pose, velocities and sleep state as they are (removed
/// bodies left out, with their springs, joints and events); each joint at the bodies'
/// present poses (its anchors and axis carried along with body a, or b for a distance
/// joint's second anchor; limits and servo targets moved by the angle or offset it has
/// now; broken and removed joints left out); the events still to come, numbered from
/// the new start. Caches (contacts, warm starts) are not in a scene file.
std::string sceneAsItIs(const std::string &text, const Scene &scene, const SceneWorld &built, std::int64_t stepsDone);

}  // namespace cyclone::scene
