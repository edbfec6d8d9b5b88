// Round bodies rolling fast keep their height (solver/round_depths.h): within a step the
// solver reads depths from anchors fixed on the bodies, which a rolling body turns away
// from the contact; the round side's share is corrected, so a ball, a capsule or a
// cylinder rolling on its side at 4.3 m/s neither sinks nor bumps.
#include <algorithm>
#include <cmath>
#include <string>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// The largest |height - rest| and |vertical speed| of a body rolled along x at `speed`
// without slipping (w = v / r about -z) on a plane, over `seconds` at 60 Hz with the
// default solver (4 sub-steps) and materials.
struct Roll {
    real heightError = 0;
    real verticalSpeed = 0;
    real speed = 0;  ///< Along x at the end, m/s.
};
Roll rollOnPlane(const Shape &shape, real rest, real speed, double seconds) {
    WorldFixture f(noSleep());
    f.ground();
    BodySettings s;
    s.shape = shape;
    s.position = Vector3(0, rest, 0);
    s.velocity = Vector3(speed, 0, 0);
    s.rotation = Vector3(0, 0, -speed / rest);
    const BodyId id = f.world.addBody(s);
    Roll roll;
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < steps; ++i) {
        f.world.step(kDt);
        const RigidBody &b = f.world.body(id);
        roll.heightError = std::max(roll.heightError, std::abs(b.getPosition().y() - rest));
        roll.verticalSpeed = std::max(roll.verticalSpeed, std::abs(b.getVelocity().y()));
    }
    roll.speed = f.world.body(id).getVelocity().x();
    return roll;
}

// A body resting on a plane whose depths are read right does not move along the normal:
// each sub-step's normal row ends with no normal velocity where the depth is within the
// slop (0.2 mm), and a depth beyond it is pushed out. Its height can err by the slop plus
// the fall of one sub-step, g h^2 = 9.81 / 240^2 = 0.17 mm, before the contact holds it:
// 0.37 mm, inside the 1 mm. Its vertical speed after a step is what the passes
// leave of a sub-step's g h = 0.041 m/s: the issue asks |vy| <= 0.01 m/s.
// Before the correction the 0.25 m ball at 4.3 m/s turned 0.072 rad per sub-step, its
// anchor rose 0.65 mm a sub-step, and it sat 2.79 mm low at -0.04 m/s.
constexpr real kHeightBound = 0.0002 + kG * (kDt / 4) * (kDt / 4);
constexpr real kVerticalSpeedBound = 0.01;

TEST(RoundDepths, FastBallRollsOnAPlaneAtItsHeight) {
    const Roll roll = rollOnPlane(Shape::sphere(0.25), 0.25, 4.3, 2.0);
    EXPECT_LE(roll.heightError, kHeightBound);
    EXPECT_LE(roll.verticalSpeed, kVerticalSpeedBound);
    // It rolled on: the default 2 mm of rolling resistance slows it by 2 mm g / (1.4 r) =
    // 0.056 m/s^2, 0.11 m/s in 2 s.
    EXPECT_NEAR(roll.speed, 4.3 - 0.002 * kG / (1.4 * 0.25) * 2, 0.01);
}

TEST(RoundDepths, CapsuleAndCylinderRollOnTheirSidesAtTheirHeight) {
    // Along z (their axis) they lie on their sides and roll about it.
    for (const Shape &shape : {Shape::capsule(0.25, 1.0), Shape::cylinder(0.25, 1.0)}) {
        SCOPED_TRACE(shape.type == ShapeType::Capsule ? "capsule" : "cylinder");
        const Roll roll = rollOnPlane(shape, 0.25, 4.3, 2.0);
        EXPECT_LE(roll.heightError, kHeightBound);
        EXPECT_LE(roll.verticalSpeed, kVerticalSpeedBound);
        EXPECT_GT(roll.speed, 4) << "it rolled on";
    }
}

}  // namespace
}  // namespace cyclone::test
