// Queries and kinematic bodies: QueryFilter::kinematicBodies decides whether rays, overlap
// queries and shape casts see them, moving (in the awake tree) or still (in the static
// tree), whatever the filter says of static and dynamic bodies.
#include <limits>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// Two 1 m kinematic cubes: one at x = +3 rising at 1 m/s, one still at x = -3; a dynamic
// cube at z = +3 and a static one at z = -3, all centred at y = 0 (no gravity). After
// one step the rising cube is at y = 1/60, still across the y = 0 plane of the queries.
struct KinematicScene {
    World world{[] {
        WorldSettings s = noSleep();
        s.gravity = Vector3::Zero();
        return s;
    }()};
    BodyId moving, still, dynamic, fixed;

    KinematicScene() {
        BodySettings s;
        s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        s.motion = Motion::Kinematic;
        s.position = Vector3(3, 0, 0);
        s.velocity = Vector3(0, 1, 0);
        moving = world.addBody(s);
        s.position = Vector3(-3, 0, 0);
        s.velocity = Vector3::Zero();
        still = world.addBody(s);
        s.motion = Motion::Dynamic;
        s.position = Vector3(0, 0, 3);
        dynamic = world.addBody(s);
        s.motion = Motion::Static;
        s.position = Vector3(0, 0, -3);
        fixed = world.addBody(s);
        world.step(kDt);
    }
};


QueryFilter only(bool kinematic, bool dynamic, bool statics) {
    QueryFilter filter;
    filter.kinematicBodies = kinematic;
    filter.dynamicBodies = dynamic;
    filter.staticBodies = statics;
    return filter;
}

TEST(KinematicQueries, RaysFindKinematicBodiesByTheirOwnFlag) {
    KinematicScene scene;
    World &world = scene.world;
    // From the origin each cube's near face is 3 - 0.5 = 2.5 m away.
    const QueryFilter kinematicOnly = only(true, false, false);
    auto hit = world.rayCast(Vector3::Zero(), Vector3(1, 0, 0), kInf, kinematicOnly);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, scene.moving);
    EXPECT_NEAR(hit->distance, 2.5, 1e-12);
    hit = world.rayCast(Vector3::Zero(), Vector3(-1, 0, 0), kInf, kinematicOnly);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, scene.still);
    EXPECT_NEAR(hit->distance, 2.5, 1e-12);
    EXPECT_FALSE(world.rayCast(Vector3::Zero(), Vector3(0, 0, 1), kInf, kinematicOnly)) << "dynamic";
    EXPECT_FALSE(world.rayCast(Vector3::Zero(), Vector3(0, 0, -1), kInf, kinematicOnly)) << "static";

    const QueryFilter noKinematic = only(false, true, true);
    EXPECT_FALSE(world.rayCast(Vector3::Zero(), Vector3(1, 0, 0), kInf, noKinematic));
    EXPECT_FALSE(world.rayCast(Vector3::Zero(), Vector3(-1, 0, 0), kInf, noKinematic));
    hit = world.rayCast(Vector3::Zero(), Vector3(0, 0, 1), kInf, noKinematic);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, scene.dynamic);
}

TEST(KinematicQueries, OverlapFindsKinematicBodiesByTheirOwnFlag) {
    KinematicScene scene;
    World &world = scene.world;
    // A 4 m sphere at the origin reaches every cube (nearest faces 2.5 m away).
    std::vector<BodyId> out;
    EXPECT_EQ(world.overlap(Shape::sphere(4), Vector3::Zero(), Quaternion::Identity(), out, only(true, false, false)), 2u);
    EXPECT_EQ(out, (std::vector<BodyId>{scene.moving, scene.still}));
    EXPECT_EQ(world.overlap(Shape::sphere(4), Vector3::Zero(), Quaternion::Identity(), out, only(false, true, true)), 2u);
    EXPECT_EQ(out, (std::vector<BodyId>{scene.dynamic, scene.fixed}));
}

TEST(KinematicQueries, ShapeCastsFindKinematicBodiesByTheirOwnFlag) {
    KinematicScene scene;
    World &world = scene.world;
    // A 0.25 m sphere from the origin touches a near face 2.5 m away after 2.25 m, short
    // of it by at most the cast's 0.1 mm tolerance.
    auto hit = world.shapeCast(Shape::sphere(0.25), Vector3::Zero(), Quaternion::Identity(), Vector3(5, 0, 0),
                               only(true, false, false));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, scene.moving);
    EXPECT_NEAR(hit->distance, 2.25, 1e-4);
    EXPECT_FALSE(world.shapeCast(Shape::sphere(0.25), Vector3::Zero(), Quaternion::Identity(), Vector3(-5, 0, 0),
                                 only(false, true, true)));
}

}  // namespace
}  // namespace cyclone::test
