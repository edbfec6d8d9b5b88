#include "run_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace cyclone::scene {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool finite(const Vector3 &v) { return v.allFinite(); }

// The first non-finite quantity of a body, or nullptr.
const char *nonFiniteQuantity(const RigidBody &body) {
    if (!finite(body.getPosition())) return "position";
    if (!body.getOrientation().coeffs().allFinite()) return "orientation";
    if (!finite(body.getVelocity())) return "velocity";
    if (!finite(body.getRotation())) return "rotation";
    return nullptr;
}

void applyEvent(World &world, BodyId id, const SceneEvent &event) {
    switch (event.kind) {
    case EventKind::Remove: world.removeBody(id); break;
    case EventKind::SetVelocity: world.setVelocity(id, event.value); break;
    case EventKind::SetRotation: world.setRotation(id, event.value); break;
    case EventKind::SetPosition: world.setPosition(id, event.value); break;
    case EventKind::ApplyImpulse:
        if (event.point) {
            world.applyImpulse(id, event.value, *event.point);
        } else {
            world.applyImpulse(id, event.value);
        }
        break;
    case EventKind::SetAwake: world.setAwake(id, event.awake); break;
    }
}

}  // namespace

StepTimes stepTimes(const std::vector<double> &stepMs) {
    StepTimes times;
    if (stepMs.empty()) return times;
    std::vector<double> sorted = stepMs;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    times.median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    times.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(n);
    times.max = sorted.back();
    return times;
}

bool hasFiniteState(const RigidBody &body) { return nonFiniteQuantity(body) == nullptr; }

RunResult runScene(const Scene &scene, SceneWorld &built, const RunOptions &options) {
    World &world = built.world;
    RunResult result;
    result.dt = options.dt;
    result.stepMs.reserve(static_cast<std::size_t>(std::min<std::int64_t>(options.steps, 10000000)));

    std::vector<std::size_t> eventOrder(scene.events.size());
    std::iota(eventOrder.begin(), eventOrder.end(), std::size_t{0});
    std::stable_sort(eventOrder.begin(), eventOrder.end(),
                     [&](std::size_t x, std::size_t y) { return scene.events[x].step < scene.events[y].step; });
    std::size_t nextEvent = 0;
    std::vector<bool> present(scene.bodies.size(), true);

    const auto runStart = Clock::now();
    for (std::int64_t step = 0; step < options.steps; ++step) {
        for (; nextEvent < eventOrder.size() && scene.events[eventOrder[nextEvent]].step <= step; ++nextEvent) {
            const SceneEvent &event = scene.events[eventOrder[nextEvent]];
            if (event.step < step) continue;
            try {
                applyEvent(world, built.ids[event.body], event);
            } catch (const InvalidArgument &error) {
                const std::string field = sceneFieldPath(error.field());
                throw SceneError(field.empty() ? event.path : event.path + "." + field,
                                 error.problem() + " (at step " + std::to_string(step) + ")");
            }
            if (event.kind == EventKind::Remove) present[event.body] = false;
        }

        const auto stepStart = Clock::now();
        std::string stepFailure;
        try {
            world.step(options.dt);
        } catch (const std::exception &error) {
            stepFailure = error.what();
        }
        result.stepMs.push_back(secondsSince(stepStart) * 1000.0);
        result.steps = step + 1;
        result.maxPenetrationOfRun = std::max(result.maxPenetrationOfRun, world.stats().maxPenetration);

        bool anyAwake = false;
        for (std::size_t i = 0; i < scene.bodies.size() && !result.nonFinite; ++i) {
            if (!present[i]) continue;
            const BodyId id = built.ids[i];
            const RigidBody &body = world.body(id);
            if (const char *quantity = nonFiniteQuantity(body)) {
                result.nonFinite = true;
                result.nonFiniteWhat = "body " + jsonQuoted(scene.bodies[i].settings.name) + " has a non-finite " +
                                       quantity + " after step " + std::to_string(step);
            }
            if (!world.isStatic(id) && body.getAwake()) anyAwake = true;
        }
        if (!result.nonFinite && world.stats().nonFiniteBodies > 0) {
            result.nonFinite = true;
            result.nonFiniteWhat = "the world reports " + std::to_string(world.stats().nonFiniteBodies) +
                                   " bodies with a non-finite state after step " + std::to_string(step);
        }
        if (!stepFailure.empty() && !result.nonFinite) {
            throw std::runtime_error("step " + std::to_string(step) + " failed: " + stepFailure);
        }
        if (!anyAwake && !result.firstAllAsleepStep) result.firstAllAsleepStep = step;

        const bool last = step + 1 == options.steps || result.nonFinite;
        if (options.trace && ((step + 1) % options.traceEvery == 0 || last)) {
            const real time = static_cast<real>(step + 1) * options.dt;
            for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
                const BodyId id = built.ids[i];
                if (present[i] && !world.isStatic(id)) {
                    options.trace->write(step, time, scene.bodies[i].settings.name, world.body(id));
                }
            }
        }
        if (options.progress) options.progress(step + 1, options.steps);
        if (result.nonFinite) break;
    }
    result.wallSeconds = secondsSince(runStart);
    return result;
}

}  // namespace cyclone::scene
