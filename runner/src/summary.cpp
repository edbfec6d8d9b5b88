#include "summary.h"

#include <algorithm>

namespace cyclone::scene {

using nlohmann::ordered_json;

ordered_json jsonVector(const Vector3 &v) { return ordered_json::array({v.x(), v.y(), v.z()}); }

int awakeDynamicBodies(const World &world) {
    int awake = 0;
    for (const BodyId id : world.bodies()) {
        if (world.motion(id) == Motion::Dynamic && world.body(id).getAwake()) ++awake;
    }
    return awake;
}

ordered_json summaryJson(const Scene &scene, const SceneWorld &built, const RunResult &result) {
    const World &world = built.world;
    const StepTimes times = result.stepTimes.summary();
    ordered_json summary;
    summary["scene"] = scene.name;
    summary["steps"] = result.steps;
    summary["dt"] = result.dt;
    summary["wall_seconds"] = result.wallSeconds;
    summary["step_ms"] = {{"median", times.median}, {"mean", times.mean}, {"max", times.max}};
    ordered_json metrics;
    metrics["awake_bodies"] = awakeDynamicBodies(world);
    metrics["contacts"] = world.stats().contacts;
    metrics["max_penetration"] = world.stats().maxPenetration;
    metrics["kinetic_energy"] = world.kineticEnergy();
    metrics["first_all_asleep_step"] =
        result.firstAllAsleepStep ? ordered_json(*result.firstAllAsleepStep) : ordered_json(nullptr);
    metrics["non_finite"] = result.nonFinite;
    summary["metrics"] = std::move(metrics);
    ordered_json bodies = ordered_json::array();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyId id = built.ids[i];
        if (!world.contains(id)) continue;
        const RigidBody &body = world.body(id);
        const Quaternion q = body.getOrientation();
        ordered_json entry;
        entry["name"] = scene.bodies[i].settings.name;
        // A compound is reported by its frame: its origin's position and velocity.
        const Vector3 frameOffset = world.framePosition(id) - body.getPosition();
        entry["position"] = jsonVector(body.getPosition() + frameOffset);
        entry["orientation"] = ordered_json::array({q.w(), q.x(), q.y(), q.z()});
        entry["velocity"] = jsonVector(body.getVelocity() + body.getRotation().cross(frameOffset));
        entry["rotation"] = jsonVector(body.getRotation());
        entry["awake"] = body.getAwake();
        bodies.push_back(std::move(entry));
    }
    summary["bodies"] = std::move(bodies);
    if (!scene.joints.empty()) {
        ordered_json joints = ordered_json::array();
        for (std::size_t j = 0; j < scene.joints.size(); ++j) {
            ordered_json entry;
            entry["name"] = scene.joints[j].name;
            const bool ran = j < result.jointError.size();  // a run that took no step has none
            entry["broken_at_step"] =
                ran && result.jointBrokenAt[j] ? ordered_json(*result.jointBrokenAt[j]) : ordered_json(nullptr);
            entry["error"] = ran ? result.jointError[j] : 0.0;
            entry["max_error"] = ran ? result.jointMaxError[j] : 0.0;
            joints.push_back(std::move(entry));
        }
        summary["joints"] = std::move(joints);
    }
    const bool hasSensors = std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                        [](const SceneBody &body) { return body.settings.sensor; });
    if (hasSensors) {
        ordered_json events = ordered_json::array();
        for (const SensorEventRecord &e : result.sensorEvents) {
            ordered_json entry;
            entry["step"] = e.step;
            entry["sensor"] = scene.bodies[e.sensor].settings.name;
            entry["body"] = scene.bodies[e.body].settings.name;
            entry["event"] = e.begin ? "begin" : "end";
            events.push_back(std::move(entry));
        }
        summary["sensor_events"] = std::move(events);
    }
    return summary;
}

std::string summaryText(const ordered_json &summary) {
    const auto compact = [](const ordered_json &value) {
        return value.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
    };
    std::string text = "{";
    bool first = true;
    for (const auto &[key, value] : summary.items()) {
        text += first ? "\n  " : ",\n  ";
        first = false;
        text += compact(key) + ": ";
        if (!value.is_array() || value.empty()) {
            text += compact(value);
            continue;
        }
        text += "[";
        for (std::size_t i = 0; i < value.size(); ++i) text += (i ? ",\n    " : "\n    ") + compact(value[i]);
        text += "\n  ]";
    }
    return text + "\n}\n";
}

}  // namespace cyclone::scene
