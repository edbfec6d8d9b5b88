// Scene -> World: the World's settings, the bodies in scene order and the springs, all
// through the public World API. A refusal by the World is reported at the scene's path.
#pragma once

#include <string>
#include <vector>

#include "json_document.h"
#include "scene.h"

namespace cyclone::scene {

/// A World built from a scene, with the handle of every scene body in scene order.
struct SceneWorld {
    World world;
    std::vector<BodyId> ids;
    /// The handle of every scene joint, in scene order.
    std::vector<JointId> joints;
};

/// Builds the World of `scene`. Throws SceneError with the JSON path of the part the
/// World refused (e.g. "bodies[3].shape.vertices" from a field "shape.vertices").
SceneWorld buildWorld(const Scene &scene);

/// A World field path (e.g. "shape.halfExtents[1]", "material.friction") as the scene
/// file spells it ("shape.half_extents[1]", "friction").
std::string sceneFieldPath(const std::string &worldField);

}  // namespace cyclone::scene
