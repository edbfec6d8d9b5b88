#include "json_document.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace cyclone::scene {

using nlohmann::json;

namespace {

bool isIdentifier(const std::string &key) {
    if (key.empty() || std::isdigit(static_cast<unsigned char>(key[0]))) return false;
    for (char c : key) {
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
    }
    return true;
}

// nlohmann's messages start with "[json.exception.parse_error.101] parse error at line
// 1, column 2: "; the place is ours to give, so the prefix goes. Control bytes are
// replaced so the message stays one line.
std::string syntaxMessage(const nlohmann::detail::exception &error) {
    std::string text(error.what());
    if (!text.empty() && text[0] == '[') {
        const auto end = text.find("] ");
        if (end != std::string::npos) text.erase(0, end + 2);
    }
    if (text.compare(0, 11, "parse error") == 0) {
        const auto colon = text.find(": ");
        if (colon != std::string::npos) text.erase(0, colon + 2);
    }
    for (char &c : text) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    }
    return text;
}

// Builds the DOM as nlohmann's own SAX DOM parser does, and keeps the path of every open
// container so that a failure can be placed.
class PathTrackingBuilder {
public:
    PathTrackingBuilder(json &root, const std::string &text) : root_(root), text_(text) {}

    bool null() { return put(nullptr) != nullptr; }
    bool boolean(bool value) { return put(value) != nullptr; }
    bool number_integer(json::number_integer_t value) { return put(value) != nullptr; }
    bool number_unsigned(json::number_unsigned_t value) { return put(value) != nullptr; }
    bool number_float(json::number_float_t value, const json::string_t &) { return put(value) != nullptr; }
    bool string(json::string_t &value) { return put(std::move(value)) != nullptr; }
    bool binary(json::binary_t &value) { return put(json::binary(std::move(value))) != nullptr; }

    bool start_object(std::size_t) { return open(json::object()); }
    bool key(json::string_t &key) {
        stack_.back().key = std::move(key);
        stack_.back().haveKey = true;
        return true;
    }
    bool end_object() {
        stack_.pop_back();
        return true;
    }
    bool start_array(std::size_t) { return open(json::array()); }
    bool end_array() {
        stack_.pop_back();
        return true;
    }

    bool parse_error(std::size_t position, const std::string &token, const nlohmann::detail::exception &error) {
        if (error.id == 406) throw SceneError(currentPath(), "must be a finite number, got " + token);
        // The parser takes a NUL byte for the end of the text; say what it is.
        for (std::size_t at : {position - 1, position}) {
            if (position > 0 && at < text_.size() && text_[at] == '\0') {
                throw SceneError(currentPath(),
                                 "invalid JSON: a NUL byte at offset " + std::to_string(at) + ", which no JSON text holds");
            }
        }
        throw SceneError(currentPath(), "invalid JSON at " + lineAndColumn(position) + ": " + syntaxMessage(error) +
                                            trailingCommaHint(position));
    }

private:
    // The offending character is the last one the parser read: `position` counts the
    // characters read, so it is at position - 1 (the end of the text when it ran out).
    std::size_t offendingIndex(std::size_t position) const {
        return std::min(position > 0 ? position - 1 : 0, text_.size());
    }

    // "line L, column C" of the offending character, both counted from 1, in bytes.
    std::string lineAndColumn(std::size_t position) const {
        const std::size_t at = offendingIndex(position);
        const std::size_t lineStart = at == 0 ? 0 : text_.rfind('\n', at - 1);
        const std::size_t line = 1 + static_cast<std::size_t>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
        const std::size_t column = lineStart == std::string::npos || at == 0 ? at + 1 : at - lineStart;
        return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }

    // A '}' or ']' right after a comma is JSON's most common mistake; it is named as such.
    std::string trailingCommaHint(std::size_t position) const {
        const std::size_t at = offendingIndex(position);
        if (at >= text_.size() || (text_[at] != '}' && text_[at] != ']')) return "";
        std::size_t before = at;
        while (before > 0 && std::isspace(static_cast<unsigned char>(text_[before - 1]))) --before;
        if (before == 0 || text_[before - 1] != ',') return "";
        return " (a comma before '" + std::string(1, text_[at]) + "': JSON allows none after the last element)";
    }

    struct Frame {
        json *value;
        std::string path;
        std::string key;
        bool haveKey = false;
    };

    std::string currentPath() const {
        if (stack_.empty()) return kTopLevelPath;
        const Frame &top = stack_.back();
        if (top.value->is_array()) return elementPath(top.path, top.value->size());
        if (top.haveKey) return memberPath(top.path, top.key);
        return top.path.empty() ? kTopLevelPath : top.path;
    }

    json *put(json value) {
        if (stack_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        Frame &top = stack_.back();
        if (top.value->is_array()) {
            top.value->push_back(std::move(value));
            return &top.value->back();
        }
        json &slot = (*top.value)[top.key];
        slot = std::move(value);
        top.haveKey = false;
        return &slot;
    }

    bool open(json container) {
        // A scene is a few levels deep; a document nested this deep is not one, and its
        // paths would be longer than any message should be.
        if (stack_.size() >= kMaxJsonDepth) {
            throw SceneError(currentPath(), "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        }
        std::string path = stack_.empty() ? std::string() : currentPath();
        json *slot = put(std::move(container));
        stack_.push_back(Frame{slot, std::move(path), std::string(), false});
        return true;
    }

    json &root_;
    const std::string &text_;
    std::vector<Frame> stack_;
};

}  // namespace

std::string memberPath(const std::string &parent, const std::string &key) {
    if (isIdentifier(key)) return parent.empty() ? key : parent + "." + key;
    return parent + "[" + jsonQuoted(key) + "]";
}

std::string elementPath(const std::string &parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

std::string jsonQuoted(const std::string &text) {
    return json(text).dump(-1, ' ', false, json::error_handler_t::replace);
}

json parseJsonDocument(const std::string &text) {
    json root;
    PathTrackingBuilder builder(root, text);
    json::sax_parse(text, &builder, json::input_format_t::json, true, false);
    return root;
}

}  // namespace cyclone::scene
