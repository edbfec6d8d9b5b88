// The summary's sensor_events through the real cyclone-world: steps worked out from the
// scheme's free fall, a body asleep in the sensor at load, a removal, a layer the sensor
// does not see, and no key at all in a scene without sensors.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "runner_test_support.h"

namespace {

using namespace runner_test;
using nlohmann::json;

// g = 10, dt = 0.01, one sub-step: after k steps the ball has dropped g dt^2 k (k + 1) / 2
// = 0.0005 k (k + 1) m (symplectic Euler, as Run.FreeFallMatchesTheSchemeWorkedByHand).
// The zone spans y in [90, 92.4]; the ball (radius 0.5, from y = 100) overlaps it while
// its centre is in (89.5, 92.9): from a drop of 7.1 m (first reached after 119 steps:
// 7.14 m; 118 give 7.021) to one of 10.5 m (after 145 steps: 10.585; 144 give 10.44).
// Sensors test the poses at a step's start, so step 119 (0-based) reports the begin and
// step 145 the end. The crate sleeps inside the zone from the start (begin at step 0)
// until it is removed at step 200; the ghost, on layer 2, is never seen.
TEST(SensorEvents, SummaryListsBeginsAndEndsInOrder) {
    TempDir dir;
    const std::string scene = dir.file("zone.json");
    writeText(scene, R"({"settings": {"gravity": [0, -10, 0], "dt": 0.01, "steps": 250, "substeps": 1},
        "bodies": [
          {"name": "zone", "static": true, "sensor": true, "collides_with": [0],
           "shape": {"type": "box", "half_extents": [10, 1.2, 1]}, "position": [0, 91.2, 0]},
          {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 100, 0]},
          {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [5, 91, 0],
           "awake": false},
          {"name": "ghost", "layer": 2, "shape": {"type": "sphere", "radius": 0.5}, "position": [-5, 100, 0]}],
        "events": [{"step": 200, "remove": "crate"}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    const json expected = json::parse(R"([
        {"step": 0, "sensor": "zone", "body": "crate", "event": "begin"},
        {"step": 119, "sensor": "zone", "body": "ball", "event": "begin"},
        {"step": 145, "sensor": "zone", "body": "ball", "event": "end"},
        {"step": 200, "sensor": "zone", "body": "crate", "event": "end"}])");
    EXPECT_EQ(summary["sensor_events"], expected);
    // The sensor pushed nothing: the ball fell freely for 2.5 s.
    EXPECT_NEAR(summary["bodies"][1]["velocity"][1].get<double>(), -25, 1e-9);
    EXPECT_EQ(summary["metrics"]["contacts"], 0);
}

// The shipped trigger zone counts what enters: the two crates dropped over it, the ball
// that rolls through it (and out), not the crate dropped beside it nor the layer-3 bird
// that flies through; crate0's removal at step 300 ends its overlap. (When each begins
// depends on the contacts; the count and the order of the crates do not: crate0 falls
// 0.65 m, crate1 1.65 m, before reaching the zone's top.)
TEST(SensorEvents, TheTriggerZoneCountsWhatEnters) {
    TempDir dir;
    const Process p = runWorld({"run", scenePath("trigger-zone"), "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json events = json::parse(readText(dir.file("s.json")))["sensor_events"];
    std::vector<std::string> begins, ends;
    for (const json &e : events) {
        EXPECT_EQ(e["sensor"], "zone");
        (e["event"] == "begin" ? begins : ends).push_back(e["body"].get<std::string>());
    }
    EXPECT_EQ(begins, (std::vector<std::string>{"crate0", "crate1", "ball"}));
    EXPECT_EQ(ends, (std::vector<std::string>{"ball", "crate0"}));
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back(), json::parse(R"({"step": 300, "sensor": "zone", "body": "crate0", "event": "end"})"));
}

TEST(SensorEvents, NoKeyWithoutSensors) {
    TempDir dir;
    const Process p =
        runWorld({"run", scenePath("pyramid-10"), "--steps", "5", "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_FALSE(json::parse(readText(dir.file("s.json"))).contains("sensor_events"));
}

}  // namespace
