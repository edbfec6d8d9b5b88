#include "scene_loader.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <utility>
#include <unordered_map>

#include "json_reading.h"
#include "scene_fields.h"

namespace cyclone::scene {

using nlohmann::json;

namespace {

// A hull needs volume: the points must not all lie on one plane (or line, or point).
bool spansVolume(const std::vector<Vector3> &points) {
    real scale = 0;
    for (const auto &p : points) scale = std::max(scale, (p - points[0]).cwiseAbs().maxCoeff());
    if (!(scale > 0) || !std::isfinite(scale)) return false;
    std::vector<Vector3> unit;
    unit.reserve(points.size());
    for (const auto &p : points) unit.push_back((p - points[0]) / scale);
    std::size_t far = 0;
    for (std::size_t i = 0; i < unit.size(); ++i) {
        if (unit[i].squaredNorm() > unit[far].squaredNorm()) far = i;
    }
    const Vector3 axis = unit[far].normalized();
    std::size_t off = 0;
    real offDistance = 0;
    for (std::size_t i = 0; i < unit.size(); ++i) {
        const real d = (unit[i] - axis * axis.dot(unit[i])).norm();
        if (d > offDistance) {
            offDistance = d;
            off = i;
        }
    }
    if (offDistance < 1e-9) return false;
    const Vector3 normal = axis.cross(unit[off]).normalized();
    real height = 0;
    for (const auto &p : unit) height = std::max(height, std::abs(normal.dot(p)));
    return height > 1e-9;
}

Shape readShape(const json &value, const std::string &path, bool isStatic);

// A "heightfield" shape's fields (scene-format.md, shapes): rows and columns of samples,
// their spacing [dx, dz] and rows x columns heights, row by row.
Shape readHeightfield(const json &value, const std::string &path) {
    Shape shape;
    shape.type = ShapeType::Heightfield;
    const auto count = [&](const char *name) {
        return static_cast<int>(readInteger(required(value, path, name), memberPath(path, name), 2, 1 << 15));
    };
    shape.rows = count("rows");
    shape.columns = count("columns");
    const std::string spacingPath = memberPath(path, "spacing");
    const json &spacing = required(value, path, "spacing");
    if (!spacing.is_array() || spacing.size() != 2) fail(spacingPath, "must be [dx, dz], got " + describe(spacing));
    for (std::size_t k = 0; k < 2; ++k)
        shape.spacing[k] = readNumber(spacing[k], elementPath(spacingPath, k), Range::PositiveLength);
    const std::string heightsPath = memberPath(path, "heights");
    const json &heights = required(value, path, "heights");
    const auto expected = static_cast<std::size_t>(shape.rows) * static_cast<std::size_t>(shape.columns);
    expectArray(heights, heightsPath, expected);
    if (heights.size() != expected)
        fail(heightsPath, "must hold rows x columns = " + std::to_string(expected) + " numbers, got " +
                              std::to_string(heights.size()));
    shape.heights.reserve(expected);
    for (std::size_t k = 0; k < heights.size(); ++k)
        shape.heights.push_back(readNumber(heights[k], elementPath(heightsPath, k), Range::Length));
    return shape;
}

// A mesh's "triangles" at `path`: each 3 different indices of its `vertexCount` vertices.
std::vector<std::array<int, 3>> readTriangles(const json &value, const std::string &path, std::size_t vertexCount) {
    const std::string trianglesPath = memberPath(path, "triangles");
    const json &triangles = required(value, path, "triangles");
    expectArray(triangles, trianglesPath, kMaxShapePoints);
    if (triangles.empty()) fail(trianglesPath, "needs at least 1 triangle");
    const auto last = static_cast<std::int64_t>(vertexCount) - 1;
    std::vector<std::array<int, 3>> read;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const std::string trianglePath = elementPath(trianglesPath, t);
        const json &triangle = triangles[t];
        if (!triangle.is_array() || triangle.size() != 3) {
            fail(trianglePath, "must be 3 vertex indices [i, j, k], got " + describe(triangle));
        }
        std::array<int, 3> indices{};
        for (int k = 0; k < 3; ++k) {
            indices[k] = static_cast<int>(readInteger(triangle[k], elementPath(trianglePath, k), 0, last));
        }
        if (indices[0] == indices[1] || indices[1] == indices[2] || indices[0] == indices[2]) {
            fail(trianglePath, "must name 3 different vertices");
        }
        read.push_back(indices);
    }
    return read;
}

// A compound's "children" at `path`: each a convex shape with its pose in the body.
std::vector<CompoundChild> readChildren(const json &value, const std::string &path) {
    const std::string childrenPath = memberPath(path, "children");
    const json &children = required(value, path, "children");
    expectArray(children, childrenPath, kMaxShapePoints);
    if (children.empty()) fail(childrenPath, "needs at least 1 child");
    std::vector<CompoundChild> read;
    for (std::size_t i = 0; i < children.size(); ++i) {
        const std::string childPath = elementPath(childrenPath, i);
        const json &child = children[i];
        expectObject(child, childPath);
        CompoundChild part;
        const std::string shapePath = memberPath(childPath, "shape");
        const json &childShape = required(child, childPath, "shape");
        expectObject(childShape, shapePath);
        const json *childType = member(childShape, "type");
        if (childType && childType->is_string()) {
            const std::string &name = childType->get_ref<const std::string &>();
            if (name == "plane" || name == "mesh" || name == "compound" || name == "heightfield")
                fail(memberPath(shapePath, "type"), "a compound's child must be convex (box, sphere, capsule, "
                                                    "cylinder or convex), got " + jsonQuoted(name));
        }
        part.shape = readShape(childShape, shapePath, false);
        readOptional(child, childPath, "position", part.position,
                     [](const json &v, const std::string &p) { return readVector3(v, p, Range::Length); });
        readOptional(child, childPath, "orientation", part.orientation, readOrientation);
        read.push_back(std::move(part));
    }
    return read;
}

Shape readShape(const json &value, const std::string &path, bool isStatic) {
    expectObject(value, path);
    const std::string typePath = memberPath(path, "type");
    const std::string &type = readString(required(value, path, "type"), typePath);
    Shape shape;
    const auto radius = [&] { return readNumber(required(value, path, "radius"), memberPath(path, "radius"), Range::PositiveLength); };
    if (type == "box") {
        shape.type = ShapeType::Box;
        shape.halfExtents = readVector3(required(value, path, "half_extents"), memberPath(path, "half_extents"), Range::PositiveLength);
    } else if (type == "sphere") {
        shape.type = ShapeType::Sphere;
        shape.radius = radius();
    } else if (type == "capsule") {
        shape.type = ShapeType::Capsule;
        shape.radius = radius();
        shape.length = readNumber(required(value, path, "length"), memberPath(path, "length"), Range::NonNegativeLength);
    } else if (type == "cylinder") {
        shape.type = ShapeType::Cylinder;
        shape.radius = radius();
        shape.length = readNumber(required(value, path, "length"), memberPath(path, "length"), Range::PositiveLength);
    } else if (type == "convex") {
        shape.type = ShapeType::Convex;
        const std::string pointsPath = memberPath(path, "vertices");
        shape.vertices = readPoints(required(value, path, "vertices"), pointsPath, 4);
        if (!spansVolume(shape.vertices)) fail(pointsPath, "must hold 4 or more points not all on one plane");
    } else if (type == "plane" || type == "mesh") {
        if (!isStatic) fail(typePath, "a " + type + " is for static bodies only; add \"static\": true");
        if (type == "plane") {
            shape.type = ShapeType::Plane;
            const std::string normalPath = memberPath(path, "normal");
            shape.normal = readVector3(required(value, path, "normal"), normalPath);
            if (shape.normal.cwiseAbs().maxCoeff() == 0) fail(normalPath, "must not be zero");
            shape.offset = readNumber(required(value, path, "offset"), memberPath(path, "offset"), Range::Length);
        } else {
            shape.type = ShapeType::Mesh;
            shape.vertices = readPoints(required(value, path, "vertices"), memberPath(path, "vertices"), 3);
            shape.triangles = readTriangles(value, path, shape.vertices.size());
        }
    } else if (type == "heightfield") {
        if (!isStatic) fail(typePath, "a heightfield is for static bodies only; add \"static\": true");
        shape = readHeightfield(value, path);
    } else if (type == "compound") {
        shape.type = ShapeType::Compound;
        shape.children = readChildren(value, path);
    } else {
        fail(typePath, "unknown shape type " + jsonQuoted(type) +
                           " (known: box, sphere, capsule, cylinder, convex, plane, mesh, heightfield, compound)" +
                           didYouMean(type, {"box", "sphere", "capsule", "cylinder", "convex", "plane", "mesh",
                                             "heightfield", "compound"}));
    }
    return shape;
}

WorldSettings readSettings(const json &value, const std::string &path, Scene &scene) {
    expectObject(value, path);
    WorldSettings settings;
    const auto iterations = [](std::int64_t min) {
        return [min](const json &v, const std::string &p) { return static_cast<int>(readInteger(v, p, min, kMaxIterations)); };
    };
    readOptional(value, path, "gravity", settings.gravity, [](const json &v, const std::string &p) { return readVector3(v, p); });
    readOptional(value, path, "dt", scene.dt, [](const json &v, const std::string &p) {
        const real dt = readNumber(v, p, Range::Positive);
        if (dt > kMaxStep) fail(p, "must be at most 1 s (kMaxStep; a longer step lets a resting stack slide apart), got " + describe(v));
        if (dt < kMinStep) fail(p, "must be at least 1e-06 s (kMinStep; the step divides by it), got " + describe(v));
        return dt;
    });
    readOptional(value, path, "steps", scene.steps, [](const json &v, const std::string &p) { return readInteger(v, p, 0, kMaxSteps); });
    readOptional(value, path, "velocity_iterations", settings.velocityIterations, iterations(1));
    readOptional(value, path, "position_iterations", settings.positionIterations, iterations(0));
    readOptional(value, path, "substeps", settings.substeps, iterations(1));
    readOptional(value, path, "sleep", settings.sleep, readBool);
    readOptional(value, path, "sleep_epsilon", settings.sleepEpsilon,
             [](const json &v, const std::string &p) { return readNumber(v, p, Range::Positive); });
    if (const json *integrator = member(value, "integrator")) {
        const std::string integratorPath = memberPath(path, "integrator");
        const std::string &name = readString(*integrator, integratorPath);
        const auto *row = std::find_if(std::begin(kIntegrators), std::end(kIntegrators),
                                       [&](const IntegratorName &entry) { return name == entry.name; });
        if (row == std::end(kIntegrators)) {
            std::string known;
            std::vector<std::string> names;
            for (const auto &entry : kIntegrators) {
                known += (known.empty() ? "" : ", ") + jsonQuoted(entry.name);
                names.emplace_back(entry.name);
            }
            fail(integratorPath, "unknown integrator " + jsonQuoted(name) + " (known: " + known + ")" + didYouMean(name, names));
        }
        settings.integrator = row->integrator;
    }
    return settings;
}

// "locked_axes": a list of distinct axis names.
LockedAxes readLockedAxes(const json &value, const std::string &path) {
    expectArray(value, path, 6);
    LockedAxes locks;
    const std::pair<const char *, bool LockedAxes::*> axes[] = {{"x", &LockedAxes::x},   {"y", &LockedAxes::y},
                                                                {"z", &LockedAxes::z},   {"rx", &LockedAxes::rx},
                                                                {"ry", &LockedAxes::ry}, {"rz", &LockedAxes::rz}};
    for (std::size_t k = 0; k < value.size(); ++k) {
        const std::string elementAt = elementPath(path, k);
        const std::string &name = readString(value[k], elementAt);
        const auto *axis = std::find_if(std::begin(axes), std::end(axes), [&](const auto &a) { return name == a.first; });
        if (axis == std::end(axes))
            fail(elementAt, "unknown axis " + jsonQuoted(name) + "; known: \"x\", \"y\", \"z\", \"rx\", \"ry\", \"rz\"");
        if (locks.*(axis->second)) fail(elementAt, jsonQuoted(name) + " is given twice");
        locks.*(axis->second) = true;
    }
    return locks;
}

SceneBody readBody(const json &value, const std::string &path) {
    expectObject(value, path);
    SceneBody body;
    body.path = path;
    BodySettings &settings = body.settings;
    const std::string namePath = memberPath(path, "name");
    settings.name = readString(required(value, path, "name"), namePath);
    if (settings.name.empty()) fail(namePath, "must not be empty");
    bool isStatic = false;
    readOptional(value, path, "static", isStatic, readBool);
    if (isStatic) settings.motion = Motion::Static;
    if (const json *motion = member(value, "motion")) {
        const std::string motionPath = memberPath(path, "motion");
        const std::string name = readString(*motion, motionPath);
        if (name == "dynamic") settings.motion = Motion::Dynamic;
        else if (name == "static") settings.motion = Motion::Static;
        else if (name == "kinematic") settings.motion = Motion::Kinematic;
        else fail(motionPath, "must be \"dynamic\", \"static\" or \"kinematic\", got " + jsonQuoted(name) +
                                  didYouMean(name, {"dynamic", "static", "kinematic"}));
        if (member(value, "static") && isStatic != (settings.motion == Motion::Static))
            fail(motionPath, jsonQuoted(name) + " disagrees with \"static\": " + (isStatic ? "true" : "false"));
    }
    const Motion motion = settings.motion;
    const bool immovable = motion != Motion::Dynamic;
    settings.shape = readShape(required(value, path, "shape"), memberPath(path, "shape"), motion == Motion::Static);
    const auto positive = [](const json &v, const std::string &p) { return readNumber(v, p, Range::Positive); };
    const auto finite = [](const json &v, const std::string &p) { return readNumber(v, p); };
    const auto unit = [](const json &v, const std::string &p) { return readNumber(v, p, Range::Unit); };
    const auto vector = [](const json &v, const std::string &p) { return readVector3(v, p); };
    // A static or kinematic body has infinite mass whatever the file says; a mass it
    // gives must still be a number.
    readOptional(value, path, "mass", settings.mass, immovable ? +finite : +positive);
    if (const json *inertia = member(value, "inertia")) {
        const Matrix3 tensor = readInertia(*inertia, memberPath(path, "inertia"));
        if (!immovable) settings.inertia = tensor;
    }
    if (immovable) settings.mass = 1;
    readOptional(value, path, "position", settings.position,
                 [](const json &v, const std::string &p) { return readVector3(v, p, Range::Length); });
    readOptional(value, path, "orientation", settings.orientation, readOrientation);
    readOptional(value, path, "velocity", settings.velocity, vector);
    readOptional(value, path, "rotation", settings.rotation, vector);
    readOptional(value, path, "linear_damping", settings.linearDamping, unit);
    readOptional(value, path, "angular_damping", settings.angularDamping, unit);
    readOptional(value, path, "friction", settings.material.friction,
             [](const json &v, const std::string &p) { return readNumber(v, p, Range::NonNegative); });
    readOptional(value, path, "restitution", settings.material.restitution, unit);
    readOptional(value, path, "rolling_friction", settings.material.rollingFriction,
                 [](const json &v, const std::string &p) { return readNumber(v, p, Range::NonNegative); });
    readOptional(value, path, "spinning_friction", settings.material.spinningFriction,
                 [](const json &v, const std::string &p) { return readNumber(v, p, Range::NonNegative); });
    readOptional(value, path, "can_sleep", settings.canSleep, readBool);
    readOptional(value, path, "awake", settings.awake, readBool);
    readOptional(value, path, "ccd", settings.ccd, readBool);
    readOptional(value, path, "layer", settings.layer,
                 [](const json &v, const std::string &p) { return static_cast<int>(readInteger(v, p, 0, 31)); });
    if (const json *layers = member(value, "collides_with")) {
        const std::string layersPath = memberPath(path, "collides_with");
        expectArray(*layers, layersPath, 32);
        settings.collidesWith = 0;
        for (std::size_t k = 0; k < layers->size(); ++k)
            settings.collidesWith |= 1u << readInteger((*layers)[k], elementPath(layersPath, k), 0, 31);
    }
    readOptional(value, path, "sensor", settings.sensor, readBool);
    readOptional(value, path, "gravity_scale", settings.gravityScale, finite);
    readOptional(value, path, "locked_axes", settings.lockedAxes, readLockedAxes);
    readOptional(value, path, "surface_velocity", settings.surfaceVelocity, vector);
    if (const json *oneWay = member(value, "one_way")) {
        const std::string oneWayPath = memberPath(path, "one_way");
        settings.oneWay = readVector3(*oneWay, oneWayPath);
        if (settings.oneWay->cwiseAbs().maxCoeff() == 0) fail(oneWayPath, "must not be zero");
    }
    return body;
}

using NameIndex = std::unordered_map<std::string, std::size_t>;

std::size_t readBodyName(const json &value, const std::string &path, const NameIndex &names) {
    const std::string &name = readString(value, path);
    const auto it = names.find(name);
    if (it == names.end()) fail(path, "no body named " + jsonQuoted(name));
    return it->second;
}

SceneSpring readSpring(const json &value, const std::string &path, const NameIndex &names) {
    expectObject(value, path);
    SceneSpring spring;
    spring.path = path;
    SpringSettings &settings = spring.settings;
    spring.a = readBodyName(required(value, path, "a"), memberPath(path, "a"), names);
    if (const json *b = member(value, "b"); b && !b->is_null()) {
        const std::string bPath = memberPath(path, "b");
        spring.b = readBodyName(*b, bPath, names);
        if (*spring.b == spring.a) fail(bPath, "must name a different body than a (or be null for an anchored spring)");
    }
    const auto point = [](const json &v, const std::string &p) { return readVector3(v, p, Range::Length); };
    readOptional(value, path, "a_point", settings.aPoint, point);
    readOptional(value, path, "b_point", settings.bPoint, point);
    readOptional(value, path, "stiffness", settings.stiffness,
             [](const json &v, const std::string &p) { return readNumber(v, p, Range::Positive); });
    const auto nonNegative = [](const json &v, const std::string &p) { return readNumber(v, p, Range::NonNegative); };
    readOptional(value, path, "damping", settings.damping, nonNegative);
    readOptional(value, path, "rest_length", settings.restLength,
                 [](const json &v, const std::string &p) { return readNumber(v, p, Range::NonNegativeLength); });
    if (const json *force = member(value, "force")) {
        const std::string forcePath = memberPath(path, "force");
        const std::string &name = readString(*force, forcePath);
        if (name == "automatic") settings.force = SpringForce::Automatic;
        else if (name == "explicit") settings.force = SpringForce::Explicit;
        else fail(forcePath, "unknown spring force " + jsonQuoted(name) + " (known: \"automatic\", \"explicit\")" +
                                 didYouMean(name, {"automatic", "explicit"}));
    }
    return spring;
}

JointType readJointType(const json &value, const std::string &path) {
    const std::string &name = readString(value, path);
    if (name == "ball") return JointType::Ball;
    if (name == "hinge") return JointType::Hinge;
    if (name == "fixed") return JointType::Fixed;
    if (name == "slider") return JointType::Slider;
    if (name == "distance") return JointType::Distance;
    fail(path, "unknown joint type " + jsonQuoted(name) + " (known: \"ball\", \"hinge\", \"fixed\", \"slider\", \"distance\")" +
                   didYouMean(name, {"ball", "hinge", "fixed", "slider", "distance"}));
}

// A motor: {"speed", "max_force"}, or (v3) a servo's {"target", "frequency",
// "damping_ratio", "max_force"}; both a speed and a target is an error.
void readMotor(const json &motor, const std::string &path, JointSettings &s) {
    expectObject(motor, path);
    const real maxForce = readNumber(required(motor, path, "max_force"), memberPath(path, "max_force"), Range::NonNegative);
    const json *target = member(motor, "target");
    if (!target) {
        for (const char *key : {"frequency", "damping_ratio"})
            if (member(motor, key)) fail(memberPath(path, key), "only a servo (a motor with a \"target\") has it");
        s.motor = JointMotor{readNumber(required(motor, path, "speed"), memberPath(path, "speed")), maxForce};
        return;
    }
    if (member(motor, "speed"))
        fail(memberPath(path, "speed"), "a motor has either a \"speed\" or a \"target\" (a servo), not both");
    const std::string targetPath = memberPath(path, "target");
    JointServo servo;
    servo.target = readNumber(*target, targetPath);
    if (s.type == JointType::Hinge && (servo.target < -M_PI || servo.target > M_PI))
        fail(targetPath, "a hinge's target must be within [-pi, pi], got " + describe(*target));
    servo.frequency = readNumber(required(motor, path, "frequency"), memberPath(path, "frequency"), Range::Positive);
    servo.dampingRatio = readNumber(required(motor, path, "damping_ratio"), memberPath(path, "damping_ratio"), Range::NonNegative);
    servo.maxForce = maxForce;
    s.servo = servo;
}

// A ball joint's v3 limits: "swing_limit" [a, b] (each in (0, pi]) with "normal" (required
// when a != b, perpendicular to the axis) and "twist_limit" [lo, hi] within [-pi, pi].
void readBallLimits(const json &value, const std::string &path, JointSettings &s) {
    const auto pairOf = [&](const json &pair, const std::string &pairPath) {
        expectArray(pair, pairPath, 2);
        if (pair.size() != 2) fail(pairPath, "must be two numbers, got " + describe(pair));
        return std::pair(readNumber(pair[0], elementPath(pairPath, 0)), readNumber(pair[1], elementPath(pairPath, 1)));
    };
    const json *swing = member(value, "swing_limit");
    const json *normal = member(value, "normal");
    if (normal && !swing) fail(memberPath(path, "normal"), "only a ball joint with a \"swing_limit\" has it");
    if (swing) {
        const std::string swingPath = memberPath(path, "swing_limit");
        const auto [a, b] = pairOf(*swing, swingPath);
        for (int k = 0; k < 2; ++k) {
            const real angle = k == 0 ? a : b;
            if (!(angle > 0 && angle <= M_PI))
                fail(elementPath(swingPath, static_cast<std::size_t>(k)),
                     "must be in (0, pi], got " + describe((*swing)[static_cast<std::size_t>(k)]));
        }
        s.swingLimit = JointSwingLimit{a, b};
        if (!normal && a != b) fail(swingPath, "a \"swing_limit\" whose two angles differ needs a \"normal\"");
        if (normal) {
            const std::string normalPath = memberPath(path, "normal");
            const Vector3 n = readVector3(*normal, normalPath);
            if (!(n.norm() > 1e-12)) fail(normalPath, "must not be zero, got " + describe(*normal));
            if (std::abs(n.normalized().dot(s.axis.normalized())) > 1e-6)
                fail(normalPath, "must be perpendicular to \"axis\", got " + describe(*normal));
            s.normal = n;
        }
    }
    if (const json *twist = member(value, "twist_limit")) {
        const std::string twistPath = memberPath(path, "twist_limit");
        const auto [lo, hi] = pairOf(*twist, twistPath);
        if (!(-M_PI <= lo && lo <= hi && hi <= M_PI)) fail(twistPath, "must satisfy -pi <= lo <= hi <= pi, got " + describe(*twist));
        s.twistLimit = JointLimits{lo, hi};
    }
}

SceneJoint readJoint(const json &value, const std::string &path, const NameIndex &names) {
    expectObject(value, path);
    SceneJoint joint;
    joint.path = path;
    JointSettings &s = joint.settings;
    joint.name = readString(required(value, path, "name"), memberPath(path, "name"));
    s.type = readJointType(required(value, path, "type"), memberPath(path, "type"));
    const std::string typeName = value.at("type").get<std::string>();
    joint.a = readBodyName(required(value, path, "a"), memberPath(path, "a"), names);
    if (const json &b = required(value, path, "b"); !b.is_null()) {
        const std::string bPath = memberPath(path, "b");
        joint.b = readBodyName(b, bPath, names);
        if (*joint.b == joint.a) fail(bPath, "must name a different body than a (or be null to join a to the world)");
    }
    s.anchor = readVector3(required(value, path, "anchor"), memberPath(path, "anchor"), Range::Length);
    const bool axial = s.type == JointType::Hinge || s.type == JointType::Slider;
    const bool distance = s.type == JointType::Distance;
    // A field another type has would be silently ignored: refused, at its place.
    const auto onlyFor = [&](const char *key, bool allowed, const char *types) {
        if (member(value, key) && !allowed)
            fail(memberPath(path, key), std::string("only ") + types + " joints have it, not a " + jsonQuoted(typeName) + " joint");
    };
    onlyFor("anchor_b", distance, "distance");
    const bool ball = s.type == JointType::Ball;
    onlyFor("limits", axial, "hinge and slider");
    onlyFor("swing_limit", ball, "ball");
    onlyFor("twist_limit", ball, "ball");
    onlyFor("normal", ball, "ball");
    onlyFor("motor", axial, "hinge and slider");
    onlyFor("min_distance", distance, "distance");
    onlyFor("max_distance", distance, "distance");
    onlyFor("stiffness", distance, "distance");
    onlyFor("damping", distance, "distance");
    if (const json *anchorB = member(value, "anchor_b")) s.anchorB = readVector3(*anchorB, memberPath(path, "anchor_b"), Range::Length);
    const bool limitedBall = ball && (member(value, "swing_limit") || member(value, "twist_limit"));
    if (axial || limitedBall) {
        const std::string axisPath = memberPath(path, "axis");
        s.axis = readVector3(required(value, path, "axis"), axisPath);
        if (!(s.axis.norm() > 1e-12)) fail(axisPath, "must not be zero, got " + describe(value.at("axis")));
    }
    if (const json *limits = member(value, "limits")) {
        const std::string limitsPath = memberPath(path, "limits");
        expectArray(*limits, limitsPath, 2);
        if (limits->size() != 2) fail(limitsPath, "must be [lo, hi], got " + describe(*limits));
        JointLimits l;
        l.lower = readNumber((*limits)[0], elementPath(limitsPath, 0));
        l.upper = readNumber((*limits)[1], elementPath(limitsPath, 1));
        if (!(l.lower <= l.upper)) fail(limitsPath, "lo must be <= hi, got " + describe(*limits));
        if (s.type == JointType::Hinge && (l.lower < -M_PI || l.upper > M_PI))
            fail(limitsPath, "a hinge's angles must be within [-pi, pi], got " + describe(*limits));
        s.limits = l;
    }
    if (const json *motor = member(value, "motor")) readMotor(*motor, memberPath(path, "motor"), s);
    if (ball) readBallLimits(value, path, s);
    const auto nonNegative = [](const json &v, const std::string &p) { return readNumber(v, p, Range::NonNegative); };
    if (const json *d = member(value, "min_distance")) s.minDistance = readNumber(*d, memberPath(path, "min_distance"), Range::NonNegativeLength);
    if (const json *d = member(value, "max_distance")) s.maxDistance = readNumber(*d, memberPath(path, "max_distance"), Range::NonNegativeLength);
    if (distance) {
        const real at = (s.anchor - s.anchorB.value_or(s.anchor)).norm();
        if (!(s.minDistance.value_or(at) <= s.maxDistance.value_or(at))) {
            fail(memberPath(path, s.maxDistance ? "max_distance" : "min_distance"),
                 "min_distance must be <= max_distance, got " + formatNumber(s.minDistance.value_or(at)) + " > " +
                     formatNumber(s.maxDistance.value_or(at)) + (s.minDistance && s.maxDistance ? "" : " (the anchors' distance at load)"));
        }
    }
    readOptional(value, path, "stiffness", s.stiffness, nonNegative);
    readOptional(value, path, "damping", s.damping, nonNegative);
    readOptional(value, path, "break_force", s.breakForce,
                 [](const json &v, const std::string &p) { return readNumber(v, p, Range::Positive); });
    if (const json *collide = member(value, "collide_connected")) s.collideConnected = readBool(*collide, memberPath(path, "collide_connected"));
    return joint;
}

struct EventAction {
    const char *key;
    EventKind kind;
    const char *valueKey;  // the vector it sets, or nullptr
};
constexpr EventAction kEventActions[] = {
    {"remove", EventKind::Remove, nullptr},
    {"set_velocity", EventKind::SetVelocity, "velocity"},
    {"set_rotation", EventKind::SetRotation, "rotation"},
    {"set_position", EventKind::SetPosition, "position"},
    {"apply_impulse", EventKind::ApplyImpulse, "impulse"},
    {"set_awake", EventKind::SetAwake, nullptr},
    {"remove_joint", EventKind::RemoveJoint, nullptr},
};

// An event with no known action: a key that looks like a misspelt action is named, with
// the action meant; else the event is refused as a whole.
[[noreturn]] void failWithoutAction(const json &event, const std::string &path) {
    std::vector<std::string> actions;
    for (const auto &action : kEventActions) actions.emplace_back(action.key);
    for (auto it = event.begin(); it != event.end(); ++it) {
        if (it.key() == "step") continue;
        if (const std::string guess = nearestName(it.key(), actions); !guess.empty()) {
            fail(memberPath(path, it.key()), "unknown event type " + jsonQuoted(it.key()) + "; did you mean " +
                                                 jsonQuoted(guess) + "?");
        }
    }
    fail(path, "needs one of \"remove\", \"set_velocity\", \"set_rotation\", \"set_position\", "
               "\"apply_impulse\", \"set_awake\", \"remove_joint\"");
}

SceneEvent readEvent(const json &value, const std::string &path, const Scene &scene, const NameIndex &names,
                     const NameIndex &jointNames) {
    expectObject(value, path);
    SceneEvent event;
    event.path = path;
    event.step = readInteger(required(value, path, "step"), memberPath(path, "step"), 0, kMaxSteps);
    const EventAction *action = nullptr;
    for (const auto &candidate : kEventActions) {
        if (!member(value, candidate.key)) continue;
        if (action) {
            fail(memberPath(path, candidate.key),
                 "an event does one thing; this one already has " + jsonQuoted(action->key));
        }
        action = &candidate;
    }
    if (!action) failWithoutAction(value, path);
    event.kind = action->kind;
    const std::string targetPath = memberPath(path, action->key);
    if (event.kind == EventKind::RemoveJoint) {
        const std::string &name = readString(value[action->key], targetPath);
        const auto it = jointNames.find(name);
        if (it == jointNames.end()) fail(targetPath, "no joint named " + jsonQuoted(name));
        event.joint = it->second;
        return event;
    }
    event.body = readBodyName(value[action->key], targetPath, names);
    const BodySettings &target = scene.bodies[event.body].settings;
    const Motion targetMotion = target.motion;
    if (targetMotion == Motion::Static && event.kind != EventKind::Remove) {
        fail(targetPath, "body " + jsonQuoted(target.name) + " is static; only \"remove\" applies to it");
    }
    if (targetMotion == Motion::Kinematic && (event.kind == EventKind::ApplyImpulse || event.kind == EventKind::SetAwake)) {
        fail(targetPath, "body " + jsonQuoted(target.name) +
                             " is kinematic; only \"remove\", \"set_velocity\", \"set_rotation\" and \"set_position\" apply to it");
    }
    if (action->valueKey) {
        event.value = readVector3(required(value, path, action->valueKey), memberPath(path, action->valueKey),
                                  event.kind == EventKind::SetPosition ? Range::Length : Range::Any);
    }
    if (event.kind == EventKind::ApplyImpulse) {
        if (const json *point = member(value, "point")) {
            event.point = readVector3(*point, memberPath(path, "point"), Range::Length);
        }
    }
    if (event.kind == EventKind::SetAwake) {
        event.awake = readBool(required(value, path, "awake"), memberPath(path, "awake"));
    }
    return event;
}

// Events run by step, then in file order; one that names a body an earlier event removed
// could not be applied, so it is refused now rather than in the middle of a run.
void checkRemovals(const Scene &scene) {
    std::vector<std::size_t> order(scene.events.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t x, std::size_t y) { return scene.events[x].step < scene.events[y].step; });
    std::map<std::size_t, const SceneEvent *> removedBy;
    std::map<std::size_t, const SceneEvent *> jointRemovedBy;
    for (std::size_t i : order) {
        const SceneEvent &event = scene.events[i];
        if (event.kind == EventKind::RemoveJoint) {
            const auto [it, first] = jointRemovedBy.emplace(event.joint, &event);
            if (!first) {
                fail(memberPath(event.path, "remove_joint"),
                     "joint " + jsonQuoted(scene.joints[event.joint].name) + " was removed by " + it->second->path +
                         " at step " + std::to_string(it->second->step));
            }
            continue;
        }
        const auto removed = removedBy.find(event.body);
        if (removed != removedBy.end()) {
            fail(memberPath(event.path, eventKindName(event.kind)),
                 "body " + jsonQuoted(scene.bodies[event.body].settings.name) + " was removed by " +
                     removed->second->path + " at step " + std::to_string(removed->second->step));
        }
        if (event.kind == EventKind::Remove) removedBy[event.body] = &event;
    }
}

}  // namespace

