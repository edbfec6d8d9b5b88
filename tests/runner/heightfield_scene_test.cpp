// The scene format's "heightfield" shape (scene-format.md, shapes): read as given, and
// every bad field refused with exit 2 and one line naming its place.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "runner_test_support.h"

namespace {

using namespace runner_test;

// The runner's stderr on a scene whose only body is `body` (exit 2, one line), without
// the file's name.
std::string heightfieldRefusal(const std::string &body) {
    TempDir dir;
    const std::string scene = dir.file("scene.json");
    writeText(scene, R"({"bodies": [)" + body + "]}");
    const Process p = runWorld({"run", scene}, dir);
    EXPECT_EQ(p.status, 2) << p.err;
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    const std::string prefix = scene + ": ";
    return p.err.compare(0, prefix.size(), prefix) == 0 ? p.err.substr(prefix.size()) : p.err;
}

// A static field named "hills" whose shape has the given fields after "type".
std::string hills(const std::string &fields, bool isStatic = true) {
    return std::string(R"({"name": "hills", )") + (isStatic ? R"("static": true, )" : "") +
           R"("shape": {"type": "heightfield", )" + fields + "}}";
}

TEST(HeightfieldScene, BadFieldsAreRefusedWhereTheyStand) {
    const std::string spacing = R"("spacing": [1, 1], )";
    EXPECT_EQ(heightfieldRefusal(hills(R"("rows": 1, "columns": 2, )" + spacing + R"("heights": [0, 0])")),
              "bodies[0] (\"hills\").shape.rows: must be an integer in [2, 32768], got 1\n");
    EXPECT_EQ(heightfieldRefusal(hills(R"("rows": 2, "columns": 2, "spacing": [1, 0], "heights": [0, 0, 0, 0])")),
              "bodies[0] (\"hills\").shape.spacing[1]: must be finite and > 0 (at most 1e12 m), got 0\n");
    EXPECT_EQ(heightfieldRefusal(hills(R"("rows": 2, "columns": 2, )" + spacing + R"("heights": [0, 0, 0])")),
              "bodies[0] (\"hills\").shape.heights: must hold rows x columns = 4 numbers, got 3\n");
    EXPECT_EQ(heightfieldRefusal(hills(R"("rows": 2, "columns": 2, )" + spacing + R"("heights": [0, 0, "x", 0])")),
              "bodies[0] (\"hills\").shape.heights[2]: must be a number, got string \"x\"\n");
    EXPECT_EQ(heightfieldRefusal(hills(R"("rows": 2, "columns": 2, )" + spacing + R"("heights": [0, 0, 0, 0])", false)),
              "bodies[0] (\"hills\").shape.type: a heightfield is for static bodies only; add \"static\": true\n");
}

TEST(HeightfieldScene, AFieldIsRunAsGiven) {
    // A ball dropped from 1 m onto a flat field at y = 0.5 (placed at (-2, 0.5, -2)) rests
    // on it with its centre at 0.5 + 0.25 = 0.75 after 2 s.
    TempDir dir;
    const std::string scene = dir.file("scene.json");
    writeText(scene, R"({"settings": {"steps": 120}, "bodies": [)" +
                         std::string(R"({"name": "hills", "static": true, "position": [-2, 0.5, -2], "shape": {"type": "heightfield", "rows": 3, "columns": 3, "spacing": [2, 2], "heights": [0, 0, 0, 0, 0, 0, 0, 0, 0]}},)") +
                         R"({"name": "ball", "shape": {"type": "sphere", "radius": 0.25}, "position": [0.3, 1.5, 0.2]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const auto summary = nlohmann::json::parse(readText(dir.file("s.json")));
    bool found = false;
    for (const auto &body : summary["bodies"]) {
        if (body["name"] != "ball") continue;
        found = true;
        EXPECT_NEAR(body["position"][1].get<double>(), 0.75, 0.001);
    }
    EXPECT_TRUE(found);
}

}  // namespace
