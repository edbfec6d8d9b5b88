// Errors that point at the mistake: a misspelt required field, event type or shape type is
// named where it stands with the word that was meant; places name the body or joint they
// are in; a JSON syntax error gives its line and column. Each case runs the real runner and
// checks its whole line.
#include <gtest/gtest.h>

#include <string>

#include "runner_test_support.h"

namespace {

using namespace runner_test;

constexpr const char *kGround =
    R"({"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}})";
constexpr const char *kCrate = R"({"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}})";

// The runner's stderr on `text`, which must be refused (exit 2, one line).
std::string refusal(const std::string &text, const std::vector<std::string> &options = {}) {
    TempDir dir;
    const std::string scene = dir.file("scene.json");
    writeText(scene, text);
    std::vector<std::string> args = {"run", scene};
    args.insert(args.end(), options.begin(), options.end());
    const Process p = runWorld(args, dir);
    EXPECT_EQ(p.status, 2) << p.err;
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    // The file's own name goes: the rest is what the tests compare.
    const std::string prefix = scene + ": ";
    EXPECT_EQ(p.err.compare(0, prefix.size(), prefix), 0) << p.err;
    return p.err.compare(0, prefix.size(), prefix) == 0 ? p.err.substr(prefix.size()) : p.err;
}

// "halfextents" is one deletion from "half_extents": the place is the misspelt key.
TEST(ErrorHints, AMisspeltRequiredFieldIsNamedWithTheFieldMeant) {
    EXPECT_EQ(refusal(R"({"bodies": [{"name": "crate", "shape": {"type": "box", "halfextents": [1, 1, 1]}}]})"),
              "bodies[0] (\"crate\").shape.halfextents: unknown field; did you mean \"half_extents\"? "
              "(\"half_extents\" is required)\n");
    // "bodys" is two edits from "bodies" (y -> i, + e), within the two allowed for 5 letters.
    EXPECT_EQ(refusal(R"({"bodys": []})"), "bodys: unknown field; did you mean \"bodies\"? (\"bodies\" is required)\n");
}

// A missing field with no near key is still "required field missing"; a key that is a
// field of its own ("b" beside a missing "a") is never taken for a misspelling.
TEST(ErrorHints, AMissingFieldWithoutANearKeyIsSaidMissing) {
    EXPECT_EQ(refusal(R"({"bodies": [{"name": "crate", "shape": {"type": "box", "size": [1, 1, 1]}}]})"),
              "bodies[0] (\"crate\").shape.half_extents: required field missing\n");
    EXPECT_EQ(refusal(std::string(R"({"bodies": [)") + kCrate + R"(], "springs": [{"b": "crate"}]})"),
              "springs[0].a: required field missing\n");
}

// "set_velocty" is one deletion from "set_velocity".
TEST(ErrorHints, AMisspeltEventTypeIsNamedWithTheTypeMeant) {
    EXPECT_EQ(refusal(std::string(R"({"bodies": [)") + kCrate +
                      R"(], "events": [{"step": 10, "set_velocty": "crate", "velocity": [1, 0, 0]}]})"),
              "events[0].set_velocty: unknown event type \"set_velocty\"; did you mean \"set_velocity\"?\n");
    // Nothing near any event type: the event is refused as a whole, as before.
    EXPECT_EQ(refusal(std::string(R"({"bodies": [)") + kCrate + R"(], "events": [{"step": 10, "explode": "crate"}]})"),
              "events[0]: needs one of \"remove\", \"set_velocity\", \"set_rotation\", \"set_position\", "
              "\"apply_impulse\", \"set_awake\", \"remove_joint\"\n");
}

