// Places of messages that name what they are in: `bodies[30] ("crate").mass` reads better
// than `bodies[30].mass` in a file of a hundred bodies. SceneError and SceneWarning keep
// the plain JSON path; the name is added where a message is printed.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace cyclone::scene {

/// `path` with the name of the body or joint it lies in after its index, e.g.
/// "bodies[30].mass" -> `bodies[30] ("crate").mass`, when `document` gives that element a
/// "name" string that is not empty; else `path` as it is.
std::string namedPlace(const std::string &path, const nlohmann::json &document);

}  // namespace cyclone::scene
