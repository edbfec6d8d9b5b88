// The viewer's character mode without a window: keys and the camera's heading to a walk.
#include <gtest/gtest.h>

#include "character_mode.h"

namespace cyclone::viewer {
namespace {

World floorWorld() {
    World world;
    BodySettings floor;
    floor.motion = Motion::Static;
    floor.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(floor);
    return world;
}

TEST(CharacterMode, WalksAlongTheCameraHeading) {
    // The camera looks down towards -z and +x (heading (1, -1, -1)): W walks along
    // (1, 0, -1) / sqrt 2 at 4 m/s, so 1 s (60 steps) covers 4 m that way; the camera's
    // pitch does not slow it.
    World world = floorWorld();
    CharacterMode mode;
    mode.start(world, Vector3::Zero());
    ASSERT_TRUE(mode.on());
    WalkKeys keys;
    keys.forward = true;
    mode.drive(world, keys, Vector3(1, -1, -1));
    for (int i = 0; i < 60; ++i) world.step(1.0 / 60);
    const Vector3 focus = mode.focus(world);
    EXPECT_NEAR(focus.x(), 4 / std::sqrt(2.0), 0.05);
    EXPECT_NEAR(focus.z(), -4 / std::sqrt(2.0), 0.05);
    // D walks to the right of the heading: heading x up = (1, 0, -1) x (0, 1, 0) = (1, 0, 1).
    keys.forward = false;
    keys.right = true;
    const Vector3 before = mode.focus(world);
    mode.drive(world, keys, Vector3(1, -1, -1));
    for (int i = 0; i < 60; ++i) world.step(1.0 / 60);
    const Vector3 moved = mode.focus(world) - before;
    EXPECT_NEAR(moved.x(), 4 / std::sqrt(2.0), 0.05);
    EXPECT_NEAR(moved.z(), 4 / std::sqrt(2.0), 0.05);
    mode.stop(world);
    EXPECT_FALSE(mode.on());
    EXPECT_EQ(world.bodyCount(), 1u);
}

}  // namespace
}  // namespace cyclone::viewer
