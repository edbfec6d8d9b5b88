// A body dropped nearly lying, tilted onto one end, lands on a vertex, an edge, an end's
// sphere or a rim point and turns about it; its other end then comes down within the step
// faster than the body fell (collision/manifold_clipping.cpp, planeContact). From 2-6 m
// (6.3-10.8 m/s, 10-18 cm a step at 60 Hz) the other end went 25-71 mm into the ground
// when the manifold held only the points near the first one: the other end needs its own
// point, a gap that the contact lets close, before it arrives.
//
// The bound: the speculative contact acts in the step of the impact, letting the gap
// close and no more; what gravity adds within that step, g dt^2 = 9.81 / 60^2 = 2.7 mm,
// plus the slop (0.2 mm) is the most that should remain, within the drop tests' 5 mm
// (speculative_contact_test.cpp).
#include <algorithm>
#include <cmath>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr real kLandingDeepest = 0.005;
constexpr real kRadius = 0.2;
constexpr real kLength = 1.0;

// How far the lowest point of `shape` lies below its centre when its orientation is `turn`:
// a box's or hull's lowest corner; a capsule's or cylinder's (core kLength along local z,
// radius kRadius) lower end, half the core's vertical extent below, plus the radius (the
// end sphere's bottom) or the radius across the axis, r sqrt(1 - axisY^2) (the rim).
real lowestBelowCentre(const Shape &shape, const Matrix3 &turn) {
    std::vector<Vector3> corners = shape.vertices;
    if (shape.type == ShapeType::Box)
        for (int c = 0; c < 8; ++c)
            corners.emplace_back(c & 1 ? shape.halfExtents.x() : -shape.halfExtents.x(),
                                 c & 2 ? shape.halfExtents.y() : -shape.halfExtents.y(),
                                 c & 4 ? shape.halfExtents.z() : -shape.halfExtents.z());
    if (!corners.empty()) {
        real lowest = 0;
        for (const Vector3 &v : corners) lowest = std::max(lowest, -(turn * v).y());
        return lowest;
    }
    const real axisY = turn.col(2).y();
    const real across = shape.type == ShapeType::Capsule ? kRadius : kRadius * std::sqrt(1 - axisY * axisY);
    return std::abs(axisY) * kLength / 2 + across;
}

// A body of `shape` turned by `turn`, its lowest point `height` above the ground.
BodyId droppedBody(WorldFixture &f, const Shape &shape, const Quaternion &turn, real height) {
    BodySettings s;
    s.shape = shape;
    s.mass = 1;
    s.orientation = turn;
    s.position = Vector3(0, height + lowestBelowCentre(shape, turn.toRotationMatrix()), 0);
    return f.world.addBody(s);
}

// A capsule's or cylinder's axis (local z) turned onto x, then tilted `tilt` towards y.
Quaternion lyingTilted(real tilt) {
    return Quaternion(Eigen::AngleAxis<real>(tilt, Vector3::UnitZ())) *
           Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
}

// How far the lowest point of body `id` (of `shape`) lies below the ground, y = 0.
real belowGround(const WorldFixture &f, BodyId id, const Shape &shape) {
    const RigidBody &b = f.world.body(id);
    return lowestBelowCentre(shape, b.getTransform().linear()) - b.getPosition().y();
}

// Steps 4 s and returns how far the body's lowest point went below the ground.
real deepestBelowGround(WorldFixture &f, BodyId id, const Shape &shape) {
    real deepest = 0;
    for (int i = 0; i < 240; ++i) {
        f.world.step(kDt);
        deepest = std::max(deepest, belowGround(f, id, shape));
    }
    return deepest;
}

TEST(TiltedLanding, CapsuleLandsOnBothEnds) {
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::capsule(kRadius, kLength);
    const BodyId capsule = droppedBody(f, shape, lyingTilted(kPi / 12), 6);
    EXPECT_LE(deepestBelowGround(f, capsule, shape), kLandingDeepest);
    // It ends lying on its side: its core the radius above the ground.
    EXPECT_NEAR(f.position(capsule).y(), kRadius, kLandingDeepest);
}

TEST(TiltedLanding, CylinderLandsOnBothRims) {
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::cylinder(kRadius, kLength);
    const BodyId cylinder = droppedBody(f, shape, lyingTilted(kPi / 36), 6);
    EXPECT_LE(deepestBelowGround(f, cylinder, shape), kLandingDeepest);
    EXPECT_NEAR(f.position(cylinder).y(), kRadius, kLandingDeepest);
}

