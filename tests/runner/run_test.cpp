// End to end through the real cyclone-world: the shipped scenes run, the summary and the
// trace say the same thing in the contract's format, a blow-up exits 3, and the command
// line does what --help says.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "runner_test_support.h"

namespace {

using namespace runner_test;
using nlohmann::json;

std::vector<std::string> splitCsvLine(const std::string &line) {
    std::vector<std::string> fields;
    std::string field;
    for (char c : line) {
        if (c == ',') {
            fields.push_back(field);
            field.clear();
        } else {
            field += c;
        }
    }
    fields.push_back(field);
    return fields;
}

std::vector<std::string> lines(const std::string &text) {
    std::vector<std::string> result;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = text.find('\n', start);
        result.push_back(text.substr(start, end - start));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return result;
}

const char *const kShippedScenes[] = {"tower",   "pyramid-20", "pyramid-10", "resting-shapes", "incline",
                                      "sleep-wake", "springs", "mixed-shapes", "pendulum", "chain-20",
                                      "chain-20-heavy", "chain-20-heavy-swing", "door", "crane",
                                      "trigger-zone", "drops", "ragdoll-stairs", "servo", "platformer",
                                      "conveyor", "terrain"};

TEST(Run, EveryShippedSceneRunsAsItIs) {
    for (const char *name : kShippedScenes) {
        TempDir dir;
        const Process p = runWorld({"run", scenePath(name), "--summary", dir.file("s.json")}, dir);
        EXPECT_EQ(p.status, 0) << name << ": " << p.err;
        EXPECT_TRUE(p.err.empty()) << name << ": " << p.err;
        EXPECT_EQ(lineCount(p.out), 1) << p.out;
        const json summary = json::parse(readText(dir.file("s.json")));
        EXPECT_EQ(summary["scene"], name);
        EXPECT_FALSE(summary["metrics"]["non_finite"].get<bool>()) << name;
    }
}

TEST(Run, SummaryHasTheContractsFieldsInOrder) {
    TempDir dir;
    const Process p = runWorld({"run", scenePath("tower"), "--steps", "30", "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const auto summary = nlohmann::ordered_json::parse(readText(dir.file("s.json")));
    std::vector<std::string> keys;
    for (const auto &item : summary.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"scene", "steps", "dt", "wall_seconds", "step_ms", "metrics", "bodies"}));
    EXPECT_EQ(summary["steps"], 30);
    EXPECT_DOUBLE_EQ(summary["dt"].get<double>(), 1.0 / 60.0);
    for (const char *key : {"median", "mean", "max"}) EXPECT_GE(summary["step_ms"][key].get<double>(), 0.0) << key;
    EXPECT_LE(summary["step_ms"]["median"].get<double>(), summary["step_ms"]["max"].get<double>());
    keys.clear();
    for (const auto &item : summary["metrics"].items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"awake_bodies", "contacts", "max_penetration", "kinetic_energy",
                                              "first_all_asleep_step", "non_finite"}));
    ASSERT_EQ(summary["bodies"].size(), 13u);
    EXPECT_EQ(summary["bodies"][0]["name"], "ground");
    EXPECT_EQ(summary["bodies"][12]["name"], "box11");
    keys.clear();
    for (const auto &item : summary["bodies"][1].items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"name", "position", "orientation", "velocity", "rotation", "awake"}));
    EXPECT_EQ(summary["bodies"][1]["orientation"].size(), 4u);
}

