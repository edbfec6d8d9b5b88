// Unknown fields are not silent: the loader warns about each with its place and the
// nearest known name, the runner prints one line each, and --strict refuses the scene.
// Every field of the format's second version is known, used or not.
#include <gtest/gtest.h>

#include <algorithm>

#include "runner_test_support.h"
#include "scene_fields.h"
#include "scene_loader.h"

namespace {

using namespace runner_test;
using namespace cyclone::scene;

std::vector<std::pair<std::string, std::string>> warningsOf(const std::string &text) {
    std::vector<std::pair<std::string, std::string>> found;
    for (const SceneWarning &w : loadScene(text, "x").warnings) found.emplace_back(w.path, w.message);
    return found;
}

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
    EXPECT_EQ(editDistance("positon", "position"), 1u);   // one deletion
    EXPECT_EQ(editDistance("frictoin", "friction"), 1u);  // one swap
    EXPECT_EQ(editDistance("stesp", "steps"), 1u);
    EXPECT_EQ(editDistance("mas", "mass"), 1u);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);  // k->s, e->i, +g
    EXPECT_EQ(editDistance("", "abc"), 3u);
    EXPECT_EQ(editDistance("same", "same"), 0u);
}

// The issues' three typos: each would have left its default in place without a word.
TEST(SceneFields, TyposAreNamedWithTheirPlaceAndTheFieldMeant) {
    const auto warnings = warningsOf(R"({"settings": {"stesp": 10}, "bodies": [{"name": "b",
        "shape": {"type": "sphere", "radius": 1}, "frictoin": 0.1, "positon": [0, 5, 0]}]})");
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"settings.stesp", "unknown field; did you mean \"steps\"?"},
        {"bodies[0].frictoin", "unknown field; did you mean \"friction\"?"},
        {"bodies[0].positon", "unknown field; did you mean \"position\"?"},
    };
    EXPECT_EQ(warnings, expected);
}

TEST(SceneFields, FieldsOfAnotherKindAndFieldsOutOfPlace) {
    const auto warnings = warningsOf(R"({"steps": 5, "colour": "red", "bodies": [
        {"name": "b", "shape": {"type": "sphere", "radius": 1, "half_extents": [1, 1, 1]}, "Mass": 2}],
        "events": [{"step": 1, "set_velocity": "b", "velocity": [1, 0, 0], "impulse": [0, 1, 0]}]})");
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"colour", "unknown field"},
        {"steps", "unknown field here; did you mean \"settings.steps\"?"},
        {"bodies[0].Mass", "unknown field; did you mean \"mass\"?"},
        {"bodies[0].shape.half_extents", "not a field of a \"sphere\" shape (its fields: type, radius); ignored"},
        {"events[0].impulse",
         "not a field of a \"set_velocity\" event (its fields: step, set_velocity, velocity); ignored"},
    };
    EXPECT_EQ(warnings, expected);
}

// Every field the contract names, of both versions, in one scene: no warning. Field names
// only: the loader refuses some combinations (a hinge with a distance joint's fields),
// but the table knows every field of the contract.
std::vector<SceneWarning> fieldWarnings(const std::string &text) { return unknownFields(nlohmann::json::parse(text)); }

