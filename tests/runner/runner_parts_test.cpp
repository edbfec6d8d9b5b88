// The runner's small parts: step-time statistics, World field names as scene paths, CSV
// fields, trace rows that read back bit for bit, files written whole or not at all.
#include <gtest/gtest.h>

#include <sstream>

#include "atomic_file.h"
#include "json_document.h"
#include "run_loop.h"
#include "runner_test_support.h"
#include "scene_world.h"
#include "trace_writer.h"

namespace {

using namespace cyclone;
using namespace cyclone::scene;
using namespace runner_test;

TEST(StepTimeStats, MedianMeanAndMax) {
    StepTimeStats stats;
    EXPECT_EQ(stats.summary().median, 0.0);
    for (double ms : {5.0, 1.0, 3.0, 2.0}) stats.add(ms);
    StepTimes times = stats.summary();
    EXPECT_DOUBLE_EQ(times.median, 2.5);
    EXPECT_DOUBLE_EQ(times.mean, 11.0 / 4);
    EXPECT_DOUBLE_EQ(times.max, 5.0);
    stats.add(4.0);
    EXPECT_DOUBLE_EQ(stats.summary().median, 3.0);
}

TEST(StepTimeStats, BeyondTheSampleTheMeanAndMaxStayExact) {
    StepTimeStats stats;
    const std::int64_t n = static_cast<std::int64_t>(StepTimeStats::kMaxSamples) * 2;
    // Times 0, 1, 2, 0, 1, 2, ...: mean 1, median 1, max 2.
    for (std::int64_t i = 0; i < n; ++i) stats.add(static_cast<double>(i % 3));
    const StepTimes times = stats.summary();
    EXPECT_EQ(stats.count(), n);
    EXPECT_NEAR(times.mean, 1.0, 1e-6);
    EXPECT_EQ(times.median, 1.0);
    EXPECT_EQ(times.max, 2.0);
}

TEST(SceneFieldPath, WorldFieldsReadAsTheSceneFileSpellsThem) {
    EXPECT_EQ(sceneFieldPath("shape.halfExtents[1]"), "shape.half_extents[1]");
    EXPECT_EQ(sceneFieldPath("velocityIterations"), "velocity_iterations");
    EXPECT_EQ(sceneFieldPath("material.friction"), "friction");
    EXPECT_EQ(sceneFieldPath("material.rollingFriction"), "rolling_friction");
    EXPECT_EQ(sceneFieldPath("aPoint"), "a_point");
    EXPECT_EQ(sceneFieldPath("shape.vertices[3][1]"), "shape.vertices[3][1]");
    EXPECT_EQ(sceneFieldPath(""), "");
}

TEST(JsonPaths, MembersElementsAndOddKeys) {
    EXPECT_EQ(memberPath("", "bodies"), "bodies");
    EXPECT_EQ(memberPath(elementPath("bodies", 3), "mass"), "bodies[3].mass");
    EXPECT_EQ(memberPath("settings", "odd key"), "settings[\"odd key\"]");
    EXPECT_EQ(jsonQuoted("a\nb"), "\"a\\nb\"");
}

TEST(TraceWriter, HeaderAndRowsThatReadBackExactly) {
    std::ostringstream out;
    TraceWriter trace(out);
    RigidBody body;
    body.setPosition(0.1, 1.0 / 3.0, -2e-17);
    body.setVelocity(1e300, -0.0, 7);
    trace.write(4, 5 * 0.1, "a,\"b\"", body);
    std::istringstream in(out.str());
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    EXPECT_EQ(header, "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,awake");
    const std::string prefix = "4,0.5,\"a,\"\"b\"\"\",";
    ASSERT_EQ(row.compare(0, prefix.size(), prefix), 0) << row;
    std::istringstream fields(row.substr(prefix.size()));
    std::vector<double> values;
    for (std::string field; std::getline(fields, field, ',');) values.push_back(std::stod(field));
    ASSERT_EQ(values.size(), 14u);
    EXPECT_EQ(values[0], 0.1);
    EXPECT_EQ(values[1], 1.0 / 3.0);
    EXPECT_EQ(values[2], -2e-17);
    EXPECT_EQ(values[3], 1.0);
    EXPECT_EQ(values[7], 1e300);
    EXPECT_EQ(values[9], 7.0);
    EXPECT_EQ(values[13], 1.0);  // awake
}

TEST(AtomicFile, RenamedOnlyWhenCommitted) {
    TempDir dir;
    {
        AtomicFile file(dir.file("out.json"));
        file.stream() << "partial";
        EXPECT_FALSE(fs::exists(dir.file("out.json")));
    }
    EXPECT_TRUE(dir.files().empty());
    {
        AtomicFile file(dir.file("out.json"));
        file.stream() << "whole";
        file.commit();
    }
    EXPECT_EQ(readText(dir.file("out.json")), "whole");
    EXPECT_EQ(dir.files(), std::vector<std::string>{"out.json"});
}

// Through a link in a temporary folder, so that a failure replaces the link, never the device.
TEST(AtomicFile, NonRegularFilesAreWrittenInPlace) {
    TempDir dir;
    fs::create_symlink("/dev/null", dir.file("null"));
    {
        AtomicFile file(dir.file("null"));
        file.stream() << "discarded";
        EXPECT_NO_THROW(file.commit());
    }
    EXPECT_TRUE(fs::is_symlink(dir.file("null")));
    EXPECT_EQ(dir.files(), std::vector<std::string>{"null"});
}

TEST(AtomicFile, UnwritablePlaceIsRefusedAtOnce) {
    TempDir dir;
    EXPECT_THROW(AtomicFile(dir.file("missing/out.json")), std::runtime_error);
}

}  // namespace
