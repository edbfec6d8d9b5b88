// Height fields in a World: bodies roll and slide across cells and diagonals without
// bumps, slide down a slope at the closed-form acceleration, rest and sleep; rays, shape
// casts and overlaps meet the surface where geometry puts it; bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "floor_crossing.h"
#include "world_fixture.h"

namespace cyclone::test::heightfield_world {
namespace {

// rows x columns samples `spacing` apart, of height h(x, z) (x, z in the field's frame).
template <class Height>
Shape field(int rows, int columns, real spacing, Height h) {
    std::vector<real> heights;
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < columns; ++j) heights.push_back(h(j * spacing, i * spacing));
    return Shape::heightfield(rows, columns, {spacing, spacing}, heights);
}

// A flat 20 m x 20 m field at y = 0 of 1 m cells, centred on the origin when placed at
// kFlatCorner.
Shape flatShape() { return field(21, 21, 1.0, [](real, real) { return real(0); }); }
const Vector3 kFlatCorner(-10, 0, -10);

BodyId flatField(World &world, real friction = 0.6) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = flatShape();
    s.position = kFlatCorner;
    s.material.friction = friction;
    return world.addBody(s);
}

struct Track {
    real heightError = 0;    // largest |y - rest|, m
    real verticalSpeed = 0;  // largest |vy| from the 16th step on, m/s
    real travelled = 0;      // m
};

// `shape` (turned by `orientation`) started at rest height `rest` with `velocity` across
// the flat field, rolling without slipping when `roll`, for 6 s (floor_crossing.h).
Track cross(const Shape &shape, const Quaternion &orientation, real rest, const Vector3 &velocity, bool roll,
            real friction) {
    const FloorTrack t = crossFloor(flatShape(), shape, orientation, rest, velocity, roll, friction, 6.0, kFlatCorner);
    return {heightError(t, rest), verticalSpeed(t, 15), t.travelled};
}

TEST(Heightfield, BallRollsAcrossCellsAndDiagonalsWithoutBumps) {
    // At 1.08 m/s along (1, 0.4) for 6 s the ball crosses some 6 cell edges along x, 2
    // along z and 4 diagonals (x = z within a cell), all inner edges of a flat surface:
    // its centre stays at its radius, 0.25 m. Bounds of the issue: 1 mm, 0.01 m/s.
    const Track t = cross(Shape::sphere(0.25), Quaternion::Identity(), 0.25, Vector3(1.0, 0, 0.4), true, 0.6);
    EXPECT_LE(t.heightError, 0.001);
    EXPECT_LE(t.verticalSpeed, 0.01);
    EXPECT_GT(t.travelled, 5) << "1.08 m/s for 6 s, less what rolling resistance takes";
}

TEST(Heightfield, BoxCapsuleAndCylinderSlideAcrossCellsWithoutBumps) {
    // Sliding at 4 m/s with friction 0.1 they stop after v^2 / (2 mu g) = 8.1 m, over some
    // 20 inner edges; each keeps its rest height: the box's half height 0.5, the capsule's
    // and the cylinder's radius (lying along their path, local z turned onto v).
    const Vector3 v(3.6, 0, 1.7);
    const Quaternion alongPath(Eigen::AngleAxis<real>(std::atan2(v.x(), v.z()), Vector3::UnitY()));
    struct Case {
        const char *name;
        Shape shape;
        Quaternion orientation;
        real rest;
    };
    // The cylinder lies on its side: local z along the path, turned about it so that its
    // round side is down (any turn about its axis does).
    const Case cases[] = {{"box", Shape::box(Vector3(0.5, 0.5, 0.5)), Quaternion::Identity(), 0.5},
                          {"capsule", Shape::capsule(0.2, 0.6), alongPath, 0.2},
                          {"cylinder", Shape::cylinder(0.3, 0.8), alongPath, 0.3}};
    for (const Case &c : cases) {
        SCOPED_TRACE(c.name);
        const Track t = cross(c.shape, c.orientation, c.rest, v, false, 0.1);
        EXPECT_LE(t.heightError, 0.001);
        EXPECT_LE(t.verticalSpeed, 0.01);
        EXPECT_GT(t.travelled, 7);
    }
}

