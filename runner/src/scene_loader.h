// Scene files -> Scene: every field of the scene-format contract with its default, and
// every check, done before anything is built or stepped.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "json_document.h"
#include "scene.h"

namespace cyclone::scene {

/// Largest number of iterations or sub-steps per step a scene may ask for.
inline constexpr int kMaxIterations = 1000;
/// Largest number of points of a convex shape or vertices or triangles of a mesh.
inline constexpr std::size_t kMaxShapePoints = 1000000;
/// Largest number of springs or of events in a scene.
inline constexpr std::size_t kMaxSprings = 1000000;
inline constexpr std::size_t kMaxEvents = 1000000;

/// An integration scheme's name in scene files. kIntegrators is the one table that maps
/// names to schemes; a new scheme is one more row.
struct IntegratorName {
    const char *name;
    Integrator integrator;
};
inline constexpr IntegratorName kIntegrators[] = {
    {"newton-euler", Integrator::NewtonEuler},
    {"newton-euler-gyroscopic", Integrator::NewtonEulerGyroscopic},
    {"newton-euler-implicit", Integrator::NewtonEulerImplicit},
    {"momentum-conserving", Integrator::MomentumConserving},
};

/// Loads a scene from the text of a scene file; `fallbackName` names the scene when the
/// file has no "name". Throws SceneError (path and message) on anything that cannot run.
Scene loadScene(const std::string &text, const std::string &fallbackName);

/// As loadScene(text, ...) from an already parsed document.
Scene loadSceneDocument(const nlohmann::json &document, const std::string &fallbackName);

}  // namespace cyclone::scene
