#include "scene_writer.h"

#include <nlohmann/json.hpp>

#include "summary.h"

namespace cyclone::scene {
namespace {

using nlohmann::ordered_json;

// A body's frame (world.framePose) when the scene was loaded and now: what carries a
// point or a direction given at load to where the body holds it now.
struct Carry {
    Matrix4 then = Matrix4::Identity();
    Matrix4 now = Matrix4::Identity();
    Vector3 point(const Vector3 &p) const { return now * (then.inverse() * p); }
    Vector3 direction(const Vector3 &d) const { return now.linear() * (then.linear().transpose() * d); }
};

Carry carryOf(const SceneBody &body, const World &world, BodyId id) {
    Carry carry;
    carry.then.linear() = body.settings.orientation.normalized().toRotationMatrix();
    carry.then.translation() = body.settings.position;
    carry.now = world.framePose(id);
    return carry;
}

void writeBodies(ordered_json &root, const Scene &scene, const SceneWorld &built, std::vector<bool> &kept) {
    const World &world = built.world;
    ordered_json bodies = ordered_json::array();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyId id = built.ids[i];
        kept[i] = world.contains(id);
        if (!kept[i]) continue;
        ordered_json entry = root["bodies"][i];
        const RigidBody &body = world.body(id);
        const Quaternion q = body.getOrientation();
        // A compound is placed by its frame (as the summary reports it).
        const Vector3 frameOffset = world.framePosition(id) - body.getPosition();
        entry["position"] = jsonVector(body.getPosition() + frameOffset);
        entry["orientation"] = ordered_json::array({q.w(), q.x(), q.y(), q.z()});
        if (world.motion(id) != Motion::Static) {
            entry["velocity"] = jsonVector(body.getVelocity() + body.getRotation().cross(frameOffset));
            entry["rotation"] = jsonVector(body.getRotation());
        }
        if (world.motion(id) == Motion::Dynamic) entry["awake"] = body.getAwake();
        bodies.push_back(std::move(entry));
    }
    root["bodies"] = std::move(bodies);
}

// Shifts a [lo, hi] pair by -by.
void shiftPair(ordered_json &pair, real by) {
    pair = ordered_json::array({pair[0].get<real>() - by, pair[1].get<real>() - by});
}

void writeJoints(ordered_json &root, const Scene &scene, const SceneWorld &built, std::vector<bool> &kept) {
    if (!root.contains("joints")) return;
    const World &world = built.world;
    ordered_json joints = ordered_json::array();
    for (std::size_t j = 0; j < scene.joints.size(); ++j) {
        const SceneJoint &joint = scene.joints[j];
        kept[j] = world.contains(built.joints[j]);
        if (!kept[j]) continue;
        ordered_json entry = root["joints"][j];
        const JointSettings &s = joint.settings;
        const Carry a = carryOf(scene.bodies[joint.a], world, built.ids[joint.a]);
        entry["anchor"] = jsonVector(a.point(s.anchor));
        if (entry.contains("axis")) entry["axis"] = jsonVector(a.direction(s.axis));
        if (s.type == JointType::Distance) {
            const Vector3 anchorB = s.anchorB ? *s.anchorB : s.anchor;
            const Vector3 nowB =
                joint.b ? carryOf(scene.bodies[*joint.b], world, built.ids[*joint.b]).point(anchorB) : anchorB;
            if (entry.contains("anchor_b") || joint.b) entry["anchor_b"] = jsonVector(nowB);
            // Their default is the anchors' distance at load, which the joint keeps.
            const real atLoad = (anchorB - s.anchor).norm();
            if (!entry.contains("min_distance")) entry["min_distance"] = s.minDistance ? *s.minDistance : atLoad;
            if (!entry.contains("max_distance")) entry["max_distance"] = s.maxDistance ? *s.maxDistance : atLoad;
        }
        if (s.type == JointType::Hinge || s.type == JointType::Slider) {
            // Limits and servo targets count from the pose at load; the joint starts anew now.
            const real position = world.jointState(built.joints[j]).position;
            if (entry.contains("limits")) shiftPair(entry["limits"], position);
            if (entry.contains("motor") && entry["motor"].contains("target"))
                entry["motor"]["target"] = entry["motor"]["target"].get<real>() - position;
        }
        joints.push_back(std::move(entry));
    }
    root["joints"] = std::move(joints);
}

}  // namespace

std::string sceneAsItIs(const std::string &text, const Scene &scene, const SceneWorld &built, std::int64_t stepsDone) {
    ordered_json root = ordered_json::parse(text);
    std::vector<bool> bodyKept(scene.bodies.size(), true);
    std::vector<bool> jointKept(scene.joints.size(), true);
    writeBodies(root, scene, built, bodyKept);
    writeJoints(root, scene, built, jointKept);
    for (std::size_t j = 0; j < scene.joints.size(); ++j) {
        if (!bodyKept[scene.joints[j].a] || (scene.joints[j].b && !bodyKept[*scene.joints[j].b])) jointKept[j] = false;
    }
    if (root.contains("springs")) {
        ordered_json springs = ordered_json::array();
        for (std::size_t k = 0; k < scene.springs.size(); ++k) {
            const SceneSpring &spring = scene.springs[k];
            if (bodyKept[spring.a] && (!spring.b || bodyKept[*spring.b])) springs.push_back(root["springs"][k]);
        }
        root["springs"] = std::move(springs);
    }
    if (root.contains("events")) {
        ordered_json events = ordered_json::array();
        for (std::size_t k = 0; k < scene.events.size(); ++k) {
            const SceneEvent &event = scene.events[k];
            if (event.step < stepsDone) continue;
            if (event.kind == EventKind::RemoveJoint ? !jointKept[event.joint] : !bodyKept[event.body]) continue;
            ordered_json entry = root["events"][k];
            entry["step"] = event.step - stepsDone;
            events.push_back(std::move(entry));
        }
        root["events"] = std::move(events);
    }
    return root.dump(2) + "\n";
}

}  // namespace cyclone::scene