TEST(SceneFields, EveryFieldOfTheContractIsKnown) {
    const auto warnings = fieldWarnings(R"({"name": "all",
        "settings": {"gravity": [0, -9.81, 0], "dt": 0.01, "steps": 5, "velocity_iterations": 4,
                     "position_iterations": 1, "substeps": 2, "sleep": true, "sleep_epsilon": 0.01,
                     "integrator": "newton-euler"},
        "bodies": [
          {"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
          {"name": "mesh", "static": true, "shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
                                                      "triangles": [[0, 1, 2]]}},
          {"name": "b", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "static": false, "mass": 1,
           "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "position": [0, 1, 0], "orientation": [1, 0, 0, 0],
           "velocity": [0, 0, 0], "rotation": [0, 0, 0], "linear_damping": 1, "angular_damping": 1,
           "friction": 0.5, "restitution": 0, "can_sleep": true, "awake": true, "ccd": false,
           "motion": "dynamic", "layer": 1, "collides_with": [0, 1], "sensor": false,
           "rolling_friction": 0.01, "spinning_friction": 0.01},
          {"name": "s", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 1, 0]},
          {"name": "c", "shape": {"type": "capsule", "radius": 0.5, "length": 1}, "position": [6, 1, 0]},
          {"name": "y", "shape": {"type": "cylinder", "radius": 0.5, "length": 1}, "position": [9, 1, 0]},
          {"name": "h", "shape": {"type": "convex", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]},
           "position": [12, 1, 0]}],
        "springs": [{"a": "b", "a_point": [0, 0.5, 0], "b": "s", "b_point": [0, 0, 0], "stiffness": 10,
                     "damping": 0.1, "rest_length": 1}],
        "joints": [{"name": "j", "type": "hinge", "a": "b", "b": null, "anchor": [0, 1, 0], "anchor_b": [0, 1, 0],
                    "axis": [0, 1, 0], "limits": [-1, 1], "motor": {"speed": 1, "max_force": 5},
                    "min_distance": 0, "max_distance": 1, "stiffness": 0, "damping": 0, "break_force": 100,
                    "collide_connected": false}],
        "events": [{"step": 1, "remove": "y"}, {"step": 1, "set_velocity": "b", "velocity": [1, 0, 0]},
                   {"step": 1, "set_rotation": "b", "rotation": [0, 1, 0]},
                   {"step": 2, "set_position": "s", "position": [3, 2, 0]},
                   {"step": 2, "apply_impulse": "c", "impulse": [0, 1, 0], "point": [6, 1, 0]},
                   {"step": 3, "set_awake": "c", "awake": false}, {"step": 4, "remove_joint": "j"}]})");
    EXPECT_TRUE(warnings.empty()) << warnings.size() << " warnings, the first " << warnings.front().path;
}

// A spring's "force", which the loader reads (scene_loader_test), is not reported as
// unknown; a misspelt one is.
TEST(SceneFields, ASpringsForceIsKnown) {
    const std::string bodies = R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1}}], "springs": [)";
    EXPECT_TRUE(warningsOf(bodies + R"({"a": "b", "b": null, "force": "explicit"}]})").empty());
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"springs[0].froce", "unknown field; did you mean \"force\"?"}};
    EXPECT_EQ(warningsOf(bodies + R"({"a": "b", "b": null, "froce": "explicit"}]})"), expected);
}

// An axis means something to hinges and sliders only: on a ball, fixed or distance joint
// it would be dropped without a word, so each one is warned about at its place, and the
// scene still runs (the contract gives the axis to hinges and sliders; it refuses only
// what cannot run).
const char *const kAxisScene = R"({"bodies": [
    {"name": "p", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 1, 0]},
    {"name": "q", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 2, 0]}],
  "joints": [
    {"name": "ball", "type": "ball", "a": "p", "b": null, "anchor": [0, 1.5, 0], "axis": [0, 1, 0]},
    {"name": "hinge", "type": "hinge", "a": "q", "b": "p", "anchor": [0, 1.5, 0], "axis": [0, 0, 1]},
    {"name": "fixed", "type": "fixed", "a": "q", "b": "p", "anchor": [0, 1.5, 0], "axis": [1, 0, 0]},
    {"name": "rope", "type": "distance", "a": "q", "b": null, "anchor": [0, 2, 0], "anchor_b": [0, 3, 0],
     "axis": [0, 0, 0]}]})";