// Semi-implicit Euler from rest under g: v_n = -g n dt, y_n = y0 - g dt^2 n (n + 1) / 2.
TEST(Run, FreeFallMatchesTheSchemeWorkedByHand) {
    TempDir dir;
    const std::string scene = dir.file("fall.json");
    writeText(scene, R"({"settings": {"gravity": [0, -10, 0], "dt": 0.01, "steps": 100, "substeps": 1, "sleep": false},
        "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 100, 0]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--quiet"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_TRUE(p.out.empty());
    const json ball = json::parse(readText(dir.file("s.json")))["bodies"][0];
    EXPECT_NEAR(ball["velocity"][1].get<double>(), -10.0, 1e-9);
    EXPECT_NEAR(ball["position"][1].get<double>(), 100 - 10 * 1e-4 * 5050, 1e-9);
    const json metrics = json::parse(readText(dir.file("s.json")))["metrics"];
    EXPECT_NEAR(metrics["kinetic_energy"].get<double>(), 0.5 * 1 * 100, 1e-6);
    EXPECT_TRUE(metrics["first_all_asleep_step"].is_null());
    EXPECT_EQ(metrics["awake_bodies"], 1);
}

TEST(Run, OverridesOfStepsAndDt) {
    TempDir dir;
    const Process p =
        runWorld({"run", scenePath("springs"), "--steps=7", "--dt", "0.004", "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    EXPECT_EQ(summary["steps"], 7);
    EXPECT_DOUBLE_EQ(summary["dt"].get<double>(), 0.004);
}

// The last recorded trace rows are the summary's dynamic bodies, to the last bit.
TEST(Run, TraceAndSummaryAgree) {
    TempDir dir;
    const Process p = runWorld({"run", scenePath("sleep-wake"), "--steps", "500", "--every", "7", "--summary",
                                dir.file("s.json"), "--trace", dir.file("t.csv")},
                               dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    const std::vector<std::string> rows = lines(readText(dir.file("t.csv")));
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows[0], "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,awake");

    std::map<long, std::vector<std::vector<std::string>>> byStep;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto fields = splitCsvLine(rows[i]);
        ASSERT_EQ(fields.size(), 17u) << rows[i];
        byStep[std::stol(fields[0])].push_back(fields);
    }
    // Every 7th step (6, 13, ...) and the last one (499).
    std::vector<long> expected;
    for (long s = 6; s < 500; s += 7) expected.push_back(s);
    expected.push_back(499);
    std::vector<long> recorded;
    for (const auto &entry : byStep) recorded.push_back(entry.first);
    EXPECT_EQ(recorded, expected);
    for (const auto &[step, stepRows] : byStep) {
        // "stack2" is removed at step 420; "ground" is static and never traced.
        EXPECT_EQ(stepRows.size(), step < 420 ? 7u : 6u) << step;
        EXPECT_EQ(std::stod(stepRows[0][1]), (step + 1) * (1.0 / 60.0));
    }

    const auto &last = byStep.rbegin()->second;
    std::vector<json> dynamicBodies;
    for (const json &body : summary["bodies"]) {
        if (body["name"] != "ground") dynamicBodies.push_back(body);
    }
    ASSERT_EQ(last.size(), dynamicBodies.size());
    for (std::size_t i = 0; i < last.size(); ++i) {
        const auto &row = last[i];
        const json &body = dynamicBodies[i];
        EXPECT_EQ(row[2], body["name"].get<std::string>());
        const std::vector<double> state = {
            body["position"][0], body["position"][1], body["position"][2], body["orientation"][0],
            body["orientation"][1], body["orientation"][2], body["orientation"][3], body["velocity"][0],
            body["velocity"][1], body["velocity"][2], body["rotation"][0], body["rotation"][1], body["rotation"][2]};
        for (std::size_t k = 0; k < state.size(); ++k) EXPECT_EQ(std::stod(row[3 + k]), state[k]) << row[2] << " " << k;
        EXPECT_EQ(row[16], body["awake"].get<bool>() ? "1" : "0");
    }
    EXPECT_EQ(summary["bodies"].size(), 7u);  // stack2 removed
}

TEST(Run, SleepWakeFallsAsleepAndTheBallWakesIt) {
    TempDir dir;
    const Process p = runWorld({"run", scenePath("sleep-wake"), "--steps", "241", "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    ASSERT_FALSE(summary["metrics"]["first_all_asleep_step"].is_null());
    EXPECT_LT(summary["metrics"]["first_all_asleep_step"].get<int>(), 240);
    // set_velocity at step 240 woke the ball.
    for (const json &body : summary["bodies"]) {
        if (body["name"] == "ball") {
            EXPECT_TRUE(body["awake"].get<bool>());
            EXPECT_GT(body["velocity"][0].get<double>(), 10.0);
        }
    }
}

TEST(Run, DeterministicSummaries) {
    TempDir dir;
    ASSERT_EQ(runWorld({"run", scenePath("pyramid-10"), "--steps", "200", "--summary", dir.file("a.json")}, dir).status, 0);
    ASSERT_EQ(runWorld({"run", scenePath("pyramid-10"), "--steps", "200", "--summary", dir.file("b.json")}, dir).status, 0);
    json a = json::parse(readText(dir.file("a.json")));
    json b = json::parse(readText(dir.file("b.json")));
    EXPECT_EQ(a["bodies"], b["bodies"]);
    EXPECT_EQ(a["metrics"]["first_all_asleep_step"], b["metrics"]["first_all_asleep_step"]);
}

TEST(Run, NoTemporaryFilesAreLeft) {
    TempDir dir;
    ASSERT_EQ(runWorld({"run", scenePath("tower"), "--steps", "20", "--summary", dir.file("s.json"), "--trace",
                        dir.file("t.csv")},
                       dir)
                  .status,
              0);
    auto files = dir.files();
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"s.json", "t.csv"}));
}

class BlowUp : public ::testing::TestWithParam<const char *> {};

TEST_P(BlowUp, ExitsThreeWithNonFiniteInTheSummary) {
    TempDir dir;
    const std::string scene = dir.file("blow.json");
    writeText(scene, GetParam());
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json"), "--trace", dir.file("t.csv")}, dir);
    EXPECT_EQ(p.status, 3) << p.err;
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    EXPECT_NE(p.err.find("non-finite"), std::string::npos) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    EXPECT_TRUE(summary["metrics"]["non_finite"].get<bool>());
    EXPECT_LT(summary["steps"].get<int>(), 100);
    EXPECT_EQ(lines(readText(dir.file("t.csv")))[0], "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,awake");
}

INSTANTIATE_TEST_SUITE_P(
    Run, BlowUp,
    ::testing::Values(
        R"({"settings": {"steps": 100}, "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1}}],
            "events": [{"step": 3, "set_velocity": "b", "velocity": [1e300, 0, 0]}]})",
        R"({"settings": {"steps": 100}, "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1},
            "velocity": [0, 1e300, 1e300]}]})",
        R"({"settings": {"steps": 100, "gravity": [0, -1e300, 0]},
            "bodies": [{"name": "b", "shape": {"type": "box", "half_extents": [1, 1, 1]}}]})",
        R"({"settings": {"steps": 100}, "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1}}],
            "events": [{"step": 0, "apply_impulse": "b", "impulse": [0, 1e300, 0]}]})"));

