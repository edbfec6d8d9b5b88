#include "scene_fields.h"

#include <algorithm>
#include <cctype>

#include "json_document.h"

namespace cyclone::scene {

using nlohmann::json;

namespace {

using Names = std::vector<std::string>;

// Every field of the contract at each place. Fields of the second version that the runner
// does not act on yet (motion, layer, joints, ...) are known all the same: a scene that
// uses them correctly gets no warning.
const Names kTopFields = {"name", "settings", "bodies", "springs", "joints", "events"};
const Names kSettingsFields = {"gravity", "dt", "steps", "velocity_iterations", "position_iterations",
                                   "substeps", "sleep", "sleep_epsilon", "integrator"};
const Names kBodyFields = {"name", "shape", "static", "mass", "inertia", "position", "orientation",
                               "velocity", "rotation", "linear_damping", "angular_damping", "friction",
                               "restitution", "can_sleep", "awake", "ccd", "motion", "layer", "collides_with",
                               "sensor", "rolling_friction", "spinning_friction", "gravity_scale", "locked_axes",
                               "surface_velocity", "one_way"};
const Names kChildFields = {"shape", "position", "orientation"};
// A spring's "force" ("automatic" or "explicit") is the runner's own, beside the contract's.
const Names kSpringFields = {"a", "a_point", "b", "b_point", "stiffness", "damping", "rest_length", "force"};
const Names kJointFields = {"name", "type", "a", "b", "anchor", "anchor_b", "axis", "limits", "motor",
                                "min_distance", "max_distance", "stiffness", "damping", "break_force",
                                "collide_connected", "swing_limit", "twist_limit", "normal"};
const Names kMotorFields = {"speed", "max_force", "target", "frequency", "damping_ratio"};
// The joint types without an axis: one given to them is ignored, and said so.
const Names kJointTypesWithoutAxis = {"ball", "fixed", "distance"};

struct Variant {
    const char *name;  // a shape's type or an event's action
    Names fields;      // its fields beside "type" (shapes) or "step" and the action (events)
};

const Variant kShapes[] = {
    {"box", {"half_extents"}},         {"sphere", {"radius"}},          {"capsule", {"radius", "length"}},
    {"cylinder", {"radius", "length"}}, {"convex", {"vertices"}},        {"plane", {"normal", "offset"}},
    {"mesh", {"vertices", "triangles"}}, {"compound", {"children"}},
};

const Variant kEvents[] = {
    {"remove", {}},          {"set_velocity", {"velocity"}}, {"set_rotation", {"rotation"}},
    {"set_position", {"position"}}, {"apply_impulse", {"impulse", "point"}}, {"set_awake", {"awake"}},
    {"remove_joint", {}},
};

// Whether `key` is a field at some place of the format: such a key is never taken for a
// misspelling of another one ("b" beside a missing "a").
bool isFieldAnywhere(const std::string &key) {
    for (const Names *names : {&kTopFields, &kSettingsFields, &kBodyFields, &kChildFields, &kSpringFields,
                               &kJointFields, &kMotorFields}) {
        if (std::find(names->begin(), names->end(), key) != names->end()) return true;
    }
    for (const Variant &variant : kShapes) {
        if (std::find(variant.fields.begin(), variant.fields.end(), key) != variant.fields.end()) return true;
    }
    for (const Variant &variant : kEvents) {
        if (key == variant.name || std::find(variant.fields.begin(), variant.fields.end(), key) != variant.fields.end())
            return true;
    }
    return key == "type" || key == "step";
}

std::string lower(std::string text) {
    for (char &c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool among(const std::string &key, const Names &names) { return std::find(names.begin(), names.end(), key) != names.end(); }

std::string list(const Names &names) {
    std::string text;
    for (const std::string &name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

class Checker {
public:
    std::vector<SceneWarning> warnings;

    // Warns about each member of `object` not in `known`; `what` names the kind of object
    // for fields that belong to another variant ("a \"sphere\" shape").
    void check(const json &object, const std::string &path, const Names &known, const std::string &what = "",
               const Names &otherVariants = {}) {
        if (!object.is_object()) return;
        for (auto it = object.begin(); it != object.end(); ++it) {
            const std::string &key = it.key();
            if (among(key, known)) continue;
            std::string message;
            if (among(key, otherVariants)) {
                message = "not a field of " + what + " (its fields: " + list(known) + "); ignored";
            } else if (const std::string guess = nearestName(key, known); !guess.empty()) {
                message = "unknown field; did you mean " + jsonQuoted(guess) + "?";
            } else if (path.empty() && among(key, kSettingsFields)) {
                message = "unknown field here; did you mean \"settings." + key + "\"?";
            } else {
                message = "unknown field";
            }
            warnings.push_back({memberPath(path, key), message});
        }
    }

    void shape(const json &value, const std::string &path) {
        if (!value.is_object()) return;
        const auto type = value.find("type");
        const Variant *variant = nullptr;
        for (const Variant &v : kShapes) {
            if (type != value.end() && type->is_string() && *type == v.name) variant = &v;
        }
        if (!variant) return;  // the loader has refused it already
        Names known = {"type"}, others;
        known.insert(known.end(), variant->fields.begin(), variant->fields.end());
        for (const Variant &v : kShapes) others.insert(others.end(), v.fields.begin(), v.fields.end());
        check(value, path, known, "a " + jsonQuoted(variant->name) + " shape", others);
        const auto children = value.find("children");
        if (std::string(variant->name) == "compound" && children != value.end() && children->is_array()) {
            for (std::size_t i = 0; i < children->size(); ++i) {
                const json &child = (*children)[i];
                const std::string childPath = elementPath(memberPath(path, "children"), i);
                check(child, childPath, kChildFields);
                if (child.is_object() && child.contains("shape")) shape(child.at("shape"), memberPath(childPath, "shape"));
            }
        }
    }

    void event(const json &value, const std::string &path) {
        if (!value.is_object()) return;
        const Variant *variant = nullptr;
        Names others;
        for (const Variant &v : kEvents) {
            if (value.contains(v.name) && !variant) variant = &v;
            others.push_back(v.name);
            others.insert(others.end(), v.fields.begin(), v.fields.end());
        }
        if (!variant) return;
        Names known = {"step", variant->name};
        known.insert(known.end(), variant->fields.begin(), variant->fields.end());
        check(value, path, known, "a " + jsonQuoted(variant->name) + " event", others);
    }
};

// Each element of the array `document[key]` checked by `each(element, path)`.
template <typename Each>
void forEach(const json &document, const char *key, Each each) {
    const auto array = document.find(key);
    if (array == document.end() || !array->is_array()) return;
    for (std::size_t i = 0; i < array->size(); ++i) each((*array)[i], elementPath(key, i));
}

}  // namespace

std::size_t editDistance(const std::string &a, const std::string &b) {
    // Three rows of the optimal-string-alignment table: the row before last, last, current.
    std::vector<std::size_t> before(b.size() + 1), last(b.size() + 1), current(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) last[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t substitute = last[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            current[j] = std::min({last[j] + 1, current[j - 1] + 1, substitute});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
                current[j] = std::min(current[j], before[j - 2] + 1);
            }
        }
        std::swap(before, last);
        std::swap(last, current);
    }
    return last[b.size()];
}

std::string nearestName(const std::string &typed, const Names &known) {
    const std::string text = lower(typed);
    const std::size_t limit = text.size() <= 4 ? 1 : text.size() <= 8 ? 2 : 3;
    std::string best;
    std::size_t bestDistance = limit + 1;
    for (const std::string &name : known) {
        const std::size_t distance = editDistance(text, name);
        if (distance < bestDistance) {
            best = name;
            bestDistance = distance;
        }
    }
    return best;
}

std::string didYouMean(const std::string &typed, const Names &known) {
    const std::string guess = nearestName(typed, known);
    return guess.empty() ? "" : "; did you mean " + jsonQuoted(guess) + "?";
}

std::string misspellingOf(const json &object, const std::string &key) {
    if (!object.is_object()) return "";
    for (auto it = object.begin(); it != object.end(); ++it) {
        if (isFieldAnywhere(it.key())) continue;
        if (nearestName(it.key(), {key}) == key) return it.key();
    }
    return "";
}

std::vector<SceneWarning> unknownFields(const json &document) {
    Checker checker;
    if (!document.is_object()) return {};
    checker.check(document, "", kTopFields);
    if (const auto settings = document.find("settings"); settings != document.end()) {
        checker.check(*settings, "settings", kSettingsFields);
    }
    forEach(document, "bodies", [&](const json &body, const std::string &path) {
        checker.check(body, path, kBodyFields);
        if (body.is_object() && body.contains("shape")) checker.shape(body.at("shape"), memberPath(path, "shape"));
    });
    forEach(document, "springs", [&](const json &spring, const std::string &path) {
        checker.check(spring, path, kSpringFields);
    });
    forEach(document, "joints", [&](const json &joint, const std::string &path) {
        checker.check(joint, path, kJointFields);
        if (!joint.is_object()) return;
        if (joint.contains("motor")) checker.check(joint.at("motor"), memberPath(path, "motor"), kMotorFields);
        const auto type = joint.find("type");
        const bool limitedBall = joint.contains("swing_limit") || joint.contains("twist_limit");
        if (joint.contains("axis") && type != joint.end() && type->is_string() && among(*type, kJointTypesWithoutAxis) &&
            !(limitedBall && *type == "ball")) {
            checker.warnings.push_back({memberPath(path, "axis"), "ignored for a " + type->get<std::string>() +
                                                                      " joint (only hinge and slider joints have an axis)"});
        }
    });
    forEach(document, "events", [&](const json &event, const std::string &path) { checker.event(event, path); });
    return std::move(checker.warnings);
}

}  // namespace cyclone::scene
