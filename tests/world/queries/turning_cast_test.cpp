// World::shapeCast with an end orientation: shapes that turn as they move, against
// boxes, meshes, planes and height fields, with contact angles worked out in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "world_fixture.h"

namespace cyclone::test::turning_cast {
namespace {

// The cast leaves the shapes apart by at most 0.1 mm (World::shapeCast).
constexpr real kTolerance = 1e-4;

Quaternion turn(real angle, const Vector3 &axis) { return Quaternion(Eigen::AngleAxis<real>(angle, axis.normalized())); }

// A thin box, half sizes w = 0.05 (x), 0.5 (y), h = 1 (z), centred at the origin, turns
// 90 degrees about +y, which takes its +z end towards +x: after a turn theta its corner
// (w, y, h) lies at x = w cos(theta) + h sin(theta). A wall whose face is x = d = 0.6
// meets it when sqrt(h^2 + w^2) sin(theta + atan(w / h)) = d:
//   theta = asin(d / sqrt(h^2 + w^2)) - atan(w / h) = 0.592589 rad,
// at the corner (d, y, h cos(theta) - w sin(theta)). The turn is at a constant rate, so
// the fraction is theta / (pi / 2). The corner closes on the wall at (h cos(theta) - w
// sin(theta)) per rad, so the 0.1 mm gap the cast may leave is that many rad early.
constexpr real kW = 0.05, kH = 1, kD = 0.6;
const real kWallAngle = std::asin(kD / std::hypot(kH, kW)) - std::atan(kW / kH);
const real kWallRate = kH * std::cos(kWallAngle) - kW * std::sin(kWallAngle);

void expectWallHit(const std::optional<ShapeCastHit> &hit, BodyId wall) {
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, wall);
    const real exact = kWallAngle / (kPi / 2);
    EXPECT_LE(hit->fraction, exact);
    EXPECT_GE(hit->fraction, exact - kTolerance / kWallRate / (kPi / 2));
    EXPECT_EQ(hit->distance, 0);  // a turn in place
    EXPECT_NEAR(hit->point.x(), kD, kTolerance);
    EXPECT_NEAR(hit->point.z(), kH * std::cos(kWallAngle) - kW * std::sin(kWallAngle), 1e-3);
    EXPECT_NEAR((hit->normal - Vector3(-1, 0, 0)).norm(), 0, 1e-6);
}

TEST(TurningCast, ThinBoxTurnsIntoAWall) {
    World world;
    const BodyId wall = addStatic(world, Shape::box({0.5, 2, 3}), {kD + 0.5, 0, 0});
    const auto hit = world.shapeCast(Shape::box({kW, 0.5, kH}), Vector3::Zero(), Quaternion::Identity(),
                                     Vector3::Zero(), turn(kPi / 2, Vector3::UnitY()));
    expectWallHit(hit, wall);
}

TEST(TurningCast, ThinBoxTurnsIntoAMeshWall) {
    // The same wall's face as a mesh of two triangles (x = d, |y| <= 2, |z| <= 3).
    World world;
    const Shape quad = Shape::mesh({{kD, -2, -3}, {kD, 2, -3}, {kD, 2, 3}, {kD, -2, 3}}, {{{0, 1, 2}}, {{0, 2, 3}}});
    const BodyId wall = addStatic(world, quad, Vector3::Zero());
    const auto hit = world.shapeCast(Shape::box({kW, 0.5, kH}), Vector3::Zero(), Quaternion::Identity(),
                                     Vector3::Zero(), turn(kPi / 2, Vector3::UnitY()));
    expectWallHit(hit, wall);
}

TEST(TurningCast, ACompoundTurnsAboutItsFrameOrigin) {
    // The thin box as the only child of a compound, its frame's origin at the box's
    // centre: the same turn, the same hit.
    World world;
    const BodyId wall = addStatic(world, Shape::box({0.5, 2, 3}), {kD + 0.5, 0, 0});
    CompoundChild child;
    child.shape = Shape::box({kW, 0.5, kH});
    const auto hit = world.shapeCast(Shape::compound({child}), Vector3::Zero(), Quaternion::Identity(),
                                     Vector3::Zero(), turn(kPi / 2, Vector3::UnitY()));
    expectWallHit(hit, wall);
}

TEST(TurningCast, ADoorSwingsAboutItsHingeIntoAStop) {
    // A door: a compound whose one child, half sizes 0.5 (x), 1 (y), 0.05 (z), lies at
    // (0.5, 0, 0) from its frame's origin, the hinge. Turned about +y, its direction in
    // (x, z) is u = (cos(theta), -sin(theta)) and its leading side the line at 0.05 along
    // v = (-sin(theta), -cos(theta)). A stop, half sizes 0.1, 1, 0.1, centred at (0.7, 0,
    // -0.5): its corner (0.8, -0.4), at r = sqrt(0.8) and angle beta = atan2(0.4, 0.8)
    // below the x axis, meets that side when r sin(beta - theta) = 0.05,
    //   theta = beta - asin(0.05 / r) = 0.407717 rad,
    // before any other point of the stop (the rest lie at larger angles beta), and within
    // the door's length (r cos(beta - theta) = 0.893 < 1); it closes at 0.893 m per rad.
    World world;
    const BodyId stop = addStatic(world, Shape::box({0.1, 1, 0.1}), {0.7, 0, -0.5});
    CompoundChild leaf;
    leaf.shape = Shape::box({0.5, 1, 0.05});
    leaf.position = Vector3(0.5, 0, 0);
    const auto hit = world.shapeCast(Shape::compound({leaf}), Vector3::Zero(), Quaternion::Identity(),
                                     Vector3::Zero(), turn(kPi / 2, Vector3::UnitY()));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, stop);
    const real r = std::sqrt(0.8);
    const real theta = std::atan2(0.4, 0.8) - std::asin(0.05 / r);
    const real exact = theta / (kPi / 2);
    EXPECT_LE(hit->fraction, exact);
    EXPECT_GE(hit->fraction, exact - kTolerance / (r * std::cos(std::atan2(0.4, 0.8) - theta)) / (kPi / 2));
    // One of the door's points on its leading side.
    EXPECT_NEAR(hit->point.dot(Vector3(-std::sin(theta), 0, -std::cos(theta))), 0.05, 1e-3);
}