TEST(Cli, HelpExplainsEveryCommandAndFlag) {
    TempDir dir;
    for (const char *flag : {"--help", "help", "-h"}) {
        const Process p = runWorld({flag}, dir);
        EXPECT_EQ(p.status, 0);
        for (const char *word : {"run", "report", "help", "--steps", "--dt", "--summary", "--trace", "--every",
                                 "--quiet", "--version", "Exit status"}) {
            EXPECT_NE(p.out.find(word), std::string::npos) << word;
        }
    }
    const Process p = runWorld({"run", "--help"}, dir);
    EXPECT_EQ(p.status, 0);
    EXPECT_NE(p.out.find("--every"), std::string::npos);
}

// moving-platform.json has 8 bodies: the ground (static), platform, elevator and turntable
// (kinematic), and four dynamic boxes (crate0, crate1, rider, passenger).
TEST(Cli, ReportCountsKinematicBodiesApart) {
    TempDir dir;
    const Process p = runWorld({"report", scenePath("moving-platform"), "--steps", "1"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_NE(p.out.find("bodies       8 (4 dynamic, 3 kinematic, 1 static)\n"), std::string::npos) << p.out;
}

TEST(Cli, ReportTellsTheStory) {
    TempDir dir;
    const Process p = runWorld({"report", scenePath("tower"), "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    for (const char *word : {"bodies       13 (12 dynamic, 1 static)", "steps        600", "ms per step  median",
                             "asleep", "top body     box11", "drifted", "penetration"}) {
        EXPECT_NE(p.out.find(word), std::string::npos) << word << "\n" << p.out;
    }
    const json summary = json::parse(readText(dir.file("s.json")));
    if (summary["metrics"]["first_all_asleep_step"].is_null()) {
        EXPECT_NE(p.out.find("never"), std::string::npos);
    } else {
        EXPECT_NE(p.out.find("after step " + std::to_string(summary["metrics"]["first_all_asleep_step"].get<int>())),
                  std::string::npos)
            << p.out;
    }
}

TEST(Cli, ReportSaysWhenNothingSleeps) {
    TempDir dir;
    const Process p = runWorld({"report", scenePath("pyramid-20"), "--steps", "5"}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_NE(p.out.find("asleep       never"), std::string::npos) << p.out;
}

}  // namespace

namespace {

// The shipped heavy chain swinging from horizontal, through the runner: every joint is in
// the summary, in scene order, none broken, each within the issue's 50 mm target.
TEST(Run, JointsAreInTheSummary) {
    TempDir dir;
    const Process p = runWorld({"run", scenePath("chain-20-heavy-swing"), "--steps", "120", "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    ASSERT_EQ(summary["joints"].size(), 21u);
    for (std::size_t j = 0; j < 21; ++j) {
        const json &joint = summary["joints"][j];
        EXPECT_EQ(joint["name"], "j" + std::to_string(j));
        EXPECT_TRUE(joint["broken_at_step"].is_null());
        EXPECT_LE(joint["error"].get<double>(), joint["max_error"].get<double>());
        EXPECT_LE(joint["max_error"].get<double>(), 0.05);
    }
}

// A joint whose break force is below the weight it holds breaks in the first step (step
// 0); a remove_joint event for it later finds it gone and does nothing.
TEST(Run, BrokenJointIsReportedWithItsStep) {
    TempDir dir;
    const std::string scene = dir.file("break.json");
    writeText(scene, R"({"name": "break", "settings": {"steps": 10},
        "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.2}, "mass": 2, "position": [0, 5, 0]},
                   {"name": "c", "shape": {"type": "sphere", "radius": 0.2}, "mass": 2, "position": [3, 5, 0]}],
        "joints": [{"name": "weak", "type": "ball", "a": "b", "b": null, "anchor": [0, 5, 0], "break_force": 15},
                   {"name": "strong", "type": "ball", "a": "c", "b": null, "anchor": [3, 5, 0], "break_force": 25}],
        "events": [{"step": 5, "remove_joint": "weak"}, {"step": 5, "remove_joint": "strong"}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json summary = json::parse(readText(dir.file("s.json")));
    // Each holds m g = 19.62 N: "weak" (15 N) breaks in step 0, "strong" (25 N) holds until
    // its event removes it at step 5; both bodies then fall.
    EXPECT_EQ(summary["joints"][0]["broken_at_step"], 0);
    EXPECT_TRUE(summary["joints"][1]["broken_at_step"].is_null());
    // Held during step 0 (the break is found at its end), then 9 steps of free fall.
    EXPECT_NEAR(summary["bodies"][0]["velocity"][1].get<double>(), -9 * 9.81 / 60, 1e-9);
    EXPECT_LT(summary["bodies"][1]["velocity"][1].get<double>(), -0.5);  // 5 steps: -0.8175 m/s
    EXPECT_GT(summary["bodies"][1]["velocity"][1].get<double>(), -0.9);
}

}  // namespace
