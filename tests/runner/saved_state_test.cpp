// --save-state and --load-state: a run of N steps saved and resumed for M gives the trace
// rows of one run of N + M steps, byte for byte, on every shipped scene; states from
// another scene and damaged ones are refused with exit 2 and one line.
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "runner_test_support.h"
#include "../sanitized_build.h"

namespace {

using namespace runner_test;

// The rows of a trace (the header dropped) whose step is at least `first`.
std::vector<std::string> rowsFrom(const std::string &trace, long first) {
    std::vector<std::string> rows;
    std::size_t start = trace.find('\n');
    while (start != std::string::npos && start + 1 < trace.size()) {
        const std::size_t end = trace.find('\n', start + 1);
        const std::string row = trace.substr(start + 1, end == std::string::npos ? std::string::npos : end - start - 1);
        if (!row.empty() && std::stol(row.substr(0, row.find(','))) >= first) rows.push_back(row);
        start = end;
    }
    return rows;
}

std::vector<std::string> shippedScenes() {
    std::vector<std::string> names;
    for (const auto &entry : fs::directory_iterator(CYCLONE_SCENES_DIR))
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// N: steps before the save (the scenes' events fall on both sides of step 100), and M:
// steps after it. Under the sanitizers (sanitized_build.h) N = 40 and M = 25: at 100 and
// 25 this test took 113 s of the sanitized suite; the save then holds the events still to
// come, and the restore's code is the same.
constexpr int kSaved = cyclone::test::kSanitized ? 40 : 100;
constexpr int kResumed = cyclone::test::kSanitized ? 25 : 100;

TEST(SavedState, ResumedRunsGiveTheStraightRunsRowsOnEveryShippedScene) {
    const std::vector<std::string> scenes = shippedScenes();
    ASSERT_GE(scenes.size(), 20u);
    for (const std::string &name : scenes) {
        TempDir dir;
        const std::string scene = scenePath(name);
        const Process straight = runWorld({"run", scene, "--quiet", "--steps", std::to_string(kSaved + kResumed),
                                           "--trace", dir.file("straight.csv")},
                                          dir);
        ASSERT_EQ(straight.status, 0) << name << ": " << straight.err;
        const Process saved = runWorld(
            {"run", scene, "--quiet", "--steps", std::to_string(kSaved), "--save-state", dir.file("state.bin")}, dir);
        ASSERT_EQ(saved.status, 0) << name << ": " << saved.err;
        const Process resumed = runWorld({"run", scene, "--quiet", "--steps", std::to_string(kResumed), "--load-state",
                                          dir.file("state.bin"), "--trace", dir.file("resumed.csv")},
                                         dir);
        ASSERT_EQ(resumed.status, 0) << name << ": " << resumed.err;
        const std::vector<std::string> expected = rowsFrom(readText(dir.file("straight.csv")), kSaved);
        const std::vector<std::string> got = rowsFrom(readText(dir.file("resumed.csv")), 0);
        ASSERT_FALSE(expected.empty()) << name;
        ASSERT_EQ(got.size(), expected.size()) << name;
        for (std::size_t k = 0; k < got.size(); ++k) ASSERT_EQ(got[k], expected[k]) << name << ": row " << k;
    }
}

TEST(SavedState, StateOfAnotherSceneIsRefusedWithOneLine) {
    TempDir dir;
    ASSERT_EQ(runWorld({"run", scenePath("tower"), "--quiet", "--steps", "10", "--save-state", dir.file("tower.bin")}, dir).status, 0);
    const Process p = runWorld({"run", scenePath("pyramid-10"), "--quiet", "--load-state", dir.file("tower.bin")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    EXPECT_NE(p.err.find("another scene"), std::string::npos) << p.err;
}

TEST(SavedState, DamagedStateIsRefusedWithOneLine) {
    TempDir dir;
    ASSERT_EQ(runWorld({"run", scenePath("tower"), "--quiet", "--steps", "10", "--save-state", dir.file("s.bin")}, dir).status, 0);
    const std::string state = readText(dir.file("s.bin"));
    for (std::size_t at : {std::size_t(3), std::size_t(20), state.size() / 2, state.size() - 1}) {
        std::string damaged = state;
        damaged[at] = static_cast<char>(damaged[at] ^ 0x40);
        writeText(dir.file("d.bin"), damaged);
        const Process p = runWorld({"run", scenePath("tower"), "--quiet", "--load-state", dir.file("d.bin")}, dir);
        EXPECT_EQ(p.status, 2) << "byte " << at;
        EXPECT_EQ(lineCount(p.err), 1) << p.err;
    }
    writeText(dir.file("cut.bin"), state.substr(0, state.size() / 3));
    const Process cut = runWorld({"run", scenePath("tower"), "--quiet", "--load-state", dir.file("cut.bin")}, dir);
    EXPECT_EQ(cut.status, 2);
    EXPECT_EQ(lineCount(cut.err), 1) << cut.err;
}

}  // namespace

namespace {

using namespace runner_test;

// --save-scene after N steps: the scene file loads, and its bodies start where the run
// left them (positions to the last bits, as JSON numbers round-trip) with its sleep
// states; a run of it goes on.
TEST(SavedScene, StartsWhereTheRunLeftItsBodies) {
    for (const char *name : {"sleep-wake", "crane", "trigger-zone", "table-and-chair"}) {
        TempDir dir;
        const Process saved = runWorld({"run", scenePath(name), "--quiet", "--steps", "120", "--summary",
                                        dir.file("a.json"), "--save-scene", dir.file("scene.json")},
                                       dir);
        ASSERT_EQ(saved.status, 0) << name << ": " << saved.err;
        const Process loaded =
            runWorld({"run", dir.file("scene.json"), "--quiet", "--steps", "0", "--summary", dir.file("b.json")}, dir);
        ASSERT_EQ(loaded.status, 0) << name << ": " << loaded.err;
        const nlohmann::json a = nlohmann::json::parse(readText(dir.file("a.json")));
        const nlohmann::json b = nlohmann::json::parse(readText(dir.file("b.json")));
        const nlohmann::json scene = nlohmann::json::parse(readText(dir.file("scene.json")));
        ASSERT_EQ(a["bodies"].size(), b["bodies"].size()) << name;
        for (std::size_t k = 0; k < a["bodies"].size(); ++k) {
            EXPECT_EQ(a["bodies"][k]["name"], b["bodies"][k]["name"]) << name;
            // A kinematic body is awake once it has moved, not at load: only dynamic ones compare.
            if (!scene["bodies"][k].contains("motion") && !scene["bodies"][k].value("static", false)) {
                EXPECT_EQ(a["bodies"][k]["awake"], b["bodies"][k]["awake"]) << name << " body " << k;
            }
            for (int i = 0; i < 3; ++i)
                EXPECT_NEAR(a["bodies"][k]["position"][i].get<double>(), b["bodies"][k]["position"][i].get<double>(), 1e-12)
                    << name << " body " << k;
        }
        EXPECT_EQ(runWorld({"run", dir.file("scene.json"), "--quiet", "--steps", "60"}, dir).status, 0) << name;
    }
}

}  // namespace
