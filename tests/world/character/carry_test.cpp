// A character carried by what it stands on: a kinematic platform that moves, reverses and
// moves diagonally down; one that turns; a dynamic raft sliding on ice.
#include "character/character_fixture.h"

namespace cyclone::test {
namespace {

TEST(CharacterCarry, KeepsItsPlaceOnAPlatformThatReversesAndMovesDown) {
    // A kinematic platform 4 m square, its top at y = 3, moves at 2 m/s along +x for 1 s,
    // back at 2 m/s for 1 s, then diagonally down at (2, -1.5, 0) m/s (faster down than a
    // fall starts) for 1 s. The character stands still on it: its feet keep their place
    // over the platform's top centre within 2 cm, and it is on the ground every step.
    CharacterLevel level;
    level.floor();
    const BodyId platform = level.block({-2, 2.6, -2}, {2, 3, 2}, Motion::Kinematic);
    const CharacterId rider = level.character({0, 3, 0});
    level.world.step(kDt);
    const auto offset = [&] {
        return Vector3(level.feet(rider) - (level.world.body(platform).getPosition() + Vector3(0, 0.2, 0)));
    };
    const Vector3 start = offset();
    ASSERT_LT(start.norm(), 0.002);
    const Vector3 legs[3] = {{2, 0, 0}, {-2, 0, 0}, {2, -1.5, 0}};
    for (const Vector3 &velocity : legs) {
        level.world.setVelocity(platform, velocity);
        for (int i = 0; i < 60; ++i) {
            level.world.step(kDt);
            const CharacterState state = level.world.character(rider);
            ASSERT_TRUE(state.onGround) << "velocity " << velocity.transpose() << ", step " << i;
            EXPECT_EQ(state.groundBody, platform);
            EXPECT_LT((offset() - start).norm(), 0.02) << "velocity " << velocity.transpose() << ", step " << i;
        }
    }
}

TEST(CharacterCarry, TurnsWithATurningPlatform) {
    // A platform turning at 1 rad/s about the vertical through its centre carries a
    // character standing 1 m from the axis round a circle: after 1 s its feet are the
    // point (1, 1, 0) turned by 1 rad about +y, (cos 1, 1, -sin 1), within 2 cm.
    CharacterLevel level;
    level.floor();
    const BodyId platform = level.block({-2, 0.6, -2}, {2, 1, 2}, Motion::Kinematic);
    const CharacterId rider = level.character({1, 1, 0});
    level.world.step(kDt);
    level.world.setRotation(platform, {0, 1, 0});
    for (int i = 0; i < 60; ++i) {
        level.world.step(kDt);
        ASSERT_TRUE(level.world.character(rider).onGround) << "step " << i;
    }
    const Vector3 feet = level.feet(rider);
    EXPECT_NEAR(feet.x(), std::cos(1.0), 0.02);
    EXPECT_NEAR(feet.z(), -std::sin(1.0), 0.02);
    EXPECT_NEAR(feet.y(), 1, 0.002);
}

TEST(CharacterCarry, RidesADynamicRaftOnIce) {
    // A 500 kg raft slides on frictionless ice at 1 m/s; nothing slows it across, so the
    // character standing on it is carried 1 m in 1 s with it, keeping its place on it
    // within 2 cm.
    CharacterLevel level;
    level.floor(0);
    const BodyId raft = level.block({-1.5, 0, -1.5}, {1.5, 0.4, 1.5}, Motion::Dynamic, 500, 0);
    level.world.setVelocity(raft, {1, 0, 0});
    const CharacterId rider = level.character({0, 0.4, 0});
    level.world.step(kDt);
    const Vector3 start = level.feet(rider) - level.world.body(raft).getPosition();
    for (int i = 0; i < 60; ++i) {
        level.world.step(kDt);
        ASSERT_TRUE(level.world.character(rider).onGround) << "step " << i;
    }
    EXPECT_NEAR(level.world.body(raft).getPosition().x(), 1, 0.05);
    EXPECT_LT((level.feet(rider) - level.world.body(raft).getPosition() - start).norm(), 0.02);
}

}  // namespace
}  // namespace cyclone::test