// "spehre" is one swap from "sphere"; "hinje" one substitution from "hinge".
TEST(ErrorHints, AMisspeltShapeOrJointTypeIsNamedWithTheTypeMeant) {
    EXPECT_EQ(refusal(R"({"bodies": [{"name": "ball", "shape": {"type": "spehre", "radius": 1}}]})"),
              "bodies[0] (\"ball\").shape.type: unknown shape type \"spehre\" (known: box, sphere, capsule, "
              "cylinder, convex, plane, mesh, heightfield, compound); did you mean \"sphere\"?\n");
    EXPECT_EQ(refusal(std::string(R"({"bodies": [)") + kCrate +
                      R"(], "joints": [{"name": "lid", "type": "hinje", "a": "crate", "b": null, "anchor": [0, 1, 0]}]})"),
              "joints[0] (\"lid\").type: unknown joint type \"hinje\" (known: \"ball\", \"hinge\", \"fixed\", "
              "\"slider\", \"distance\"); did you mean \"hinge\"?\n");
    // "torus" is near nothing: no guess.
    EXPECT_EQ(refusal(R"({"bodies": [{"name": "ring", "shape": {"type": "torus"}}]})"),
              "bodies[0] (\"ring\").shape.type: unknown shape type \"torus\" (known: box, sphere, capsule, cylinder, "
              "convex, plane, mesh, heightfield, compound)\n");
}

// The issue's case: the 31st body of a file, bodies[30], is named by its name.
TEST(ErrorHints, PlacesNameTheBodyOrJoint) {
    std::string text = std::string(R"({"bodies": [)") + kGround;
    for (int i = 1; i < 30; ++i) {
        text += R"(, {"name": "box)" + std::to_string(i) +
                R"(", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, )" +
                std::to_string(i) + ", 0]}";
    }
    EXPECT_EQ(refusal(text + R"(, {"name": "crate", "shape": {"type": "box", "half_extents": [1, 1, 1]}, "mass": -2}]})"),
              "bodies[30] (\"crate\").mass: must be finite and > 0, got -2\n");
    EXPECT_EQ(refusal(std::string(R"({"bodies": [)") + kGround + ", " + kCrate +
                      R"(], "joints": [{"name": "lid", "type": "hinge", "a": "crate", "b": null, "anchor": [0, 1, 0], "axis": [0, 0, 0]}]})"),
              "joints[0] (\"lid\").axis: must not be zero, got an array of 3\n");
}

// Unknown fields are warned about at the named place too, and --strict refuses there.
TEST(ErrorHints, WarningsAndStrictNameTheBody) {
    TempDir dir;
    const std::string scene = dir.file("scene.json");
    writeText(scene, std::string(R"({"settings": {"steps": 1}, "bodies": [)") + kGround +
                         R"(, {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "positon": [0, 2, 0]}]})");
    const Process run = runWorld({"run", scene, "--quiet"}, dir);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, scene + ": bodies[1] (\"crate\").positon: unknown field; did you mean \"position\"?\n");
    const Process strict = runWorld({"run", scene, "--strict"}, dir);
    EXPECT_EQ(strict.status, 2);
    EXPECT_EQ(strict.err, scene + ": bodies[1] (\"crate\").positon: unknown field; did you mean \"position\"? "
                                  "(refused by --strict)\n");
}

// Line 2 is `  "settings": {"dt": 0.01,},`: two spaces, "settings" in columns 3-12, ':' 13,
// ' ' 14, '{' 15, "dt" 16-19, ':' 20, ' ' 21, 0.01 22-25, ',' 26, '}' 27.
TEST(ErrorHints, AJsonSyntaxErrorGivesLineAndColumn) {
    EXPECT_EQ(refusal("{\n  \"settings\": {\"dt\": 0.01,},\n  \"bodies\": []\n}"),
              "settings: invalid JSON at line 2, column 27: syntax error while parsing object key - unexpected '}'; "
              "expected string literal (a comma before '}': JSON allows none after the last element)\n");
    // A missing comma between two bodies: line 3 is `  {"name": "b"}`, its '{' in column 3.
    EXPECT_EQ(refusal("{\"bodies\": [\n  {\"name\": \"a\"}\n  {\"name\": \"b\"}\n]}"),
              "bodies[1]: invalid JSON at line 3, column 3: syntax error while parsing array - unexpected '{'; "
              "expected ']'\n");
}

}  // namespace