TEST(TiltedLanding, SteepCylinderLandsOnItsRim) {
    // Tilted 60 degrees up: it lands on its rim, far from the side line's other end, and
    // tips over onto its side or onto its cap. Either way it ends resting on the ground:
    // its centre the radius up (on its side) or half its length up (on its cap).
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::cylinder(kRadius, kLength);
    const BodyId cylinder = droppedBody(f, shape, lyingTilted(kPi / 3), 3);
    EXPECT_LE(deepestBelowGround(f, cylinder, shape), kLandingDeepest);
    const real y = f.position(cylinder).y();
    EXPECT_LE(std::min(std::abs(y - kRadius), std::abs(y - kLength / 2)), kLandingDeepest) << y;
}

TEST(TiltedLanding, PlankLandsOnBothEnds) {
    // A 1 x 0.2 x 0.2 plank tilted 5 degrees about z from 2 m (6.3 m/s, 105 mm a step):
    // its far edge lies 1 sin 5 deg = 87 mm above the near one, farther than the near
    // edge's gap and the step's fall leave when the near edge lands.
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::box(Vector3(0.5, 0.1, 0.1));
    const BodyId plank = droppedBody(f, shape, Quaternion(Eigen::AngleAxis<real>(kPi / 36, Vector3::UnitZ())), 2);
    EXPECT_LE(deepestBelowGround(f, plank, shape), kLandingDeepest);
    // It ends lying on a long face: its centre half its height up.
    EXPECT_NEAR(f.position(plank).y(), 0.1, kLandingDeepest);
}

TEST(TiltedLanding, BoxLandsOnACorner) {
    // A 1.2 x 0.2 x 0.4 box turned 15 degrees about z and 20 about x from 6 m: it lands on
    // one corner and its far end comes down.
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::box(Vector3(0.6, 0.1, 0.2));
    const Quaternion turn = Quaternion(Eigen::AngleAxis<real>(kPi / 9 / 3, Vector3::UnitX())) *
                            Quaternion(Eigen::AngleAxis<real>(kPi / 9 / 4, Vector3::UnitZ()));
    const BodyId box = droppedBody(f, shape, turn, 6);
    EXPECT_LE(deepestBelowGround(f, box, shape), kLandingDeepest);
}

TEST(TiltedLanding, HullLandsOnBothEnds) {
    // A 1.2 m triangular prism (hull of six points) tilted 5 degrees from 2 m.
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::convex({Vector3(-0.6, -0.1, -0.15), Vector3(-0.6, -0.1, 0.15), Vector3(-0.6, 0.15, 0),
                                       Vector3(0.6, -0.1, -0.15), Vector3(0.6, -0.1, 0.15), Vector3(0.6, 0.15, 0)});
    const BodyId hull = droppedBody(f, shape, Quaternion(Eigen::AngleAxis<real>(kPi / 36, Vector3::UnitZ())), 2);
    EXPECT_LE(deepestBelowGround(f, hull, shape), kLandingDeepest);
}

// The plank of PlankLandsOnBothEnds and the capsule of CapsuleLandsOnBothEnds landing
// on a static floor whose top is y = 0: their far sides are the incident shape's corners
// over the floor's face or triangles. Returns the deeper of the two landings.
real deepestOnFloor(WorldFixture &f) {
    const Shape plankShape = Shape::box(Vector3(0.5, 0.1, 0.1));
    const BodyId plank =
        droppedBody(f, plankShape, Quaternion(Eigen::AngleAxis<real>(kPi / 36, Vector3::UnitZ())), 2);
    const Shape capsuleShape = Shape::capsule(kRadius, kLength);
    const BodyId capsule = droppedBody(f, capsuleShape, lyingTilted(kPi / 12), 6);
    f.world.setPosition(capsule, f.position(capsule) + Vector3(0, 0, 4));
    real deepest = 0;
    for (int i = 0; i < 240; ++i) {
        f.world.step(kDt);
        deepest = std::max({deepest, belowGround(f, plank, plankShape), belowGround(f, capsule, capsuleShape)});
    }
    return deepest;
}

TEST(TiltedLanding, OnAStaticBox) {
    WorldFixture f(noSleep());
    addStatic(f.world, Shape::box(Vector3(20, 0.5, 20)), Vector3(0, -0.5, 0));
    EXPECT_LE(deepestOnFloor(f), kLandingDeepest);
}

TEST(TiltedLanding, OnAMeshFloor) {
    // Two triangles, placed so that their shared edge (z = x - 10) passes 10 m from where
    // the bodies land. A plank landing across an inner edge, its far end over the other
    // triangle, still went 15.7 mm deep (docs/contacts_and_sleep.md).
    WorldFixture f(noSleep());
    addStatic(f.world,
              Shape::mesh({Vector3(-20, 0, -20), Vector3(20, 0, -20), Vector3(20, 0, 20), Vector3(-20, 0, 20)},
                          {{0, 2, 1}, {0, 3, 2}}),
              Vector3(10, 0, 0));
    EXPECT_LE(deepestOnFloor(f), kLandingDeepest);
}

}  // namespace
}  // namespace cyclone::test
