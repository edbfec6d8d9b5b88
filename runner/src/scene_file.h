// A scene file's text loaded as both the runner and the viewer load it: refusals name their
// place with the body or joint it is in (named_places.h), --strict refuses a field the
// format has not, and the warnings about such fields are printed one line each.
#pragma once

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>

#include "scene.h"

namespace cyclone::scene {

/// `text` with control characters replaced by '?', for a one-line message.
std::string oneLine(std::string text);

/// A loaded scene and the document it was read from, which names the places of later
/// messages (a refusal while building or running).
class SceneFile {
public:
    /// Loads `text`; `fallbackName` names the scene when the file has no "name". Throws
    /// SceneError at the named place (`bodies[3] ("crate").mass`); with `strict`, also for
    /// the first unknown field (the message counts the others).
    SceneFile(const std::string &text, const std::string &fallbackName, bool strict);

    Scene &scene() { return scene_; }
    const Scene &scene() const { return scene_; }

    /// `path` (a JSON path of this file) with the name of the body or joint it is in.
    std::string place(const std::string &path) const;

    /// Writes "FILE: PLACE: message" for each warning, at most kMaxWarningsShown, then one
    /// line counting the rest.
    void writeWarnings(std::ostream &out, const std::string &file) const;

private:
    nlohmann::json document_;
    Scene scene_;
};

}  // namespace cyclone::scene
