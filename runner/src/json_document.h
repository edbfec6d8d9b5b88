// JSON parsing that knows where it is: a syntax error or an out-of-range number is
// reported at the JSON path of the value being read (`bodies[3].mass`), not only at a
// byte offset, so that a scene error always names its place.
#pragma once

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace cyclone::scene {

/// A problem at one place of a scene file: `path` is a JSON path such as
/// "bodies[3].mass" ("(top level)" for the document itself), `message` says what is wrong.
class SceneError : public std::runtime_error {
public:
    SceneError(std::string path, std::string message)
        : std::runtime_error(path + ": " + message), path_(std::move(path)), message_(std::move(message)) {}
    const std::string &path() const { return path_; }
    const std::string &message() const { return message_; }

private:
    std::string path_;
    std::string message_;
};

/// Deepest nesting of arrays and objects a scene file may have.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// The path shown for the document itself.
inline constexpr const char *kTopLevelPath = "(top level)";

/// `parent` + ".key", or `parent["key"]` when the key is not an identifier.
std::string memberPath(const std::string &parent, const std::string &key);
/// `parent[index]`.
std::string elementPath(const std::string &parent, std::size_t index);

/// `text` quoted and escaped as a JSON string, safe to put in a one-line message.
std::string jsonQuoted(const std::string &text);

/// Parses `text` as one JSON document. Throws SceneError naming the path at which the
/// text stops being valid JSON, holds a number too large for a double, or nests deeper
/// than kMaxJsonDepth.
nlohmann::json parseJsonDocument(const std::string &text);

}  // namespace cyclone::scene