TEST(SceneFields, AnAxisOnAJointWithoutOneIsWarnedAbout) {
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"joints[0].axis", "ignored for a ball joint (only hinge and slider joints have an axis)"},
        {"joints[2].axis", "ignored for a fixed joint (only hinge and slider joints have an axis)"},
        {"joints[3].axis", "ignored for a distance joint (only hinge and slider joints have an axis)"},
    };
    EXPECT_EQ(warningsOf(kAxisScene), expected);

    TempDir dir;
    const std::string scene = dir.file("axis.json");
    writeText(scene, kAxisScene);
    const Process p = runWorld({"run", scene, "--steps", "2", "--quiet", "--summary", dir.file("s.json")}, dir);
    EXPECT_EQ(p.status, 0) << p.err;
    // The runner's line names the joint (joints[0] is named "ball").
    EXPECT_EQ(p.err.rfind(scene + ": joints[0] (\"ball\").axis: ignored for a ball joint", 0), 0u) << p.err;
    EXPECT_EQ(std::count(p.err.begin(), p.err.end(), '\n'), 3) << p.err;
}

TEST(SceneFields, CompoundChildrenAreChecked) {
    // A compound's children and their shapes are checked for unknown fields too.
    const nlohmann::json document = nlohmann::json::parse(R"({"bodies": [{"name": "t", "shape": {"type": "compound",
        "children": [{"shape": {"type": "box", "half_extents": [1, 1, 1], "radius": 2}, "positon": [0, 1, 0]}]}}]})");
    const std::vector<SceneWarning> warnings = unknownFields(document);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0].path, "bodies[0].shape.children[0].positon");
    EXPECT_EQ(warnings[0].message, "unknown field; did you mean \"position\"?");
    EXPECT_EQ(warnings[1].path, "bodies[0].shape.children[0].shape.radius");
}

TEST(SceneFields, NoShippedSceneWarns) {
    for (const auto &entry : fs::directory_iterator(CYCLONE_SCENES_DIR)) {
        if (entry.path().extension() != ".json") continue;
        const Scene scene = loadScene(readText(entry.path().string()), "x");
        EXPECT_TRUE(scene.warnings.empty()) << entry.path() << ": " << scene.warnings.front().path;
    }
}

const char *const kTypoScene = R"({"settings": {"stesp": 10}, "bodies": [{"name": "b",
    "shape": {"type": "sphere", "radius": 1}, "frictoin": 0.1, "positon": [0, 5, 0]}]})";

TEST(SceneFields, TheRunnerWarnsOneLineEachAndRuns) {
    TempDir dir;
    const std::string scene = dir.file("typo.json");
    writeText(scene, kTypoScene);
    const Process p = runWorld({"run", scene, "--steps", "2", "--quiet", "--summary", dir.file("s.json")}, dir);
    EXPECT_EQ(p.status, 0) << p.err;
    EXPECT_EQ(p.err, scene + ": settings.stesp: unknown field; did you mean \"steps\"?\n" + scene +
                         ": bodies[0] (\"b\").frictoin: unknown field; did you mean \"friction\"?\n" + scene +
                         ": bodies[0] (\"b\").positon: unknown field; did you mean \"position\"?\n");
    EXPECT_TRUE(fs::exists(dir.file("s.json")));
}

TEST(SceneFields, StrictRefusesWithOneLineAndWritesNothing) {
    TempDir dir;
    const std::string scene = dir.file("typo.json");
    writeText(scene, kTypoScene);
    const Process p = runWorld(
        {"run", scene, "--strict", "--summary", dir.file("s.json"), "--trace", dir.file("t.csv")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(p.err, scene +
                         ": settings.stesp: unknown field; did you mean \"steps\"? (refused by --strict; 2 more "
                         "unknown fields)\n");
    EXPECT_TRUE(p.out.empty());
    EXPECT_EQ(dir.files(), std::vector<std::string>{"typo.json"});
    // A scene without unknown fields runs under --strict.
    const Process clean = runWorld({"run", scenePath("springs"), "--strict", "--steps", "3", "--quiet"}, dir);
    EXPECT_EQ(clean.status, 0) << clean.err;
    EXPECT_TRUE(clean.err.empty()) << clean.err;
}

}  // namespace
