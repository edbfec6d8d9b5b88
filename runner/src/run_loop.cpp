#include "run_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace cyclone::scene {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool finite(const Vector3 &v) { return v.allFinite(); }

// The first non-finite quantity of a body, or nullptr. A position beyond kMaxCoordinate
// counts: collision detection cannot place the body any more.
const char *nonFiniteQuantity(const RigidBody &body) {
    if (!(body.getPosition().norm() <= kMaxCoordinate)) return "position (or one beyond 1e12 m)";
    if (!body.getOrientation().coeffs().allFinite()) return "orientation";
    if (!finite(body.getVelocity())) return "velocity";
    if (!finite(body.getRotation())) return "rotation";
    return nullptr;
}

// The largest acceleration the springs can give each body this step, from Hooke's law and
// the damping bounded by the attachment points' speeds.
std::vector<real> springAccelerations(const Scene &scene, const SceneWorld &built, const std::vector<bool> &present) {
    std::vector<real> acceleration(scene.bodies.size(), 0);
    const World &world = built.world;
    const auto pointState = [&](std::size_t index, const Vector3 &local, Vector3 &position, real &speed) {
        const RigidBody &body = world.body(built.ids[index]);
        position = body.getPointInWorldSpace(local);
        speed = body.getVelocity().norm() + body.getRotation().norm() * local.norm();
    };
    for (const SceneSpring &spring : scene.springs) {
        if (!present[spring.a] || (spring.b && !present[*spring.b])) continue;
        Vector3 a, b = spring.settings.bPoint;
        real speedA = 0, speedB = 0;
        pointState(spring.a, spring.settings.aPoint, a, speedA);
        if (spring.b) pointState(*spring.b, spring.settings.bPoint, b, speedB);
        const real force = spring.settings.stiffness * ((a - b).norm() + spring.settings.restLength) +
                           spring.settings.damping * (speedA + speedB);
        acceleration[spring.a] += force * world.body(built.ids[spring.a]).getInverseMass();
        if (spring.b) acceleration[*spring.b] += force * world.body(built.ids[*spring.b]).getInverseMass();
    }
    return acceleration;
}

// A body that one step could carry beyond kMaxCoordinate has blown up; stepping it would
// hand collision detection coordinates it cannot handle. Returns what, or "".
std::string leavesRange(const Scene &scene, const SceneWorld &built, const std::vector<bool> &present, real dt,
                        std::int64_t step) {
    const World &world = built.world;
    const std::vector<real> springs = springAccelerations(scene, built, present);
    const real gravity = world.settings().gravity.norm();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        if (!present[i] || world.isStatic(built.ids[i])) continue;
        const RigidBody &body = world.body(built.ids[i]);
        const real reach =
            body.getPosition().norm() + (body.getVelocity().norm() + (gravity + springs[i]) * dt) * dt;
        if (!(reach <= kMaxCoordinate)) {
            return "body " + jsonQuoted(scene.bodies[i].settings.name) + " blew up: step " + std::to_string(step) +
                   " would carry it beyond 1e12 m (counted as non-finite)";
        }
    }
    return "";
}

// The scene's events in the order they apply: by step, then as written.
std::vector<std::size_t> eventOrder(const std::vector<SceneEvent> &events) {
    std::vector<std::size_t> order(events.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t x, std::size_t y) { return events[x].step < events[y].step; });
    return order;
}

// Scene index by BodyId, for sensor events (whose ids may be stale: a removed body's).
class SceneIndex {
public:
    explicit SceneIndex(const std::vector<BodyId> &ids) {
        for (std::size_t i = 0; i < ids.size(); ++i) index_.emplace(key(ids[i]), i);
    }
    std::size_t of(BodyId id) const { return index_.at(key(id)); }

private:
    static std::uint64_t key(BodyId id) { return std::uint64_t(id.generation) << 32 | id.index; }
    std::unordered_map<std::uint64_t, std::size_t> index_;
};

// Appends the sensor events the World reported for `step`: the ends, then the begins.
void recordSensorEvents(const WorldEvents &events, const SceneIndex &index, std::int64_t step,
                        std::vector<SensorEventRecord> &out) {
    for (const SensorEvent &e : events.sensorEnds) out.push_back({step, index.of(e.sensor), index.of(e.body), false});
    for (const SensorEvent &e : events.sensorBegins) out.push_back({step, index.of(e.sensor), index.of(e.body), true});
}