TEST(Heightfield, BoxSlidesDownASlopeAtTheClosedFormAcceleration) {
    // The field y = -tan(theta) x, theta = 20 deg, in 0.5 m cells; a box of friction 0.2
    // on it (the field's 0.2 too, so the pair's is 0.2 whatever the mixing) slides down
    // at a = g (sin theta - mu cos theta) = 9.81 (0.34202 - 0.2 x 0.93969) = 1.5115 m/s^2.
    // Measured from the velocity along the slope between 0.5 s and 1.5 s; bound 5 %.
    const real theta = 20 * kPi / 180, mu = 0.2;
    WorldFixture f(noSleep());
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = field(11, 41, 0.5, [&](real x, real) { return -std::tan(theta) * x; });
    ground.position = Vector3(0, 0, -2.5);
    ground.material.friction = mu;
    f.world.addBody(ground);
    // Its bottom face on the slope: turned by -theta about z (local y onto the surface
    // normal (sin, cos, 0)), its centre 0.25 m along the normal from x = 2 on the surface.
    const Vector3 normal(std::sin(theta), std::cos(theta), 0);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.25, 0.25, 0.25));
    s.orientation = Quaternion(Eigen::AngleAxis<real>(-theta, Vector3::UnitZ()));
    s.position = Vector3(2, -2 * std::tan(theta), 0.3) + 0.25 * normal;
    s.mass = 1;
    s.material.friction = mu;
    const BodyId box = f.world.addBody(s);
    const Vector3 downSlope(std::cos(theta), -std::sin(theta), 0);
    f.simulate(0.5);
    const real v0 = f.world.body(box).getVelocity().dot(downSlope);
    f.simulate(1.0);
    const real v1 = f.world.body(box).getVelocity().dot(downSlope);
    const real expected = kG * (std::sin(theta) - mu * std::cos(theta));
    EXPECT_NEAR(v1 - v0, expected, 0.05 * expected);
    // Still on the slope: its centre 0.25 m above the surface along the normal.
    const Vector3 p = f.position(box);
    EXPECT_NEAR((p - Vector3(0, 0, p.z())).dot(normal), 0.25, 0.001);
}

TEST(Heightfield, BoxRestingOnAFieldSleeps) {
    // A box put down on a flat field comes to rest and falls asleep (the World's sleep
    // takes 0.5 s of rest by default); 3 s is ample.
    WorldFixture f;
    flatField(f.world);
    const BodyId box = f.box(Vector3(0.3, 0.5, 0.7), Vector3(0.5, 0.5, 0.5));
    f.simulate(3.0);
    EXPECT_FALSE(f.world.body(box).getAwake());
    EXPECT_NEAR(f.position(box).y(), 0.5, 0.001);
}

TEST(Heightfield, HullAndCompoundComeToRestOnTheSurface) {
    // Dropped from 0.2 m above their rest onto the flat field at y = 0, each settles with
    // its lowest face on the surface: the hull, a cube of half size 0.3 given by its
    // corners, at y = 0.3; the compound, two boxes of half size 0.2 side by side along x
    // (children at x = -0.2 and 0.2, the frame between them), at y = 0.2.
    WorldFixture f;
    flatField(f.world);
    std::vector<Vector3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.3 : -0.3, i & 2 ? 0.3 : -0.3, i & 4 ? 0.3 : -0.3);
    CompoundChild left, right;
    left.shape = right.shape = Shape::box(Vector3(0.2, 0.2, 0.2));
    left.position = Vector3(-0.2, 0, 0);
    right.position = Vector3(0.2, 0, 0);
    BodySettings hull, compound;
    hull.shape = Shape::convex(corners);
    hull.position = Vector3(-2.3, 0.5, 1.4);
    hull.mass = 1;
    compound.shape = Shape::compound({left, right});
    compound.position = Vector3(2.6, 0.4, -1.7);
    compound.mass = 1;
    const BodyId h = f.world.addBody(hull);
    const BodyId c = f.world.addBody(compound);
    f.simulate(2.0);
    EXPECT_NEAR(f.position(h).y(), 0.3, 0.001);
    EXPECT_NEAR(f.world.framePosition(c).y(), 0.2, 0.001);
}

