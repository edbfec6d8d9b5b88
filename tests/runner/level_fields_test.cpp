// The scene format's level fields (v3): gravity_scale, locked_axes, surface_velocity,
// one_way. Each runs as the contract says, and each bad value is refused with exit 2 and
// one line naming its place.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "runner_test_support.h"

namespace {

using namespace runner_test;
using nlohmann::json;

struct FieldError {
    const char *name;
    const char *fields;   // the body's fields beside its name and shape
    const char *path;
    const char *message;  // a part of the message
};

const FieldError kFieldErrors[] = {
    {"GravityScaleNotANumber", R"("gravity_scale": "up")", "bodies[0] (\"b\").gravity_scale", "must be a number"},
    // A number out of a double's range is refused while the JSON is read, before the
    // bodies' names are known: its place is the plain path.
    {"GravityScaleInfinite", R"("gravity_scale": -1e999)", "bodies[0].gravity_scale", "finite"},
    {"GravityScaleOverflowsGravity", R"("gravity_scale": 1e308)", "bodies[0] (\"b\").gravity_scale", "1e+308"},
    {"LockedAxesNotAList", R"("locked_axes": "z")", "bodies[0] (\"b\").locked_axes", "must be an array"},
    {"LockedAxesUnknownAxis", R"("locked_axes": ["z", "w"])", "bodies[0] (\"b\").locked_axes[1]", "unknown axis \"w\""},
    {"LockedAxesNotAString", R"("locked_axes": [2])", "bodies[0] (\"b\").locked_axes[0]", "must be a string"},
    {"LockedAxesTwice", R"("locked_axes": ["rx", "rx"])", "bodies[0] (\"b\").locked_axes[1]", "given twice"},
    {"SurfaceVelocityShort", R"("surface_velocity": [1, 0])", "bodies[0] (\"b\").surface_velocity", "array of 3 numbers"},
    {"SurfaceVelocityInfinite", R"("surface_velocity": [1, 1e999, 0])", "bodies[0].surface_velocity[1]", "finite"},
    {"OneWayZero", R"("one_way": [0, 0, 0])", "bodies[0] (\"b\").one_way", "must not be zero"},
    {"OneWayNotAVector", R"("one_way": true)", "bodies[0] (\"b\").one_way", "array of 3 numbers"},
    {"LockedAxesTooMany", R"("locked_axes": ["x", "y", "z", "rx", "ry", "rz", "x"])", "bodies[0] (\"b\").locked_axes", "at most 6"},
};

class LevelFieldError : public ::testing::TestWithParam<FieldError> {};

TEST_P(LevelFieldError, RunnerExitsTwoNamingThePlace) {
    const FieldError &c = GetParam();
    TempDir dir;
    const std::string scene = dir.file("bad.json");
    writeText(scene, std::string(R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.5}, )") + c.fields +
                         "}]}");
    const Process p = runWorld({"run", scene, "--summary", dir.file("out.json")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    const std::string prefix = scene + ": " + c.path + ": ";
    EXPECT_EQ(p.err.compare(0, prefix.size(), prefix), 0) << p.err;
    EXPECT_NE(p.err.find(c.message), std::string::npos) << p.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"bad.json"});
}

INSTANTIATE_TEST_SUITE_P(Scene, LevelFieldError, ::testing::ValuesIn(kFieldErrors),
                         [](const ::testing::TestParamInfo<FieldError> &info) { return std::string(info.param.name); });

