#include "scene_world.h"

#include <cctype>

namespace cyclone::scene {

namespace {

// The place of a World refusal: the part's own path, then the field within it.
std::string placeOf(const std::string &partPath, const std::string &worldField) {
    const std::string field = sceneFieldPath(worldField);
    if (field.empty()) return partPath;
    return partPath.empty() ? field : partPath + "." + field;
}

}  // namespace

std::string sceneFieldPath(const std::string &worldField) {
    std::string field = worldField;
    // The scene file has friction and restitution on the body, not under "material".
    const std::string material = "material.";
    if (field.compare(0, material.size(), material) == 0) field.erase(0, material.size());
    if (field == "isStatic") return "static";
    std::string out;
    for (char c : field) {
        if (std::isupper(static_cast<unsigned char>(c))) {
            out += '_';
            out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        } else {
            out += c;
        }
    }
    return out;
}

SceneWorld buildWorld(const Scene &scene) {
    const auto refuse = [](const std::string &partPath, const InvalidArgument &error) -> SceneError {
        return SceneError(placeOf(partPath, error.field()), error.problem());
    };
    SceneWorld built{[&] {
                         try {
                             return World(scene.world);
                         } catch (const InvalidArgument &error) {
                             throw refuse("settings", error);
                         }
                     }(),
                     {}};
    built.ids.reserve(scene.bodies.size());
    for (const SceneBody &body : scene.bodies) {
        try {
            built.ids.push_back(built.world.addBody(body.settings));
        } catch (const InvalidArgument &error) {
            throw refuse(body.path, error);
        } catch (const std::invalid_argument &error) {
            throw SceneError(body.path, error.what());
        }
    }
    for (const SceneSpring &spring : scene.springs) {
        SpringSettings settings = spring.settings;
        settings.a = built.ids[spring.a];
        if (spring.b) settings.b = built.ids[*spring.b];
        try {
            built.world.addSpring(settings);
        } catch (const InvalidArgument &error) {
            throw refuse(spring.path, error);
        } catch (const std::invalid_argument &error) {
            throw SceneError(spring.path, error.what());
        }
    }
    return built;
}

}  // namespace cyclone::scene