TEST(Heightfield, RayHitsTheAnalyticPoint) {
    // Heights, rows i (z) by columns j (x), spacing 1, placed at (5, 1, -3):
    //   0 1 0
    //   2 0 1
    //   0 0 3
    // Cell (0, 0)'s triangle (0,0)-(1,0)-(1,1) holds the field points with z >= x: its
    // corners (x, y, z) = (0, 0, 0), (0, 2, 1), (1, 0, 1) span the plane y = -2x + 2z,
    // whose upward unit normal is (2, 1, -2) / 3. A ray straight down at field (0.25,
    // 0.75) meets it at y = -0.5 + 1.5 = 1, so world (5.25, 2, -2.25), 8 m below (5.25,
    // 10, -2.25).
    WorldFixture f;
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = Shape::heightfield(3, 3, {1, 1}, {0, 1, 0, 2, 0, 1, 0, 0, 3});
    s.position = Vector3(5, 1, -3);
    const BodyId ground = f.world.addBody(s);
    const auto hit = f.world.rayCast(Vector3(5.25, 10, -2.25), -Vector3::UnitY());
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->body, ground);
    EXPECT_NEAR(hit->distance, 8, 1e-12);
    EXPECT_LT((hit->point - Vector3(5.25, 2, -2.25)).norm(), 1e-12);
    EXPECT_LT((hit->normal - Vector3(2, 1, -2) / 3).norm(), 1e-12);
    // From below the surface the ray meets the solid's inside: no hit (solid below).
    EXPECT_FALSE(f.world.rayCast(Vector3(5.25, 1.5, -2.25), Vector3::UnitY(), 5).has_value());
}

TEST(Heightfield, SlantedRayWalksManyCellsToTheAnalyticPoint) {
    // A flat field at y = 0 (from (-10, 0, -10)); a ray from (1.3, 5, 2.7) along
    // (3, -1, 2) / sqrt(14) reaches y = 0 after 5 sqrt(14) m, at (16.3, 0, 12.7)... beyond
    // the field (x <= 10): no hit. Along (1, -1, 2) / sqrt(6) it reaches y = 0 after
    // 5 sqrt(6) m at (6.3, 0, 12.7), beyond z = 10: no hit either. Along (1, -1, 0.4) /
    // sqrt(2.16) at (6.3, 0, 4.7), over 5 cells along x: a hit there, normal up.
    WorldFixture f;
    flatField(f.world);
    const Vector3 origin(1.3, 5, 2.7);
    EXPECT_FALSE(f.world.rayCast(origin, Vector3(3, -1, 2).normalized()).has_value());
    EXPECT_FALSE(f.world.rayCast(origin, Vector3(1, -1, 2).normalized()).has_value());
    const auto hit = f.world.rayCast(origin, Vector3(1, -1, 0.4).normalized());
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance, 5 * std::sqrt(2.16), 1e-9);
    EXPECT_LT((hit->point - Vector3(6.3, 0, 4.7)).norm(), 1e-9);
    EXPECT_LT((hit->normal - Vector3::UnitY()).norm(), 1e-12);
}

