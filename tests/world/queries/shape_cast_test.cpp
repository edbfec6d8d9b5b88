// World::shapeCast: times of impact worked out in closed form, filters, bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// The cast leaves the shapes apart by at most 0.1 mm (World::shapeCast).
constexpr real kTolerance = 1e-4;

TEST(ShapeCast, SphereAgainstBoxFace) {
    // A 0.5 m sphere from the origin along +x by 10 m meets the face x = 4 of a 2 m cube
    // centred at x = 5 when its centre reaches x = 4 - 0.5 = 3.5: 3.5 m, fraction 0.35,
    // touching at (4, 0, 0) with the face's normal -x.
    World world;
    const BodyId box = addStatic(world, Shape::box({1, 1, 1}), {5, 0, 0});
    const auto hit = world.shapeCast(Shape::sphere(0.5), Vector3::Zero(), Quaternion::Identity(), Vector3(10, 0, 0));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, box);
    EXPECT_LE(hit->distance, 3.5);
    EXPECT_GE(hit->distance, 3.5 - kTolerance);
    EXPECT_NEAR(hit->fraction, hit->distance / 10, 1e-15);
    EXPECT_NEAR((hit->point - Vector3(4, 0, 0)).norm(), 0, kTolerance);
    EXPECT_NEAR((hit->normal - Vector3(-1, 0, 0)).norm(), 0, 1e-9);
}

TEST(ShapeCast, SphereAgainstSphereOffAxis) {
    // A 0.5 m sphere along the x axis, a 1 m sphere centred at (5, 1, 0): they touch when
    // the centres are 1.5 m apart, (x - 5)^2 + 1 = 2.25, x = 5 - sqrt(1.25) = 3.8819660 m.
    // The normal is from the target's centre to the cast sphere's: (x - 5, -1, 0) / 1.5,
    // and the point is 1 m along it from the target's centre.
    World world;
    const BodyId ball = addStatic(world, Shape::sphere(1), {5, 1, 0});
    const auto hit = world.shapeCast(Shape::sphere(0.5), Vector3::Zero(), Quaternion::Identity(), Vector3(10, 0, 0));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, ball);
    const real x = 5 - std::sqrt(1.25);
    EXPECT_LE(hit->distance, x);
    EXPECT_GE(hit->distance, x - 2 * kTolerance);  // a gap of 0.1 mm along a slanted normal
    const Vector3 normal = Vector3(x - 5, -1, 0) / 1.5;
    EXPECT_NEAR((hit->normal - normal).norm(), 0, 1e-3);
    EXPECT_NEAR((hit->point - (Vector3(5, 1, 0) + normal)).norm(), 0, 1e-3);
}

TEST(ShapeCast, MissesWhatIsNotOnTheWay) {
    // The same spheres 2 m apart across the path (1.5 m would touch): no hit; nor when the
    // target lies behind the start.
    World world;
    addStatic(world, Shape::sphere(1), {5, 2, 0});
    addStatic(world, Shape::box({1, 1, 1}), {-5, 0, 0});
    EXPECT_FALSE(world.shapeCast(Shape::sphere(0.5), Vector3::Zero(), Quaternion::Identity(), Vector3(10, 0, 0)));
    // Too short: the box face is 3.5 m away.
    EXPECT_FALSE(world.shapeCast(Shape::sphere(0.5), Vector3::Zero(), Quaternion::Identity(), Vector3(-3.4, 0, 0)));
}

TEST(ShapeCast, FiltersAsRays) {
    // Two boxes on the path, the nearer on layer 3 and ignorable: each filter that leaves
    // it out gets the farther one (face at x = 8: 8 - 0.5 = 7.5 m).
    World world;
    const BodyId near = addStatic(world, Shape::box({1, 1, 1}), {5, 0, 0}, 3);
    const BodyId far = addStatic(world, Shape::box({1, 1, 1}), {9, 0, 0});
    const Shape ball = Shape::sphere(0.5);
    const Quaternion none = Quaternion::Identity();
    EXPECT_EQ(world.shapeCast(ball, Vector3::Zero(), none, Vector3(10, 0, 0))->body, near);
    QueryFilter filter;
    filter.ignore = near;
    auto hit = world.shapeCast(ball, Vector3::Zero(), none, Vector3(10, 0, 0), filter);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, far);
    EXPECT_NEAR(hit->distance, 7.5, kTolerance);
    filter = QueryFilter();
    filter.layers = ~(1u << 3);
    EXPECT_EQ(world.shapeCast(ball, Vector3::Zero(), none, Vector3(10, 0, 0), filter)->body, far);
    filter = QueryFilter();
    filter.accept = [&](BodyId id) { return id != near; };
    EXPECT_EQ(world.shapeCast(ball, Vector3::Zero(), none, Vector3(10, 0, 0), filter)->body, far);
    filter = QueryFilter();
    filter.staticBodies = false;
    EXPECT_FALSE(world.shapeCast(ball, Vector3::Zero(), none, Vector3(10, 0, 0), filter));
}

