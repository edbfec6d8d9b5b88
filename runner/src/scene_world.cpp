#include "scene_world.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <utility>

namespace cyclone::scene {

namespace {

// The place of a World refusal: the part's own path, then the field within it.
std::string placeOf(const std::string &partPath, const std::string &worldField) {
    const std::string field = sceneFieldPath(worldField);
    if (field.empty()) return partPath;
    return partPath.empty() ? field : partPath + "." + field;
}

// The shape scaled by `factor` about its origin.
Shape scaled(Shape shape, real factor) {
    shape.halfExtents *= factor;
    shape.radius *= factor;
    shape.length *= factor;
    for (Vector3 &v : shape.vertices) v *= factor;
    return shape;
}

// The field of a shape that sets its size, as the scene file spells it, and that size, m.
std::pair<const char *, real> sizeOf(const Shape &shape) {
    switch (shape.type) {
    case ShapeType::Box: return {"shape.half_extents", shape.halfExtents.maxCoeff()};
    case ShapeType::Sphere:
    case ShapeType::Capsule:
    case ShapeType::Cylinder: return {"shape.radius", shape.radius};
    case ShapeType::Compound: return {"shape.children", shape.children.empty() ? 0 : sizeOf(shape.children[0].shape).second};
    default: {
        real size = 0;
        for (const Vector3 &v : shape.vertices) size = std::max(size, v.norm());
        return {"shape.vertices", size};
    }
    }
}

std::string roughly(real value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

// The factors f = 2^e (e within ±1100) for which works(f) holds, knowing that it fails at
// f = 1: found by widening steps out from 1, then each end by bisection to 0.01 in e.
std::optional<std::pair<real, real>> workingFactors(const std::function<bool(real)> &works) {
    const auto at = [&](double e) { return works(std::exp2(e)); };
    double inside = 0;
    bool found = false;
    for (double step = 1; step <= 1024 && !found; step *= 2) {
        for (double e : {step, -step}) {
            if (!found && at(e)) {
                inside = e;
                found = true;
            }
        }
    }
    if (!found) return std::nullopt;
    const auto edge = [&](double in, double out) {
        while (std::abs(out - in) > 0.01) {
            const double middle = (in + out) / 2;
            (at(middle) ? in : out) = middle;
        }
        return in;
    };
    // The end towards f = 1, then the far end (past +-1100 nothing is a double).
    const double near = edge(inside, 0);
    double far = inside + (inside > 0 ? 1 : -1);
    while (std::abs(far) < 1100 && at(far)) far += far - inside;
    const double farEdge = edge(inside, std::max(-1100.0, std::min(1100.0, far)));
    return std::make_pair(std::exp2(std::min(near, farEdge)), std::exp2(std::max(near, farEdge)));
}

// A body whose inertia comes from its shape and mass, refused for that inertia: the file
// has no "inertia", so the error names what it has. If the shape works at 1 kg, the mass is
// at fault and the masses that work with this shape are given; else the shape's size, with
// the sizes that work at this mass. Each candidate is tried on a scratch world.
SceneError explainDerivedInertia(const SceneBody &body, const WorldSettings &settings, const InvalidArgument &error) {
    World scratch(settings);
    const auto accepted = [&](BodySettings candidate) {
        candidate.name.clear();
        try {
            scratch.removeBody(scratch.addBody(candidate));
            return true;
        } catch (const std::exception &) {
            return false;
        }
    };
    const BodySettings &given = body.settings;
    BodySettings probe = given;
    probe.mass = 1;
    if (accepted(probe)) {
        const auto factors = workingFactors([&](real f) {
            probe.mass = given.mass * f;
            return accepted(probe);
        });
        if (factors) {
            return SceneError(body.path + ".mass", "gives this shape an inertia tensor without a finite inverse in "
                                                   "double precision; masses from about " +
                                                       roughly(given.mass * factors->first) + " to " +
                                                       roughly(given.mass * factors->second) + " kg work, got " +
                                                       roughly(given.mass));
        }
    }
    probe = given;
    const auto factors = workingFactors([&](real f) {
        probe.shape = scaled(given.shape, f);
        return accepted(probe);
    });
    const auto [field, size] = sizeOf(given.shape);
    const std::string problem = "with a mass of " + roughly(given.mass) +
                                " kg, the inertia tensor has no finite inverse in double precision";
    if (!factors) return SceneError(body.path + "." + field, problem + ": " + error.problem());
    const bool small = factors->first > 1;
    return SceneError(body.path + "." + field,
                      std::string(small ? "is too small" : "is too large") + ": " + problem + "; sizes from about " +
                          roughly(size * factors->first) + " to " + roughly(size * factors->second) +
                          " m work (the shape in proportion), got " + roughly(size));
}

}  // namespace

std::string sceneFieldPath(const std::string &worldField) {
    std::string field = worldField;
    // The scene file has friction and restitution on the body, not under "material".
    const std::string material = "material.";
    if (field.compare(0, material.size(), material) == 0) field.erase(0, material.size());
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
                         } catch (const std::exception &error) {
                             throw SceneError("settings", error.what());
                         }
                     }(),
                     {}, {}};
    built.ids.reserve(scene.bodies.size());
    for (const SceneBody &body : scene.bodies) {
        try {
            built.ids.push_back(built.world.addBody(body.settings));
        } catch (const InvalidArgument &error) {
            if (error.field() == "inertia" && !body.settings.inertia) {
                throw explainDerivedInertia(body, scene.world, error);
            }
            throw refuse(body.path, error);
        } catch (const std::exception &error) {
            throw SceneError(body.path, error.what());
        }
    }
    for (const SceneSpring &spring : scene.springs) {
        SpringSettings settings = spring.settings;
        settings.a = built.ids[spring.a];
        if (spring.b) settings.b = built.ids[*spring.b];
        // The file places attachments in a body's frame, which for a compound is not its
        // centre of mass (the World's body space).
        settings.aPoint -= built.world.localCentreOfMass(settings.a);
        if (settings.b) settings.bPoint -= built.world.localCentreOfMass(*settings.b);
        try {
            built.world.addSpring(settings);
        } catch (const InvalidArgument &error) {
            throw refuse(spring.path, error);
        } catch (const std::exception &error) {
            throw SceneError(spring.path, error.what());
        }
    }
    built.joints.reserve(scene.joints.size());
    for (const SceneJoint &joint : scene.joints) {
        JointSettings settings = joint.settings;
        settings.a = built.ids[joint.a];
        if (joint.b) settings.b = built.ids[*joint.b];
        try {
            built.joints.push_back(built.world.addJoint(settings));
        } catch (const InvalidArgument &error) {
            throw refuse(joint.path, error);
        } catch (const std::exception &error) {
            throw SceneError(joint.path, error.what());
        }
    }
    return built;
}

}  // namespace cyclone::scene