// Applies one body event of `step`; the World's refusal becomes a SceneError at the event.
void applyBodyEvent(const SceneEvent &event, std::int64_t step, SceneWorld &built) {
    try {
        applyEvent(built.world, built.ids[event.body], event);
    } catch (const InvalidArgument &error) {
        const std::string field = sceneFieldPath(error.field());
        throw SceneError(field.empty() ? event.path : event.path + "." + field,
                         error.problem() + " (at step " + std::to_string(step) + ")");
    } catch (const std::exception &error) {
        throw SceneError(memberPath(event.path, eventKindName(event.kind)),
                         std::string(error.what()) + " (at step " + std::to_string(step) + ")");
    }
}

// Applies the events of `step` in `order` from `next` on (skipping earlier steps': a
// resumed run's), advancing `next` and marking removed bodies in `present`. Returns the
// events' paths, for a failure of the step.
std::string applyEventsOf(std::int64_t step, const Scene &scene, const std::vector<std::size_t> &order,
                          std::size_t &next, SceneWorld &built, std::vector<bool> &present) {
    std::string paths;
    for (; next < order.size() && scene.events[order[next]].step <= step; ++next) {
        const SceneEvent &event = scene.events[order[next]];
        if (event.step < step) continue;
        if (event.kind == EventKind::RemoveJoint) {
            // A joint that broke, or went with one of its bodies, is already gone.
            const JointId joint = built.joints[event.joint];
            if (built.world.contains(joint)) built.world.removeJoint(joint);
        } else {
            applyBodyEvent(event, step, built);
            if (event.kind == EventKind::Remove) present[event.body] = false;
        }
        paths += (paths.empty() ? "" : ", ") + event.path;
    }
    return paths;
}

// Takes one step, its time added to `times`; returns why the World could not, or "".
std::string timedStep(World &world, real dt, StepTimeStats &times) {
    const auto stepStart = Clock::now();
    std::string failure;
    try {
        world.step(dt);
    } catch (const std::exception &error) {
        failure = error.what();
    }
    times.add(secondsSince(stepStart) * 1000.0);
    return failure;
}

// Marks the run non-finite at the first body with a non-finite quantity after `step`, or
// when the World isolated bodies for one; returns whether any dynamic body is awake (as
// far as the bodies were read).
bool checkBodies(const Scene &scene, const SceneWorld &built, const std::vector<bool> &present, std::int64_t step,
                 RunResult &result) {
    const World &world = built.world;
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
        if (world.motion(id) == Motion::Dynamic && body.getAwake()) anyAwake = true;
    }
    if (!result.nonFinite && world.stats().isolatedBodies > 0) {
        result.nonFinite = true;
        result.nonFiniteWhat = "the world found a non-finite state (" + std::to_string(world.stats().isolatedBodies) +
                               " of its bodies) in step " + std::to_string(step);
    }
    return anyAwake;
}

// Records which scene joints broke in `step` and every present joint's error after it.
void recordJoints(const SceneWorld &built, std::int64_t step, RunResult &result) {
    const World &world = built.world;
    for (const JointBreak &broken : world.events().jointsBroken) {
        const auto it = std::find(built.joints.begin(), built.joints.end(), broken.joint);
        if (it != built.joints.end()) result.jointBrokenAt[static_cast<std::size_t>(it - built.joints.begin())] = step;
    }
    for (std::size_t j = 0; j < built.joints.size(); ++j) {
        if (!world.contains(built.joints[j])) continue;
        const real error = world.jointState(built.joints[j]).error;
        result.jointError[j] = error;
        result.jointMaxError[j] = std::max(result.jointMaxError[j], error);
    }
}

// Writes the trace rows of `step`: every present body that is not static.
void writeTraceRows(const Scene &scene, const SceneWorld &built, const std::vector<bool> &present, std::int64_t step,
                    real dt, TraceWriter &trace) {
    const World &world = built.world;
    const real time = static_cast<real>(step + 1) * dt;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyId id = built.ids[i];
        if (present[i] && !world.isStatic(id)) {
            trace.write(step, time, scene.bodies[i].settings.name, world.body(id),
                        world.framePosition(id) - world.body(id).getPosition());
        }
    }
}

// The summary reports the energy as a number; one too large for a double is a state the
// run cannot report, so it is told as non-finite rather than written as null.
void checkEnergy(const World &world, RunResult &result) {
    if (result.nonFinite || std::isfinite(world.kineticEnergy())) return;
    result.nonFinite = true;
    result.nonFiniteWhat = "the kinetic energy exceeds the largest double (1.8e308 J) " +
                           (result.steps ? "after step " + std::to_string(result.firstStep + result.steps - 1)
                                         : std::string("at load"));
}

}  // namespace

