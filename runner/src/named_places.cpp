#include "named_places.h"

#include <cctype>

#include "json_document.h"

namespace cyclone::scene {

std::string namedPlace(const std::string &path, const nlohmann::json &document) {
    if (!document.is_object()) return path;
    for (const char *array : {"bodies", "joints"}) {
        const std::string prefix = std::string(array) + "[";
        if (path.compare(0, prefix.size(), prefix) != 0) continue;
        const std::size_t close = path.find(']', prefix.size());
        if (close == std::string::npos || close == prefix.size()) return path;
        std::size_t index = 0;
        for (std::size_t at = prefix.size(); at < close; ++at) {
            if (!std::isdigit(static_cast<unsigned char>(path[at])) || index > (std::size_t{1} << 40)) return path;
            index = index * 10 + static_cast<std::size_t>(path[at] - '0');
        }
        const auto elements = document.find(array);
        if (elements == document.end() || !elements->is_array() || index >= elements->size()) return path;
        const nlohmann::json &element = (*elements)[index];
        if (!element.is_object()) return path;
        const auto name = element.find("name");
        if (name == element.end() || !name->is_string() || name->get_ref<const std::string &>().empty()) return path;
        return path.substr(0, close + 1) + " (" + jsonQuoted(name->get<std::string>()) + ")" + path.substr(close + 1);
    }
    return path;
}

}  // namespace cyclone::scene