const char *eventKindName(EventKind kind) {
    for (const auto &action : kEventActions) {
        if (action.kind == kind) return action.key;
    }
    return "?";
}

Scene loadScene(const std::string &text, const std::string &fallbackName) {
    return loadSceneDocument(parseJsonDocument(text), fallbackName);
}

Scene loadSceneDocument(const json &document, const std::string &fallbackName) {
    const std::string root;
    if (!document.is_object()) fail(kTopLevelPath, "must be an object, got " + describe(document));
    Scene scene;
    scene.name = fallbackName;
    if (const json *name = member(document, "name")) {
        const std::string &text = readString(*name, "name");
        if (!text.empty()) scene.name = text;
    }
    if (const json *settings = member(document, "settings")) scene.world = readSettings(*settings, "settings", scene);

    const json &bodies = required(document, root, "bodies");
    expectArray(bodies, "bodies", kMaxBodies);
    NameIndex names;
    scene.bodies.reserve(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        SceneBody body = readBody(bodies[i], elementPath("bodies", i));
        const auto [it, inserted] = names.emplace(body.settings.name, i);
        if (!inserted) {
            fail(memberPath(body.path, "name"), "duplicate name " + jsonQuoted(body.settings.name) + ", also " +
                                                     scene.bodies[it->second].path + ".name");
        }
        scene.bodies.push_back(std::move(body));
    }

    if (const json *springs = member(document, "springs")) {
        expectArray(*springs, "springs", kMaxSprings);
        for (std::size_t i = 0; i < springs->size(); ++i) {
            scene.springs.push_back(readSpring((*springs)[i], elementPath("springs", i), names));
        }
    }
    NameIndex jointNames;
    if (const json *joints = member(document, "joints")) {
        expectArray(*joints, "joints", kMaxSprings);
        for (std::size_t i = 0; i < joints->size(); ++i) {
            SceneJoint joint = readJoint((*joints)[i], elementPath("joints", i), names);
            const auto [it, inserted] = jointNames.emplace(joint.name, i);
            if (!inserted) {
                fail(memberPath(joint.path, "name"), "duplicate joint name " + jsonQuoted(joint.name) + ", also " +
                                                          scene.joints[it->second].path + ".name");
            }
            scene.joints.push_back(std::move(joint));
        }
    }
    if (const json *events = member(document, "events")) {
        expectArray(*events, "events", kMaxEvents);
        for (std::size_t i = 0; i < events->size(); ++i) {
            scene.events.push_back(readEvent((*events)[i], elementPath("events", i), scene, names, jointNames));
        }
        checkRemovals(scene);
    }
    scene.warnings = unknownFields(document);
    return scene;
}

}  // namespace cyclone::scene
