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

TEST(SensorEvents, NoKeyWithoutSensors) {
    TempDir dir;
    const Process p =
        runWorld({"run", scenePath("pyramid-10"), "--steps", "5", "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_FALSE(json::parse(readText(dir.file("s.json"))).contains("sensor_events"));
}

}  // namespace
