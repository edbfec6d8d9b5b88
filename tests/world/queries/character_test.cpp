// The character example's controller (examples/character): a capsule moved by
// World::shapeCast climbs a 0.2 m step, stops at a wall, and is stopped by a step too high.
#include <gtest/gtest.h>

#include "character/character_controller.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// The capsule (radius 0.3 m, 1 m between its end centres: 1.6 m tall) stands with its
// centre 0.8 m above what it stands on, and stops 0.3 m before a wall, both up to its
// 5 mm skin (character::CharacterSettings).
constexpr real kHalfHeight = 0.8;
constexpr real kRadius = 0.3;
constexpr real kSkin = 0.005;

TEST(Character, ClimbsAStepAndStopsAtAWall) {
    // A step 0.2 m high over x in [2, 4] and a wall from x = 6: walking +x at 1.5 m/s for
    // 5 s (7.5 m wanted) it goes up onto the step's top (y = 0.2), down its far side onto
    // the floor, and stops 0.3 m before the wall.
    World world;
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    addStatic(world, Shape::box({1, 0.1, 2}), {3, 0.1, 0});
    addStatic(world, Shape::box({0.5, 2, 2}), {6.5, 2, 0});
    character::CharacterController walker(world, Vector3(0, kHalfHeight + kSkin, 0));
    bool onStep = false;
    for (int i = 0; i < 300; ++i) {
        walker.move(Vector3(1.5, 0, 0), kDt);
        const Vector3 &c = walker.centre();
        if (c.x() > 2.5 && c.x() < 3.5) {
            onStep = true;
            EXPECT_NEAR(c.y(), 0.2 + kHalfHeight, 2 * kSkin) << "at x = " << c.x();
        }
    }
    EXPECT_TRUE(onStep);
    EXPECT_TRUE(walker.grounded());
    EXPECT_NEAR(walker.centre().x(), 6 - kRadius, 2 * kSkin);
    EXPECT_NEAR(walker.centre().y(), kHalfHeight, 2 * kSkin);
    EXPECT_NEAR(walker.centre().z(), 0, 1e-9);
}

TEST(Character, StepTooHighBlocks) {
    // A 0.4 m step, above the 0.25 m the controller climbs: it stops 0.3 m before x = 2.
    World world;
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    addStatic(world, Shape::box({1, 0.2, 2}), {3, 0.2, 0});
    character::CharacterController walker(world, Vector3(0, kHalfHeight + kSkin, 0));
    for (int i = 0; i < 180; ++i) walker.move(Vector3(1.5, 0, 0), kDt);
    EXPECT_NEAR(walker.centre().x(), 2 - kRadius, 2 * kSkin);
    EXPECT_NEAR(walker.centre().y(), kHalfHeight, 2 * kSkin);
}

TEST(Character, WalksUpAWalkableSlope) {
    // A 20 degree ramp: its top surface rises tan(20 deg) = 0.364 m per m. Walking up it
    // the feet stay on it: the centre is 0.8 m above the surface under the capsule's
    // lowest point, which for a slope is where the cap touches, r (1/cos - 1) higher.
    World world;
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    const real angle = 20 * kPi / 180;
    BodySettings ramp;
    ramp.isStatic = true;
    ramp.shape = Shape::box({5, 0.1, 2});
    ramp.orientation = Quaternion(Eigen::AngleAxis<real>(angle, Vector3::UnitZ()));
    // Its top surface passes through (2, 0, 0): the centre is 0.1 m below it, along the normal.
    const Vector3 normal(-std::sin(angle), std::cos(angle), 0);
    const Vector3 along(std::cos(angle), std::sin(angle), 0);
    ramp.position = Vector3(2, 0, 0) + 5 * along - 0.1 * normal;
    world.addBody(ramp);
    character::CharacterController walker(world, Vector3(0, kHalfHeight + kSkin, 0));
    for (int i = 0; i < 180; ++i) walker.move(Vector3(1.5, 0, 0), kDt);
    // 4.5 m of walking, less what the slope takes: somewhere on the ramp, above x = 3.
    const Vector3 &c = walker.centre();
    ASSERT_GT(c.x(), 3);
    const real surface = (c.x() - 2) * std::tan(angle);
    EXPECT_NEAR(c.y(), surface + kHalfHeight + kRadius * (1 / std::cos(angle) - 1), 3 * kSkin);
    EXPECT_TRUE(walker.grounded());
}

}  // namespace
}  // namespace cyclone::test