// A bar, half sizes 1 (x), 0.1 (y), 0.1 (z), centred 0.5 m above the ground, turns 90
// degrees about +z: a point (x, y) goes to height x sin(theta) + y cos(theta), so its
// lowest corner (-1, -0.1) is at 0.5 - sin(theta) - 0.1 cos(theta), which is zero when
//   sqrt(1.01) sin(theta + atan(0.1)) = 0.5, theta = asin(0.5 / sqrt(1.01)) - atan(0.1)
// = 0.421063 rad; the corner then sinks at cos(theta) - 0.1 sin(theta) per rad.
void expectGroundHit(const World &world, BodyId ground) {
    const auto hit = world.shapeCast(Shape::box({1, 0.1, 0.1}), Vector3(0, 0.5, 0), Quaternion::Identity(),
                                     Vector3::Zero(), turn(kPi / 2, Vector3::UnitZ()));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, ground);
    const real theta = std::asin(0.5 / std::sqrt(1.01)) - std::atan(0.1);
    const real rate = std::cos(theta) - 0.1 * std::sin(theta);
    const real exact = theta / (kPi / 2);
    EXPECT_LE(hit->fraction, exact);
    EXPECT_GE(hit->fraction, exact - kTolerance / rate / (kPi / 2));
    EXPECT_NEAR(hit->point.y(), 0, kTolerance);
    EXPECT_NEAR(hit->point.x(), -std::cos(theta) + 0.1 * std::sin(theta), 1e-3);
    EXPECT_NEAR((hit->normal - Vector3::UnitY()).norm(), 0, 1e-6);
}

TEST(TurningCast, BarTipsOntoAPlane) {
    World world;
    expectGroundHit(world, addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero()));
}

TEST(TurningCast, BarTipsOntoAFlatHeightfield) {
    // A flat 5 x 5 field at height 0 spanning x, z in [-2, 2]: the ground of the plane test.
    World world;
    const Shape field = Shape::heightfield(5, 5, {1, 1}, std::vector<real>(25, 0));
    expectGroundHit(world, addStatic(world, field, Vector3(-2, 0, -2)));
}

