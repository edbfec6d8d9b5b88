// Errors name a place the file has: a body whose inertia comes from its shape and mass is
// refused at its mass or its shape's size (with the range that works), not at an "inertia"
// it does not have; a failure inside a run names the step or the event. Summary numbers
// are numbers, or the run says honestly that they are not.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>

#include "runner_test_support.h"
#include "scene_loader.h"
#include "scene_world.h"

namespace {

using namespace runner_test;
using namespace cyclone::scene;
using nlohmann::json;

std::string body(const std::string &shape, const std::string &mass) {
    return R"({"bodies": [{"name": "b", "shape": )" + shape + (mass.empty() ? "" : R"(, "mass": )" + mass) + "}]}";
}

// Builds the scene's World; returns the error, or "" when it was accepted.
SceneError buildError(const std::string &text) {
    try {
        buildWorld(loadScene(text, "x"));
    } catch (const SceneError &error) {
        return error;
    }
    return SceneError("", "");
}

// The number after `label` in `text`.
double numberAfter(const std::string &text, const std::string &label) {
    const auto at = text.find(label);
    EXPECT_NE(at, std::string::npos) << text;
    return at == std::string::npos ? 0 : std::strtod(text.c_str() + at + label.size(), nullptr);
}

std::string text(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return buffer;
}

constexpr const char *kUnitCube = R"({"type": "box", "half_extents": [0.5, 0.5, 0.5]})";

// The World takes masses in [1e-100, 1e100] kg (kMinMass, kMaxMass: the solver's 3 x 3
// blocks must keep their determinants within doubles); outside, the mass is refused as
// such.
TEST(ErrorPlaces, AMassOutsideTheSolversRangeIsRefusedAtTheMass) {
    const SceneError error = buildError(body(kUnitCube, "1e-120"));
    EXPECT_EQ(error.path(), "bodies[0].mass") << error.what();
    EXPECT_NE(error.message().find("[1e-100, 1e100]"), std::string::npos) << error.what();
    EXPECT_NE(error.message().find("got 1e-120"), std::string::npos) << error.what();
    // The issue's mass that froze every step is refused before any step.
    EXPECT_EQ(buildError(body(kUnitCube, R"(1e-155, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]])")).path(),
              "bodies[0].mass");
}

// A unit cube's inertia is m/6 on each axis and its bounding radius R = sqrt(3)/2, so its
// moments over R^2 are (m/6) / (3/4) = 2m/9, which must be at least 1e-100 kg: masses from
// 4.5e-100 kg work. Between 1e-100 and 4.5e-100 the mass passes its own check but the
// inertia it gives does not; the file has no inertia, so the mass is named, with the range.
TEST(ErrorPlaces, AMassWhoseInertiaIsOutOfRangeIsRefusedAtTheMassWithTheMassesThatWork) {
    const SceneError error = buildError(body(kUnitCube, "2e-100"));
    EXPECT_EQ(error.path(), "bodies[0].mass") << error.what();
    EXPECT_NE(error.message().find("got 2e-100"), std::string::npos) << error.what();
    const double lowest = numberAfter(error.message(), "masses from about ");
    const double highest = numberAfter(error.message(), " to ");
    EXPECT_GT(lowest, 4.4e-100);
    EXPECT_LT(lowest, 4.6e-100);
    EXPECT_GT(highest, 0.98e100);
    EXPECT_LE(highest, 1e100);
    // The range is the World's own: just inside it loads, just outside it does not.
    EXPECT_EQ(buildError(body(kUnitCube, text(lowest * 1.02))).path(), "");
    EXPECT_EQ(buildError(body(kUnitCube, text(lowest * 0.98))).path(), "bodies[0].mass");
}

TEST(ErrorPlaces, AHugeMassIsRefusedAtTheMass) {
    const SceneError error = buildError(body(kUnitCube, "1e200"));
    EXPECT_EQ(error.path(), "bodies[0].mass") << error.what();
    EXPECT_NE(error.message().find("got 1e+200"), std::string::npos) << error.what();
    // 5.6e102-8e154 kg were once accepted with a zero inverse inertia (the cofactor
    // inverse's determinant overflowed).
    EXPECT_EQ(buildError(body(kUnitCube, "1e103")).path(), "bodies[0].mass");
}

// The range is on the moments over R^2, which do not depend on the size: a sphere of
// 1e-60 m and 1 kg (0.4 m r^2 / r^2 = 0.4 kg) loads (it was refused when the tensor's
// cofactor inverse underflowed).
TEST(ErrorPlaces, ATinyShapeOfAnOrdinaryMassLoads) {
    EXPECT_EQ(buildError(body(R"({"type": "sphere", "radius": 1e-60})", "")).path(), "");
    EXPECT_EQ(buildError(body(R"({"type": "box", "half_extents": [1e-60, 1e-60, 1e-60]})", "")).path(), "");
}

TEST(ErrorPlaces, AnInertiaTheFileGivesIsStillItsOwnPlace) {
    const SceneError error =
        buildError(body(kUnitCube, R"(1, "inertia": [[1e-300, 0, 0], [0, 1e-300, 0], [0, 0, 1e-300]])"));
    EXPECT_EQ(error.path(), "bodies[0].inertia") << error.what();
}

// A 1 kg unit cube with inertia diag(1e-6) sank through the floor (the solver spins it
// instead of holding it): its uniform moments are 1/6 kg m^2, and 1e-6 is 6e-6 of them,
// below the 0.01 the World takes. The runner exits 2 naming the inertia, writing nothing.
TEST(ErrorPlaces, AnInertiaFarBelowTheShapesExitsTwoAtTheInertia) {
    TempDir dir;
    const std::string scene = dir.file("spin.json");
    writeText(scene, R"({"bodies": [
        {"name": "g", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
        {"name": "b", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]], "position": [0, 0.5, 0]}]})");
    const Process p = runWorld({"run", scene, "--summary", dir.file("s.json")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    EXPECT_EQ(p.err.rfind(scene + ": bodies[1] (\"b\").inertia: has a moment of 6e-06 times the shape's", 0), 0u) << p.err;
    EXPECT_NE(p.err.find("from 0.01 times it up"), std::string::npos) << p.err;
    EXPECT_FALSE(fs::exists(dir.file("s.json")));
}

// The issue's body that every step fails on (1e-155 kg with an explicit inertia, touching
// the ground): the runner's line names the step (or, once the World refuses such a mass up
// front, the mass), never "run" without a place.
TEST(ErrorPlaces, AFailedStepIsNamed) {
    TempDir dir;
    const std::string scene = dir.file("freeze.json");
    writeText(scene, R"({"bodies": [
        {"name": "g", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
        {"name": "b", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "mass": 1e-155,
         "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "position": [0, 0.5, 0]}]})");
    const Process p = runWorld({"run", scene, "--steps", "3", "--summary", dir.file("s.json")}, dir);
    if (p.status == 2) {
        EXPECT_EQ(lineCount(p.err), 1) << p.err;
        const bool atStep = p.err.rfind(scene + ": step 0: the world could not take this step: ", 0) == 0;
        const bool atMass = p.err.rfind(scene + ": bodies[1] (\"b\").mass: ", 0) == 0;
        EXPECT_TRUE(atStep || atMass) << p.err;
        EXPECT_FALSE(fs::exists(dir.file("s.json")));
    } else {
        EXPECT_TRUE(p.status == 0 || p.status == 3) << p.status << p.err;
    }
}

// 1e99 kg (near the largest mass, 1e100 kg) at 3 m/s carries 4.5e99 J; at 1e104 kg the
// summary used to say null (the inertia tensor, inverted back from its inverse, was NaN)
// with "non_finite": false.
TEST(SummaryNumbers, AHeavyBodysEnergyIsANumber) {
    TempDir dir;
    const std::string scene = dir.file("heavy.json");
    writeText(scene, R"({"settings": {"gravity": [0, 0, 0]}, "bodies": [{"name": "b",
        "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "mass": 1e99, "velocity": [3, 0, 0]}]})");
    const Process p = runWorld({"run", scene, "--steps", "2", "--summary", dir.file("s.json")}, dir);
    ASSERT_EQ(p.status, 0) << p.err;
    const json metrics = json::parse(readText(dir.file("s.json")))["metrics"];
    ASSERT_TRUE(metrics["kinetic_energy"].is_number()) << metrics.dump();
    EXPECT_NEAR(metrics["kinetic_energy"].get<double>() / 4.5e99, 1.0, 1e-9);
    EXPECT_FALSE(metrics["non_finite"].get<bool>());
}

// A 1 kg ball of radius 1 (I = 0.4) spinning at 1e200 rad/s holds 0.2e400 J: no double
// holds it, so the run says so and exits 3 with "non_finite": true, not 0 with null.
TEST(SummaryNumbers, AnEnergyBeyondDoublesIsToldAsNonFinite) {
    TempDir dir;
    const std::string scene = dir.file("spin.json");
    writeText(scene, R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1},
        "rotation": [0, 1e200, 0]}]})");
    const Process p = runWorld({"run", scene, "--steps", "0", "--summary", dir.file("s.json")}, dir);
    EXPECT_EQ(p.status, 3) << p.err;
    EXPECT_NE(p.err.find("the kinetic energy exceeds the largest double (1.8e308 J) at load"), std::string::npos)
        << p.err;
    const json metrics = json::parse(readText(dir.file("s.json")))["metrics"];
    EXPECT_TRUE(metrics["non_finite"].get<bool>());
}

}  // namespace