void StepTimeStats::add(double ms) {
    ++count_;
    sum_ += ms;
    max_ = std::max(max_, ms);
    if (samples_.size() < kMaxSamples) {
        samples_.push_back(ms);
        return;
    }
    // Reservoir sampling (xorshift64 draws): every step stays in the sample with equal odds.
    draw_ ^= draw_ << 13;
    draw_ ^= draw_ >> 7;
    draw_ ^= draw_ << 17;
    const std::uint64_t slot = draw_ % static_cast<std::uint64_t>(count_);
    if (slot < kMaxSamples) samples_[slot] = ms;
}

StepTimes StepTimeStats::summary() const {
    StepTimes times;
    if (count_ == 0) return times;
    std::vector<double> sorted = samples_;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    times.median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    times.mean = sum_ / static_cast<double>(count_);
    times.max = max_;
    return times;
}

bool hasFiniteState(const RigidBody &body) { return nonFiniteQuantity(body) == nullptr; }

void applyEvent(World &world, BodyId id, const SceneEvent &event) {
    switch (event.kind) {
    case EventKind::Remove: world.removeBody(id); break;
    case EventKind::SetVelocity: world.setVelocity(id, event.value); break;
    case EventKind::SetRotation: world.setRotation(id, event.value); break;
    case EventKind::SetPosition: world.setFramePosition(id, event.value); break;
    case EventKind::ApplyImpulse:
        if (event.point) {
            world.applyImpulse(id, event.value, *event.point);
        } else {
            world.applyImpulse(id, event.value);
        }
        break;
    case EventKind::SetAwake: world.setAwake(id, event.awake); break;
    case EventKind::RemoveJoint: break;
    }
}

RunResult runScene(const Scene &scene, SceneWorld &built, const RunOptions &options) {
    World &world = built.world;
    RunResult result;
    result.dt = options.dt;
    const std::vector<std::size_t> order = eventOrder(scene.events);
    std::size_t nextEvent = 0;
    // A resumed run's World lacks the bodies removed before the save.
    std::vector<bool> present(scene.bodies.size(), true);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) present[i] = world.contains(built.ids[i]);
    const std::int64_t first = options.firstStep;
    const std::int64_t end = first + options.steps;
    result.firstStep = first;
    const SceneIndex sceneIndex(built.ids);
    result.jointError.assign(scene.joints.size(), 0);
    result.jointMaxError.assign(scene.joints.size(), 0);
    result.jointBrokenAt.assign(scene.joints.size(), std::nullopt);
    const auto runStart = Clock::now();
    for (std::int64_t step = first; step < end; ++step) {
        const std::string eventsOfStep = applyEventsOf(step, scene, order, nextEvent, built, present);
        if (std::string what = leavesRange(scene, built, present, options.dt, step); !what.empty()) {
            result.nonFinite = true;
            result.nonFiniteWhat = what;
            break;
        }
        const std::string stepFailure = timedStep(world, options.dt, result.stepTimes);
        result.steps = step + 1 - first;
        result.maxPenetrationOfRun = std::max(result.maxPenetrationOfRun, world.stats().maxPenetration);
        if (stepFailure.empty()) recordSensorEvents(world.events(), sceneIndex, step, result.sensorEvents);
        if (world.stats().errors & StepError::PairBudgetExceeded) {
            if (!result.firstPairBudgetStep) result.firstPairBudgetStep = step;
            ++result.pairBudgetSteps;
        }
        const bool anyAwake = checkBodies(scene, built, present, step, result);
        if (!stepFailure.empty() && !result.nonFinite) {
            throw SceneError("step " + std::to_string(step),
                             "the world could not take this step" +
                                 (eventsOfStep.empty() ? std::string() : " (after " + eventsOfStep + ")") + ": " +
                                 stepFailure);
        }
        if (!anyAwake && !result.nonFinite && !result.firstAllAsleepStep) result.firstAllAsleepStep = step;
        recordJoints(built, step, result);
        const bool last = step + 1 == end || result.nonFinite;
        if (options.trace && ((step + 1) % options.traceEvery == 0 || last))
            writeTraceRows(scene, built, present, step, options.dt, *options.trace);
        if (options.progress) options.progress(step + 1 - first, options.steps);
        if (result.nonFinite) break;
    }
    result.wallSeconds = secondsSince(runStart);
    checkEnergy(world, result);
    return result;
}

}  // namespace cyclone::scene