TEST(TurningCast, RodTurnsIntoAPostItWouldMissGoingStraight) {
    // A rod, half sizes 1 (x), 0.05 (y, z), at the origin; a post, half sizes 0.1, 1, 0.1,
    // centred at (0, 0, 0.7). Moved 0.3 m along +z without turning, the rod's side reaches
    // z = 0.35 < 0.6: no hit. Turned 90 degrees about -y, its direction is (cos(theta), 0,
    // sin(theta)) and its leading side is the line at 0.05 along v = (-sin(theta), 0,
    // cos(theta)). The post's corner (0.1, 0.6) in (x, z), at r = sqrt(0.37) and polar
    // angle beta = atan2(0.6, 0.1), is the first point of it that side reaches (the other
    // corners lie at larger polar angles and radii): r sin(beta - theta) = 0.05,
    //   theta = beta - asin(0.05 / r) = 1.323356 rad,
    // closing at its distance along the rod, 0.1 cos(theta) + 0.6 sin(theta), per rad.
    World world;
    const BodyId post = addStatic(world, Shape::box({0.1, 1, 0.1}), {0, 0, 0.7});
    const Shape rod = Shape::box({1, 0.05, 0.05});
    EXPECT_FALSE(world.shapeCast(rod, Vector3::Zero(), Quaternion::Identity(), Vector3(0, 0, 0.3)));
    const auto hit =
        world.shapeCast(rod, Vector3::Zero(), Quaternion::Identity(), Vector3::Zero(), turn(kPi / 2, -Vector3::UnitY()));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, post);
    const real r = std::sqrt(0.37);
    const real theta = std::atan2(0.6, 0.1) - std::asin(0.05 / r);
    const real rate = 0.1 * std::cos(theta) + 0.6 * std::sin(theta);
    const real exact = theta / (kPi / 2);
    EXPECT_LE(hit->fraction, exact);
    EXPECT_GE(hit->fraction, exact - kTolerance / rate / (kPi / 2));
    // The point is one of the rod's points on its leading side (a face touches an edge).
    EXPECT_NEAR(hit->point.dot(Vector3(-std::sin(theta), 0, std::cos(theta))), 0.05, 1e-3);
}

TEST(TurningCast, ATurningSphereIsTheStraightCast) {
    // A sphere turning about its centre covers the same space: 0.5 m sphere along +x by
    // 10 m, turning 90 degrees about z, meets the face x = 4 of a cube centred at x = 5
    // when its centre reaches 3.5 m, as without the turn (ShapeCast.SphereAgainstBoxFace).
    World world;
    addStatic(world, Shape::box({1, 1, 1}), {5, 0, 0});
    const Shape ball = Shape::sphere(0.5);
    const Vector3 along(10, 0, 0);
    const auto straight = world.shapeCast(ball, Vector3::Zero(), Quaternion::Identity(), along);
    const auto turning =
        world.shapeCast(ball, Vector3::Zero(), Quaternion::Identity(), along, turn(kPi / 2, Vector3::UnitZ()));
    ASSERT_TRUE(straight && turning);
    EXPECT_EQ(turning->body, straight->body);
    EXPECT_LE(turning->distance, 3.5);
    EXPECT_GE(turning->distance, 3.5 - kTolerance);
    EXPECT_NEAR((turning->point - straight->point).norm(), 0, kTolerance);
    EXPECT_NEAR((turning->normal - straight->normal).norm(), 0, 1e-9);
}

TEST(TurningCast, NoTurnIsTheStraightCast) {
    // Equal orientations: the straight cast's answer, field for field; a turn of 1e-9 rad
    // moves no point by more than 1e-9 m, so it answers within the tolerance.
    World world;
    addStatic(world, Shape::box({1, 1, 1}), {5, 0.3, 0});
    addStatic(world, Shape::plane(Vector3::UnitY(), -2), Vector3::Zero());
    const Quaternion tilted = turn(0.4, Vector3(1, 2, 3));
    const Shape box = Shape::box({0.3, 0.2, 0.5});
    for (const Vector3 &translation : {Vector3(10, 0, 0), Vector3(0, -5, 0)}) {
        const auto straight = world.shapeCast(box, Vector3::Zero(), tilted, translation);
        const auto same = world.shapeCast(box, Vector3::Zero(), tilted, translation, tilted);
        ASSERT_TRUE(straight && same);
        EXPECT_EQ(same->body, straight->body);
        EXPECT_EQ(same->fraction, straight->fraction);
        EXPECT_EQ(same->point, straight->point);
        EXPECT_EQ(same->normal, straight->normal);
        const auto tiny = world.shapeCast(box, Vector3::Zero(), tilted, translation, turn(1e-9, Vector3::UnitX()) * tilted);
        ASSERT_TRUE(tiny);
        EXPECT_EQ(tiny->body, straight->body);
        EXPECT_NEAR(tiny->distance, straight->distance, kTolerance);
        EXPECT_NEAR((tiny->normal - straight->normal).norm(), 0, 1e-3);
    }
}