TEST(Heightfield, ShapeCastAndOverlapMeetTheSurface) {
    // A sphere of radius 0.5 cast down from y = 3 over the flat field touches it when its
    // centre is at 0.5: after 2.5 m of a 5 m cast, fraction 0.5 (within the cast's 1e-4 m
    // tolerance), normal up (within the GJK normal's noise, 1e-3 rad, shape_cast.cpp: the
    // sphere comes down on a cell's diagonal).
    WorldFixture f;
    const BodyId ground = flatField(f.world);
    const auto cast = f.world.shapeCast(Shape::sphere(0.5), Vector3(1.5, 3, -0.5), Quaternion::Identity(),
                                        Vector3(0, -5, 0));
    ASSERT_TRUE(cast.has_value());
    EXPECT_EQ(cast->body, ground);
    EXPECT_NEAR(cast->fraction, 0.5, 1e-4 / 5);
    EXPECT_LT((cast->normal - Vector3::UnitY()).norm(), 1e-3);
    // A box dipping 1 cm into the surface overlaps it; 1 cm above, it does not.
    std::vector<BodyId> found;
    f.world.overlap(Shape::box(Vector3(0.3, 0.3, 0.3)), Vector3(2.2, 0.29, 3.1), Quaternion::Identity(), found);
    EXPECT_EQ(found, std::vector<BodyId>{ground});
    f.world.overlap(Shape::box(Vector3(0.3, 0.3, 0.3)), Vector3(2.2, 0.31, 3.1), Quaternion::Identity(), found);
    EXPECT_TRUE(found.empty());
}

TEST(Heightfield, SensorSeesABodyOnItsSurface) {
    // A dynamic sensor ball dropped onto the field passes into it (a sensor has no
    // contacts) and reports the field once it reaches the surface: from 1 m up at radius
    // 0.25 it falls 0.75 m in sqrt(2 x 0.75 / g) = 0.39 s, so within 1 s.
    WorldFixture f;
    const BodyId ground = flatField(f.world);
    BodySettings s;
    s.shape = Shape::sphere(0.25);
    s.position = Vector3(0.4, 1, 0.6);
    s.sensor = true;
    s.mass = 1;
    const BodyId sensor = f.world.addBody(s);
    bool seen = false;
    for (int i = 0; i < 60 && !seen; ++i) {
        f.world.step(kDt);
        for (const SensorEvent &e : f.world.events().sensorBegins)
            if (e.sensor == sensor && e.body == ground) seen = true;
    }
    EXPECT_TRUE(seen);
}

TEST(Heightfield, BadInputIsRefusedAndChangesNothing) {
    WorldFixture f;
    const auto refused = [&](const Shape &shape, const std::string &field, const std::string &shown, bool isStatic) {
        SCOPED_TRACE(field);
        BodySettings s;
        s.motion = isStatic ? Motion::Static : Motion::Dynamic;
        s.shape = shape;
        try {
            f.world.addBody(s);
            ADD_FAILURE() << "accepted";
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "World::addBody") << e.what();
            EXPECT_EQ(e.field(), field) << e.what();
            EXPECT_NE(e.problem().find(shown), std::string::npos) << e.what();
        }
        EXPECT_EQ(f.world.bodyCount(), 0u);
    };
    const std::vector<real> four = {0, 0, 0, 0};
    refused(Shape::heightfield(1, 4, {1, 1}, four), "shape.rows", "got 1", true);
    refused(Shape::heightfield(2, 0, {1, 1}, four), "shape.columns", "got 0", true);
    refused(Shape::heightfield(2, 2, {0, 1}, four), "shape.spacing[0]", "got 0", true);
    refused(Shape::heightfield(2, 2, {1, -2}, four), "shape.spacing[1]", "got -2", true);
    refused(Shape::heightfield(2, 2, {1, kNaN}, four), "shape.spacing[1]", "got nan", true);
    refused(Shape::heightfield(2, 3, {1, 1}, four), "shape.heights", "got 4", true);
    refused(Shape::heightfield(2, 2, {1, 1}, {0, 0, kInf, 0}), "shape.heights[2]", "got inf", true);
    refused(Shape::heightfield(2, 2, {1, 1}, four), "shape.type", "\"heightfield\" is for static bodies only", false);
}

}  // namespace
}  // namespace cyclone::test::heightfield_world
