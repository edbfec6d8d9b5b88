// A character and dynamic bodies: it pushes a light crate along, cannot move a heavy one
// (it pushes with at most its weight), and a crate that runs into it pushes it.
#include <algorithm>

#include "character/character_fixture.h"

namespace cyclone::test {
namespace {

TEST(CharacterPush, PushesALightCrateAlong) {
    // A 10 kg crate (0.4 m cube, x in [0.8, 1.2]) on a floor of friction 0.6: sliding
    // friction 0.6 * 10 * 9.81 = 59 N, far below the 687 N it pushes with at most. It
    // walks at 1.5 m/s for 3 s and meets the crate after (0.8 - 0.3) / 1.5 = 0.33 s; from
    // then on each step gives the crate its walking speed back, which friction slows by
    // 0.6 g dt = 0.098 m/s within the step: the crate travels between
    // (1.5 - 0.098) * 2.67 = 3.74 m and 1.5 * 2.67 = 4 m, and the character stays behind it.
    CharacterLevel level;
    level.floor();
    const BodyId crate = level.block({0.8, 0, -0.2}, {1.2, 0.4, 0.2}, Motion::Dynamic, 10);
    const CharacterId walker = level.character({0, 0, 0});
    level.walk(walker, {1.5, 0, 0}, 180);
    const Vector3 moved = level.world.body(crate).getPosition() - Vector3(1, 0.2, 0);
    EXPECT_GT(moved.x(), 3.7);
    EXPECT_LT(moved.x(), 4.05);
    EXPECT_NEAR(moved.z(), 0, 0.05);
    // Right behind its near face (x - 0.2): the capsule's axis r before it.
    const real face = level.world.body(crate).getPosition().x() - 0.2;
    EXPECT_LT(level.feet(walker).x(), face - kCharacterRadius + 0.002);
    EXPECT_GT(level.feet(walker).x(), face - kCharacterRadius - 0.1);
}

TEST(CharacterPush, CannotMoveACrateHeavierThanItsPush) {
    // A 1000 kg crate holds with up to 0.6 * 1000 * 9.81 = 5886 N of friction, more than
    // the 70 * 9.81 = 687 N the character pushes with: it stays, and the character stops
    // against it, its axis r before the near face at x = 1.
    CharacterLevel level;
    level.floor();
    const BodyId crate = level.block({1, 0, -0.5}, {2, 1, 0.5}, Motion::Dynamic, 1000);
    const CharacterId walker = level.character({0, 0, 0});
    level.walk(walker, {1.5, 0, 0}, 120);
    EXPECT_NEAR(level.world.body(crate).getPosition().x(), 1.5, 0.005);
    EXPECT_NEAR(level.feet(walker).x(), 1 - kCharacterRadius, 0.01);
}

TEST(CharacterPush, ACrateRunningIntoItPushesIt) {
    // A 100 kg crate slides on ice at 3 m/s into the standing character (70 kg): as in an
    // inelastic collision, both go on at 100 * 3 / 170 = 1.765 m/s, then the ground slows
    // the character (at g). Its fastest speed is that shared one, along +x.
    CharacterLevel level;
    level.floor(0);
    const BodyId crate = level.block({-2, 0, -0.5}, {-1, 1, 0.5}, Motion::Dynamic, 100, 0);
    level.world.setVelocity(crate, {3, 0, 0});
    const CharacterId stander = level.character({0, 0, 0});
    real fastest = 0;
    for (int i = 0; i < 60; ++i) {
        level.world.step(kDt);
        fastest = std::max(fastest, level.world.character(stander).velocity.x());
    }
    EXPECT_NEAR(fastest, 100 * 3.0 / 170, 0.02);
    EXPECT_GT(level.feet(stander).x(), 0.1);
    EXPECT_LT(level.world.body(crate).getVelocity().x(), 1.8);
}

TEST(CharacterPush, ABoxDroppedOnItRestsOnItsHead) {
    // Its capsule is a body of the World: a box dropped onto it lands on its head
    // (1.8 m high) and stays there, its centre 0.25 m above.
    CharacterLevel level;
    level.floor();
    const CharacterId stander = level.character({0, 0, 0});
    const BodyId box = level.block({-0.25, 2.5, -0.25}, {0.25, 3, 0.25}, Motion::Dynamic, 2);
    for (int i = 0; i < 120; ++i) level.world.step(kDt);
    EXPECT_NEAR(level.world.body(box).getPosition().y(), kCharacterHeight + 0.25, 0.02);
    EXPECT_TRUE(level.world.character(stander).onGround);
}

}  // namespace
}  // namespace cyclone::test