TEST(TurningCast, FiltersAndUserDataAsTheStraightCast) {
    World world;
    BodySettings settings;
    settings.motion = Motion::Static;
    settings.shape = Shape::box({0.5, 2, 3});
    settings.position = Vector3(kD + 0.5, 0, 0);
    settings.layer = 3;
    settings.userData = 77;
    const BodyId wall = world.addBody(settings);
    const Shape thin = Shape::box({kW, 0.5, kH});
    const Quaternion quarter = turn(kPi / 2, Vector3::UnitY());
    const auto hit = world.shapeCast(thin, Vector3::Zero(), Quaternion::Identity(), Vector3::Zero(), quarter);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->userData, 77u);
    QueryFilter filter;
    filter.ignore = wall;
    EXPECT_FALSE(world.shapeCast(thin, Vector3::Zero(), Quaternion::Identity(), Vector3::Zero(), quarter, filter));
    filter = QueryFilter();
    filter.layers = ~(1u << 3);
    EXPECT_FALSE(world.shapeCast(thin, Vector3::Zero(), Quaternion::Identity(), Vector3::Zero(), quarter, filter));
    filter = QueryFilter();
    filter.staticBodies = false;
    EXPECT_FALSE(world.shapeCast(thin, Vector3::Zero(), Quaternion::Identity(), Vector3::Zero(), quarter, filter));
    // Turning about x keeps every point at x <= w = 0.05, short of the wall.
    EXPECT_FALSE(world.shapeCast(thin, Vector3::Zero(), Quaternion::Identity(), Vector3::Zero(),
                                 turn(kPi / 2, Vector3::UnitX())));
}

// Runs `call`, which must throw InvalidArgument from World::shapeCast about `field` with
// `shown` in its message.
template <typename Call>
void expectRefusal(Call call, const std::string &field, const std::string &shown) {
    try {
        call();
        FAIL() << "accepted a bad " << field;
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::shapeCast") << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(e.problem().find(shown), std::string::npos) << e.what();
    }
}

TEST(TurningCast, BadInputIsRefused) {
    World world;
    const Shape box = Shape::box({0.5, 0.5, 0.5});
    const Quaternion none = Quaternion::Identity();
    const Quaternion quarter = turn(kPi / 2, Vector3::UnitY());
    const Vector3 zero = Vector3::Zero();
    expectRefusal([&] { world.shapeCast(box, zero, Quaternion(2, 0, 0, 0), zero, quarter); }, "orientation",
                  "[2, 0, 0, 0]");
    expectRefusal([&] { world.shapeCast(box, zero, none, zero, Quaternion(0, 0, 0, 0)); }, "endOrientation",
                  "[0, 0, 0, 0]");
    expectRefusal([&] { world.shapeCast(box, zero, none, zero, Quaternion(kNaN, 0, 0, 0)); }, "endOrientation",
                  "nan");
    expectRefusal([&] { world.shapeCast(box, zero, none, Vector3(kInf, 0, 0), quarter); }, "translation", "inf");
    expectRefusal([&] { world.shapeCast(box, Vector3(kNaN, 0, 0), none, zero, quarter); }, "position", "nan");
    // Neither moved nor turned.
    expectRefusal([&] { world.shapeCast(box, zero, none, zero, none); }, "translation", "[0, 0, 0]");
    expectRefusal([&] { world.shapeCast(Shape::plane(Vector3::UnitY(), 0), zero, none, zero, quarter); },
                  "shape.type", "plane");
    expectRefusal([&] { world.shapeCast(Shape::sphere(-1), zero, none, zero, quarter); }, "shape.radius", "-1");
}

}  // namespace
}  // namespace cyclone::test::turning_cast