// g = 10, dt = 0.01, one sub-step (symplectic Euler): a ball of gravity_scale -0.5 rises at
// 5 m/s^2, so after 100 steps v = 5 m/s and it has risen 5 * 0.01^2 * 100 * 101 / 2
// = 2.525 m; one of scale 0 stays where it is.
TEST(LevelFields, GravityScaleNegativeHalfRisesAtHalfOfG) {
    TempDir dir;
    const std::string scene = dir.file("balloon.json");
    writeText(scene, R"({"settings": {"gravity": [0, -10, 0], "dt": 0.01, "steps": 100, "substeps": 1, "sleep": false},
        "bodies": [
          {"name": "balloon", "gravity_scale": -0.5, "shape": {"type": "sphere", "radius": 0.5}},
          {"name": "float", "gravity_scale": 0, "shape": {"type": "sphere", "radius": 0.5}, "position": [5, 0, 0]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_TRUE(p.err.empty()) << p.err;  // no unknown-field warning
    const json bodies = json::parse(readText(dir.file("s.json")))["bodies"];
    EXPECT_NEAR(bodies[0]["velocity"][1].get<double>(), 5, 1e-12);
    EXPECT_NEAR(bodies[0]["position"][1].get<double>(), 2.525, 1e-12);
    EXPECT_EQ(bodies[1]["position"][1].get<double>(), 0);
}

// Sensors filter both ways: the zone on layer 4 sees every layer, but the ghost's own
// collides_with ([0]) leaves out layer 4, so only "seen" (every layer) is reported, at
// step 0 (both start inside it; no gravity, nothing moves).
TEST(LevelFields, SensorsFilterBothWays) {
    TempDir dir;
    const std::string scene = dir.file("zone.json");
    writeText(scene, R"({"settings": {"gravity": [0, 0, 0], "steps": 10},
        "bodies": [
          {"name": "zone", "static": true, "sensor": true, "layer": 4,
           "shape": {"type": "box", "half_extents": [3, 1, 1]}},
          {"name": "seen", "shape": {"type": "sphere", "radius": 0.25}, "position": [-1, 0, 0]},
          {"name": "ghost", "collides_with": [0], "shape": {"type": "sphere", "radius": 0.25}, "position": [1, 0, 0]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json expected = json::parse(R"([{"step": 0, "sensor": "zone", "body": "seen", "event": "begin"}])");
    EXPECT_EQ(json::parse(readText(dir.file("s.json")))["sensor_events"], expected);
}

// A box locked to its x-y plane (["z", "rx", "ry"]) dropped on a ground plane whose normal
// leans towards +z: the contact pushes it along z and would tip it about x, but its z stays
// 0.25 to the bit and its orientation turns about z only (quaternion i and j exactly 0).
TEST(LevelFields, LockedAxesKeepABodyInItsPlane) {
    TempDir dir;
    const std::string scene = dir.file("planar.json");
    writeText(scene, R"({"settings": {"steps": 120},
        "bodies": [
          {"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0.2, 0.9, 0.3], "offset": 0}},
          {"name": "box", "locked_axes": ["z", "rx", "ry"], "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
           "position": [0, 2, 0.25], "orientation": [0.9, 0, 0, 0.3]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_TRUE(p.err.empty()) << p.err;
    const json box = json::parse(readText(dir.file("s.json")))["bodies"][1];
    EXPECT_EQ(box["position"][2].get<double>(), 0.25);
    EXPECT_EQ(box["orientation"][1].get<double>(), 0);
    EXPECT_EQ(box["orientation"][2].get<double>(), 0);
    EXPECT_LT(box["position"][1].get<double>(), 1.5) << "it fell onto the ground";
}

// A crate on a conveyor (a static box whose surface_velocity is [2, 0, 0]) reaches the
// belt's 2 m/s within mu g t: 0.6 * 9.81 m/s^2 takes it there in 0.34 s; after 2 s it moves
// at 2 m/s (+- 0.05). A ball jumping at 8 m/s (apex 3.76 m) through a one-way ledge (top at
// 2.1 m) rests on top of it, its centre at 2.35 m.
TEST(LevelFields, ConveyorAndOneWayLedge) {
    TempDir dir;
    const std::string scene = dir.file("level.json");
    writeText(scene, R"({"settings": {"steps": 240, "sleep": false},
        "bodies": [
          {"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
          {"name": "belt", "static": true, "surface_velocity": [2, 0, 0],
           "shape": {"type": "box", "half_extents": [30, 0.5, 1]}, "position": [0, 0.5, 10]},
          {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 1.5, 10]},
          {"name": "ledge", "static": true, "one_way": [0, 1, 0],
           "shape": {"type": "box", "half_extents": [2, 0.1, 2]}, "position": [0, 2, 0]},
          {"name": "ball", "shape": {"type": "sphere", "radius": 0.25}, "position": [0, 0.5, 0], "velocity": [0, 8, 0]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_TRUE(p.err.empty()) << p.err;
    const json bodies = json::parse(readText(dir.file("s.json")))["bodies"];
    EXPECT_NEAR(bodies[2]["velocity"][0].get<double>(), 2, 0.05);
    EXPECT_NEAR(bodies[4]["position"][1].get<double>(), 2.35, 0.01);
}

}  // namespace
