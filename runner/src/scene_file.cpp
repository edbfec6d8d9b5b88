#include "scene_file.h"

#include "json_document.h"
#include "named_places.h"
#include "scene_fields.h"
#include "scene_loader.h"

namespace cyclone::scene {

std::string oneLine(std::string text) {
    for (char &c : text) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    }
    return text;
}

SceneFile::SceneFile(const std::string &text, const std::string &fallbackName, bool strict)
    : document_(parseJsonDocument(text)) {
    try {
        scene_ = loadSceneDocument(document_, fallbackName);
    } catch (const SceneError &error) {
        throw SceneError(place(error.path()), error.message());
    }
    if (strict && !scene_.warnings.empty()) {
        const SceneWarning &first = scene_.warnings.front();
        const std::size_t more = scene_.warnings.size() - 1;
        throw SceneError(place(first.path),
                         first.message + " (refused by --strict" +
                             (more ? "; " + std::to_string(more) + " more unknown field" + (more > 1 ? "s" : "") : "") + ")");
    }
}

std::string SceneFile::place(const std::string &path) const { return namedPlace(path, document_); }

void SceneFile::writeWarnings(std::ostream &out, const std::string &file) const {
    const auto &warnings = scene_.warnings;
    for (std::size_t i = 0; i < warnings.size() && i < kMaxWarningsShown; ++i) {
        out << oneLine(file) << ": " << oneLine(place(warnings[i].path)) << ": " << oneLine(warnings[i].message) << "\n";
    }
    if (warnings.size() > kMaxWarningsShown) {
        out << oneLine(file) << ": " << warnings.size() - kMaxWarningsShown << " more unknown fields\n";
    }
}

}  // namespace cyclone::scene
