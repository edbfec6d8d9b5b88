// A character walking: flat ground, stairs, a step too high, ramps it can and cannot
// walk up, a ledge it walks off, a jump. Expected values from geometry and kinematics.
#include <algorithm>

#include "character/character_fixture.h"

namespace cyclone::test {
namespace {

TEST(CharacterWalk, CoversDistanceOnFlatGroundWithFeetOnIt) {
    // 4 m/s for 2 s (120 steps of 1/60 s): 8 m, the feet on y = 0 up to the 1 mm gap kept.
    CharacterLevel level;
    level.floor();
    const CharacterId walker = level.character({0, 0, 0});
    level.world.setCharacterVelocity(walker, {4, 0, 0});
    for (int i = 0; i < 120; ++i) {
        level.world.step(kDt);
        const CharacterState state = level.world.character(walker);
        ASSERT_TRUE(state.onGround) << "step " << i;
        EXPECT_NEAR(state.position.y(), 0, 0.002) << "step " << i;
        EXPECT_GE(state.position.y(), -1e-4) << "step " << i;
    }
    EXPECT_NEAR(level.feet(walker).x(), 8, 0.1);
    EXPECT_NEAR(level.feet(walker).z(), 0, 1e-9);
    EXPECT_NEAR(level.world.character(walker).velocity.x(), 4, 1e-6);
}

TEST(CharacterWalk, ClimbsFiveStairsToALanding) {
    // Four steps of 0.3 m rise and 0.5 m run from x = 2, then a landing 1.5 m high from
    // x = 4 to 9: walking 2 m/s for 4 s (8 m wanted) it ends on the landing at y = 1.5.
    CharacterLevel level;
    level.floor();
    for (int k = 1; k <= 4; ++k)
        level.block({2 + 0.5 * (k - 1), 0, -1}, {2 + 0.5 * k, 0.3 * k, 1});
    const BodyId landing = level.block({4, 0, -1}, {9, 1.5, 1});
    const CharacterId walker = level.character({0, 0, 0});
    level.walk(walker, {2, 0, 0}, 240);
    const CharacterState state = level.world.character(walker);
    EXPECT_GT(state.position.x(), 5);
    EXPECT_NEAR(state.position.y(), 1.5, 0.02);
    EXPECT_TRUE(state.onGround);
    ASSERT_TRUE(state.groundBody.has_value());
    EXPECT_EQ(*state.groundBody, landing);
}

TEST(CharacterWalk, StepTooHighStopsItAtItsFace) {
    // A 0.5 m step from x = 2, above the 0.35 m it climbs: the capsule stops against its
    // face, its axis (the feet) r = 0.3 m before it, on the floor.
    CharacterLevel level;
    level.floor();
    level.block({2, 0, -1}, {4, 0.5, 1});
    const CharacterId walker = level.character({0, 0, 0});
    level.walk(walker, {2, 0, 0}, 120);
    EXPECT_NEAR(level.feet(walker).x(), 2 - kCharacterRadius, 0.01);
    EXPECT_NEAR(level.feet(walker).y(), 0, 0.002);
    EXPECT_TRUE(level.world.character(walker).onGround);
}

TEST(CharacterWalk, ClimbsALowStepAndStopsAtAWall) {
    // The old example's course: a 0.2 m step over x in [2, 4], a wall from x = 6. Walking
    // +x at 1.5 m/s for 5 s it goes over the step (feet at y = 0.2 over its middle), down
    // the far side, and stops r before the wall (each to 1 cm, the old test's 2 skins).
    CharacterLevel level;
    level.floor();
    level.block({2, 0, -2}, {4, 0.2, 2});
    level.block({6, 0, -2}, {7, 4, 2});
    const CharacterId walker = level.character({0, 0, 0});
    level.world.setCharacterVelocity(walker, {1.5, 0, 0});
    bool onStep = false;
    for (int i = 0; i < 300; ++i) {
        level.world.step(kDt);
        const Vector3 feet = level.feet(walker);
        if (feet.x() > 2.5 && feet.x() < 3.5) {
            onStep = true;
            EXPECT_NEAR(feet.y(), 0.2, 0.01) << "at x = " << feet.x();
        }
    }
    EXPECT_TRUE(onStep);
    EXPECT_NEAR(level.feet(walker).x(), 6 - kCharacterRadius, 0.01);
    EXPECT_NEAR(level.feet(walker).y(), 0, 0.01);
}

TEST(CharacterWalk, WalksUpAThirtyDegreeRamp) {
    // The ramp's surface is y = (x - 2) tan 30. Walking keeps its speed across up, so at
    // 2 m/s for 4 s the feet reach x = 8; the capsule's sphere rests on the slope with its
    // centre r from it, r / cos 30 above the surface, so the feet (its lowest point, on
    // the axis) are r (1 / cos 30 - 1) = 4.6 cm above the surface under them.
    CharacterLevel level;
    level.floor();
    const real angle = 30 * kPi / 180;
    level.ramp(2, angle, 12);
    const CharacterId walker = level.character({0, 0, 0});
    level.walk(walker, {2, 0, 0}, 240);
    const Vector3 feet = level.feet(walker);
    EXPECT_NEAR(feet.x(), 8, 0.1);
    const real surface = (feet.x() - 2) * std::tan(angle);
    EXPECT_NEAR(feet.y(), surface + kCharacterRadius * (1 / std::cos(angle) - 1), 0.005);
    EXPECT_TRUE(level.world.character(walker).onGround);
}

TEST(CharacterWalk, DoesNotWalkUpASixtyDegreeRamp) {
    // At the foot of a 60 degree ramp (steeper than the 45 it walks) it may rise by its
    // step height at most, and never gets past the foot line x = 2.
    CharacterLevel level;
    level.floor();
    level.ramp(2, 60 * kPi / 180, 8);
    const CharacterId walker = level.character({0, 0, 0});
    level.world.setCharacterVelocity(walker, {2, 0, 0});
    real highest = 0;
    for (int i = 0; i < 240; ++i) {
        level.world.step(kDt);
        highest = std::max(highest, level.feet(walker).y());
        ASSERT_LT(level.feet(walker).x(), 2) << "step " << i;
    }
    EXPECT_LE(highest, kStepHeight + kSkin);
    EXPECT_NEAR(level.feet(walker).y(), 0, 0.002);
}

TEST(CharacterWalk, SlidesDownASteepRamp) {
    // Put on a 60 degree ramp, it is not on the ground and slides down towards its foot:
    // after 1 s it is lower and further down-slope (smaller x) than it started.
    CharacterLevel level;
    level.floor();
    const real angle = 60 * kPi / 180;
    level.ramp(0, angle, 8);
    // The sphere's centre r above the surface at x = 2: the feet r (1/cos - 1) above it.
    const real x = 2, y = x * std::tan(angle) + kCharacterRadius * (1 / std::cos(angle) - 1) + 0.01;
    const CharacterId walker = level.character({x, y, 0});
    level.world.step(kDt);
    EXPECT_FALSE(level.world.character(walker).onGround);
    for (int i = 0; i < 60; ++i) level.world.step(kDt);
    const Vector3 feet = level.feet(walker);
    EXPECT_LT(feet.y(), y - 1);
    EXPECT_LT(feet.x(), x - 0.5);
}

TEST(CharacterWalk, FallsOffALedgeForTheFreeFallTime) {
    // A 2 m ledge ending at x = 0; walking off at 2 m/s, it is airborne for
    // sqrt(2 h / g) = sqrt(4 / 9.81) = 0.639 s = 38.3 steps (the issue allows 8 steps: the
    // capsule's round bottom leaves the edge gradually), and lands on the floor.
    CharacterLevel level;
    const BodyId floor = level.floor();
    level.block({-6, 0, -2}, {0, 2, 2});
    const CharacterId walker = level.character({-1, 2, 0});
    level.world.setCharacterVelocity(walker, {2, 0, 0});
    int left = -1, landed = -1;
    for (int i = 0; i < 240 && landed < 0; ++i) {
        level.world.step(kDt);
        const bool onGround = level.world.character(walker).onGround;
        if (left < 0 && !onGround) left = i;
        if (left >= 0 && onGround) landed = i;
    }
    ASSERT_GE(left, 0);
    ASSERT_GE(landed, 0);
    EXPECT_NEAR(landed - left, std::sqrt(2 * 2 / kG) / kDt, 8);
    const CharacterState state = level.world.character(walker);
    EXPECT_EQ(state.groundBody, floor);
    EXPECT_NEAR(state.position.y(), 0, 0.002);
}

TEST(CharacterWalk, JumpRisesTheBallisticHeight) {
    // Jumping at 5 m/s, the feet rise v^2 / 2g = 25 / 19.62 = 1.274 m, and it lands back
    // after 2 v / g = 1.02 s = 61 steps.
    CharacterLevel level;
    level.floor();
    const CharacterId jumper = level.character({0, 0, 0});
    level.walk(jumper, {0, 0, 0}, 2);
    level.world.setCharacterVelocity(jumper, {0, 5, 0});
    level.world.step(kDt);
    level.world.setCharacterVelocity(jumper, {0, 0, 0});
    EXPECT_FALSE(level.world.character(jumper).onGround);
    real highest = 0;
    int steps = 1;
    for (; steps < 200 && !level.world.character(jumper).onGround; ++steps) {
        level.world.step(kDt);
        highest = std::max(highest, level.feet(jumper).y());
    }
    EXPECT_NEAR(highest, 25 / (2 * kG), 0.06);
    EXPECT_NEAR(steps, 2 * 5 / kG / kDt, 2);
    EXPECT_NEAR(level.feet(jumper).y(), 0, 0.002);
}

}  // namespace
}  // namespace cyclone::test