TEST(ShapeCast, RestingShapeSlidesAlongWhatItTouches) {
    // A 0.5 m cube resting on a plane (bottom face on y = 0) cast sideways meets nothing;
    // cast down it hits the plane at once; a wall 2 m ahead (face at x = 2) stops it at
    // 2 - 0.5 = 1.5 m.
    World world;
    const BodyId floor = addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    const Shape cube = Shape::box({0.5, 0.5, 0.5});
    const Quaternion none = Quaternion::Identity();
    EXPECT_FALSE(world.shapeCast(cube, Vector3(0, 0.5, 0), none, Vector3(5, 0, 0)));
    const auto down = world.shapeCast(cube, Vector3(0, 0.5, 0), none, Vector3(0, -1, 0));
    ASSERT_TRUE(down);
    EXPECT_EQ(down->body, floor);
    EXPECT_NEAR(down->distance, 0, kTolerance);
    EXPECT_NEAR((down->normal - Vector3::UnitY()).norm(), 0, 1e-12);
    const BodyId wall = addStatic(world, Shape::box({0.5, 2, 2}), {2.5, 2, 0});
    const auto ahead = world.shapeCast(cube, Vector3(0, 0.5, 0), none, Vector3(5, 0, 0));
    ASSERT_TRUE(ahead);
    EXPECT_EQ(ahead->body, wall);
    EXPECT_NEAR(ahead->distance, 1.5, kTolerance);
}

TEST(ShapeCast, CompoundCastAndTarget) {
    // A compound of two 0.25 m spheres at y = +-1 of its frame, cast along +x from the
    // origin, against a static compound whose only child on its path is a cube of face
    // x = 3 spanning y in [0.5, 1.5]: the upper sphere touches it at centre x = 2.75.
    World world;
    CompoundChild upper, lower, cube, post;
    upper.shape = lower.shape = Shape::sphere(0.25);
    upper.position = Vector3(0, 1, 0);
    lower.position = Vector3(0, -1, 0);
    cube.shape = Shape::box({0.5, 0.5, 0.5});
    cube.position = Vector3(3.5, 1, 0);
    post.shape = Shape::box({0.5, 0.5, 0.5});
    post.position = Vector3(3.5, 1, 5);
    const BodyId target = addStatic(world, Shape::compound({post, cube}), Vector3::Zero());
    const auto hit =
        world.shapeCast(Shape::compound({upper, lower}), Vector3::Zero(), Quaternion::Identity(), Vector3(10, 0, 0));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, target);
    EXPECT_NEAR(hit->distance, 2.75, kTolerance);
    EXPECT_NEAR((hit->point - Vector3(3, 1, 0)).norm(), 0, kTolerance);
}

TEST(ShapeCast, BadInputIsRefused) {
    World world;
    const auto field = [&](const Shape &shape, const Vector3 &translation) -> std::string {
        try {
            world.shapeCast(shape, Vector3::Zero(), Quaternion::Identity(), translation);
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "World::shapeCast");
            return e.field();
        }
        return "";
    };
    EXPECT_EQ(field(Shape::sphere(1), Vector3::Zero()), "translation");
    EXPECT_EQ(field(Shape::sphere(1), Vector3(std::nan(""), 0, 0)), "translation");
    EXPECT_EQ(field(Shape::plane(Vector3::UnitY(), 0), Vector3::UnitX()), "shape.type");
    EXPECT_EQ(field(Shape::sphere(0), Vector3::UnitX()), "shape.radius");
    EXPECT_EQ(field(Shape::compound({}), Vector3::UnitX()), "shape.children");
}

}  // namespace
}  // namespace cyclone::test
