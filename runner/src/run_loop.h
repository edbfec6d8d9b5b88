// The run: events of step k applied at the start of step k through the World API, the
// step timed, the trace recorded, sleep and non-finite state watched after every step.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "scene.h"
#include "scene_world.h"
#include "trace_writer.h"

namespace cyclone::scene {

struct RunOptions {
    /// Steps to take, in [0, kMaxSteps].
    std::int64_t steps = 600;
    /// Number of the first step (0-based): a resumed run (--load-state) numbers its steps
    /// on from the saved run's, and its events, trace rows and times follow.
    std::int64_t firstStep = 0;
    /// Fixed step, s, finite, > 0.
    real dt = 1.0 / 60.0;
    /// Trace every K-th step (steps K-1, 2K-1, ... 0-based) and always the last one, >= 1.
    std::int64_t traceEvery = 1;
    /// Where trace rows go; none when null.
    TraceWriter *trace = nullptr;
    /// Called after each step with the steps done and the steps asked for.
    std::function<void(std::int64_t done, std::int64_t total)> progress;
};

/// Median, mean and largest time of one World::step, ms (0 when no step was taken).
struct StepTimes {
    double median = 0;
    double mean = 0;
    double max = 0;
};

/// Step times gathered during a run: the mean and the maximum are exact; the median is
/// exact up to kMaxSamples steps and taken from a uniform sample of that size beyond, so
/// that 1e8 steps do not need 800 MB.
class StepTimeStats {
public:
    static constexpr std::size_t kMaxSamples = std::size_t{1} << 22;
    /// Adds the time of one step, ms.
    void add(double ms);
    /// Steps added.
    std::int64_t count() const { return count_; }
    StepTimes summary() const;

private:
    std::vector<double> samples_;
    std::int64_t count_ = 0;
    double sum_ = 0;
    double max_ = 0;
    std::uint64_t draw_ = 0x2545f4914f6cdd1dULL;
};

/// A body began or stopped overlapping a sensor (the summary's `sensor_events`).
struct SensorEventRecord {
    /// Step (0-based) whose events reported it.
    std::int64_t step = 0;
    /// Index in Scene::bodies of the sensor.
    std::size_t sensor = 0;
    /// Index in Scene::bodies of the body.
    std::size_t body = 0;
    /// True for "begin", false for "end".
    bool begin = true;
};

struct RunResult {
    /// Steps actually taken (fewer than asked when the state became non-finite).
    std::int64_t steps = 0;
    /// Number of the first of them (RunOptions::firstStep).
    std::int64_t firstStep = 0;
    /// The step used, s.
    real dt = 0;
    /// Wall-clock time of the whole run loop, s.
    double wallSeconds = 0;
    /// Time of each World::step, ms.
    StepTimeStats stepTimes;
    /// First step (0-based) after which no dynamic body was awake; empty if none.
    std::optional<std::int64_t> firstAllAsleepStep;
    /// Deepest contact over every step of the run, m.
    real maxPenetrationOfRun = 0;
    /// Every sensor event in the order the World reported them: per step, the ends (an
    /// end a call caused comes before the step's own), then the begins.
    std::vector<SensorEventRecord> sensorEvents;
    /// True when some body's state became NaN or infinite; the run stopped there.
    bool nonFinite = false;
    /// What became non-finite, for the message: body, step and quantity.
    std::string nonFiniteWhat;
    /// Each scene joint's error after the last step it existed in, m (scene order).
    std::vector<real> jointError;
    /// Each scene joint's largest error after any step, m.
    std::vector<real> jointMaxError;
    /// The step in which each scene joint broke, if it did.
    std::vector<std::optional<std::int64_t>> jointBrokenAt;
    /// Steps that dropped pairs for WorldSettings::maxPairs (StepError::PairBudgetExceeded).
    std::int64_t pairBudgetSteps = 0;
    /// The first of them; empty if none.
    std::optional<std::int64_t> firstPairBudgetStep;
};

/// Whether position, orientation, velocity and rotation are all finite.
bool hasFiniteState(const RigidBody &body);

/// Applies one scripted event to the body `id` through the World API (the call the event
/// names); the World's InvalidArgument passes through. remove_joint is not a body's
/// event: runScene applies it.
void applyEvent(World &world, BodyId id, const SceneEvent &event);

/// Runs `world` (built from `scene`). Throws SceneError at an event's path if the World
/// refuses an event, and at "step N" if step N fails with the state still finite.
RunResult runScene(const Scene &scene, SceneWorld &world, const RunOptions &options);

}  // namespace cyclone::scene
