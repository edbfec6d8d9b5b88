// A capsule or cylinder dropped nearly lying, tilted onto one end, lands on that end's
// sphere or rim point and turns about it; its other end then comes down within the step
// at the body's falling speed and more (collision/manifold_clipping.cpp, planeContact).
// From 6 m (10.8 m/s, 18 cm a step at 60 Hz) the other end went 25 mm (capsule, 15
// degrees) and 71 mm (cylinder, 5 degrees) into the ground when the manifold held only
// the first point: the other end needs its own point, a gap that the contact lets close,
// before it arrives.
//
// The bound: the speculative contact acts in the step of the impact, letting the gap
// close and no more; what gravity adds within that step, g dt^2 = 9.81 / 60^2 = 2.7 mm,
// plus the slop (0.2 mm) is the most that should remain, within the drop tests' 5 mm
// (speculative_contact_test.cpp).
#include <algorithm>
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr real kLandingDeepest = 0.005;
constexpr real kRadius = 0.2;
constexpr real kLength = 1.0;

// How far the lowest point lies below the centre of a capsule or cylinder (radius
// kRadius, core kLength) whose axis has vertical component `axisY`: half the core's
// vertical extent, plus the radius (capsule: the end sphere's bottom) or the radius
// across the axis, r sqrt(1 - axisY^2) (cylinder: the lower rim's lowest point).
real lowestBelowCentre(const Shape &shape, real axisY) {
    const real across = shape.type == ShapeType::Capsule ? kRadius : kRadius * std::sqrt(1 - axisY * axisY);
    return std::abs(axisY) * kLength / 2 + across;
}

// A body of `shape` whose axis (local z) lies along x tilted `tilt` up towards y, its
// lowest point `height` above the ground.
BodyId tiltedBody(WorldFixture &f, const Shape &shape, real tilt, real height) {
    BodySettings s;
    s.shape = shape;
    s.mass = 1;
    // Local z turned onto x, then x tilted towards y.
    s.orientation = Quaternion(Eigen::AngleAxis<real>(tilt, Vector3::UnitZ())) *
                    Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
    s.position = Vector3(0, height + lowestBelowCentre(shape, std::sin(tilt)), 0);
    return f.world.addBody(s);
}

// Steps 4 s and returns how far the body's lowest point went below the ground.
real deepestBelowGround(WorldFixture &f, BodyId id, const Shape &shape) {
    real deepest = 0;
    for (int i = 0; i < 240; ++i) {
        f.world.step(kDt);
        const RigidBody &b = f.world.body(id);
        const real axisY = b.getTransform().linear().col(2).y();
        deepest = std::max(deepest, lowestBelowCentre(shape, axisY) - b.getPosition().y());
    }
    return deepest;
}

TEST(TiltedLanding, CapsuleLandsOnBothEnds) {
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::capsule(kRadius, kLength);
    const BodyId capsule = tiltedBody(f, shape, kPi / 12, 6);
    EXPECT_LE(deepestBelowGround(f, capsule, shape), kLandingDeepest);
    // It ends lying on its side: its core the radius above the ground.
    EXPECT_NEAR(f.position(capsule).y(), kRadius, kLandingDeepest);
}

TEST(TiltedLanding, CylinderLandsOnBothRims) {
    WorldFixture f(noSleep());
    f.ground();
    const Shape shape = Shape::cylinder(kRadius, kLength);
    const BodyId cylinder = tiltedBody(f, shape, kPi / 36, 6);
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
    const BodyId cylinder = tiltedBody(f, shape, kPi / 3, 3);
    EXPECT_LE(deepestBelowGround(f, cylinder, shape), kLandingDeepest);
    const real y = f.position(cylinder).y();
    EXPECT_LE(std::min(std::abs(y - kRadius), std::abs(y - kLength / 2)), kLandingDeepest) << y;
}

}  // namespace
}  // namespace cyclone::test
