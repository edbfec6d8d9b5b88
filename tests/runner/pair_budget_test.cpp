// The runner warns once, on stderr, when a step drops pairs for WorldSettings::maxPairs
// (issue 34, item 2), and still exits 0.
#include <gtest/gtest.h>

#include <string>

#include "runner_test_support.h"

namespace {

using namespace runner_test;

std::size_t occurrences(const std::string &text, const std::string &word) {
    std::size_t count = 0;
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++count;
    return count;
}

// 370 unit boxes at one point over a plane: 370 x 369 / 2 = 68,265 box pairs overlap, more
// than the default budget of 65,536, in the first step (the push-out of that step may
// part some of them before the second). The runner warns once, naming the first step
// that dropped pairs (0), the budget, and the count of such steps out of the two.
TEST(PairBudgetWarning, TheRunnerWarnsOnceWithTheFirstStepAndTheBudget) {
    TempDir dir;
    std::string bodies =
        R"({"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}})";
    for (int i = 0; i < 370; ++i)
        bodies += R"(, {"name": "b)" + std::to_string(i) +
                  R"(", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 0.5, 0]})";
    writeText(dir.file("pile.json"), R"({"name": "pile", "settings": {"steps": 2}, "bodies": [)" + bodies + "]}");
    const Process p = runWorld({"run", dir.file("pile.json")}, dir);
    EXPECT_EQ(p.status, 0) << p.err;
    EXPECT_EQ(occurrences(p.err, "warning"), 1u) << p.err;
    EXPECT_NE(p.err.find("step 0: warning: more bodies overlapped than 65536 pairs"), std::string::npos) << p.err;
    EXPECT_NE(p.err.find(" of 2 steps)"), std::string::npos) << p.err;

    // 100 boxes (4,950 pairs) stay within the budget: no warning.
    std::string few =
        R"({"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}})";
    for (int i = 0; i < 100; ++i)
        few += R"(, {"name": "b)" + std::to_string(i) +
               R"(", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 0.5, 0]})";
    writeText(dir.file("few.json"), R"({"name": "few", "settings": {"steps": 2}, "bodies": [)" + few + "]}");
    const Process q = runWorld({"run", dir.file("few.json")}, dir);
    EXPECT_EQ(q.status, 0) << q.err;
    EXPECT_EQ(q.err.find("warning"), std::string::npos) << q.err;
}

}  // namespace
