// A scene as loaded from a scene file (the scene-format contract): world
// settings, run settings, named bodies, springs and joints between named bodies and
// scripted events.
// Everything in it has been validated; each part keeps its JSON path for later messages.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cyclone/world.h"

namespace cyclone::scene {

/// Largest number of steps a scene or the command line may ask for.
inline constexpr std::int64_t kMaxSteps = 100000000;
/// Largest number of bodies in a scene.
inline constexpr std::size_t kMaxBodies = 1000000;
// kMaxCoordinate, the largest coordinate or size a scene may give: the World's
// (cyclone/world/settings.h).

/// A body of the scene, in scene order.
struct SceneBody {
    /// JSON path of the body, e.g. "bodies[3]".
    std::string path;
    /// What is given to World::addBody (the name included).
    BodySettings settings;
};

/// A spring between two named bodies, or anchored at a world point when `b` is empty.
struct SceneSpring {
    /// JSON path of the spring, e.g. "springs[0]".
    std::string path;
    /// Index in Scene::bodies of the first body.
    std::size_t a = 0;
    /// Index in Scene::bodies of the second body; empty for an anchored spring.
    std::optional<std::size_t> b;
    /// Points, stiffness, damping and rest length (the body handles are filled in later).
    SpringSettings settings;
};

/// A joint between two named bodies, or a body and the world when `b` is empty.
struct SceneJoint {
    /// JSON path of the joint, e.g. "joints[2]".
    std::string path;
    /// Unique among the scene's joints.
    std::string name;
    /// Index in Scene::bodies of the first body.
    std::size_t a = 0;
    /// Index in Scene::bodies of the second body; empty: joined to the world.
    std::optional<std::size_t> b;
    /// Everything else (the body handles are filled in later).
    JointSettings settings;
};

/// What a scripted event does; each is one World call.
enum class EventKind { Remove, SetVelocity, SetRotation, SetPosition, ApplyImpulse, SetAwake, RemoveJoint };

/// Name of an event kind as in scene files: "remove", "set_velocity", ...
const char *eventKindName(EventKind kind);

/// An event applied at the start of step `step` (0-based), before it is simulated.
struct SceneEvent {
    /// JSON path of the event, e.g. "events[2]".
    std::string path;
    /// Step at whose start the event applies, >= 0.
    std::int64_t step = 0;
    EventKind kind = EventKind::Remove;
    /// Index in Scene::bodies of the target body (every kind but RemoveJoint).
    std::size_t body = 0;
    /// Index in Scene::joints of the joint remove_joint removes.
    std::size_t joint = 0;
    /// Velocity (m/s), rotation (rad/s), position (m) or impulse (N s), by kind.
    Vector3 value = Vector3::Zero();
    /// World-space point of an impulse (m); empty: the centre of mass.
    std::optional<Vector3> point;
    /// The state set by set_awake.
    bool awake = true;
};

/// Something about a scene that does not stop it from running, e.g. an unknown field.
struct SceneWarning {
    /// JSON path of the field, e.g. "bodies[0].positon".
    std::string path;
    /// What is wrong and what was probably meant.
    std::string message;
};

/// A whole scene.
struct Scene {
    /// The scene's name ("name" in the file; the file's stem when absent).
    std::string name;
    /// Settings of the World.
    WorldSettings world;
    /// Fixed step, s, finite, > 0.
    real dt = 1.0 / 60.0;
    /// Steps a run takes, in [0, kMaxSteps].
    std::int64_t steps = 600;
    std::vector<SceneBody> bodies;
    std::vector<SceneSpring> springs;
    std::vector<SceneJoint> joints;
    /// Events in file order (a run applies those of one step in this order).
    std::vector<SceneEvent> events;
    /// Fields the contract does not have, in file order; they change nothing.
    std::vector<SceneWarning> warnings;
};

}  // namespace cyclone::scene
