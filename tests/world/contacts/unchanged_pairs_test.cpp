// Unchanged pairs (DebugSettings::unchangedPairs): a pair that found no contact with
// both bodies standing still is not tested again while neither body's state changes.
//
// The scene: two rows of ten unit boxes on the ground, along x, touching face to face
// within a row; the second row 3 cm behind the first (z = 1.03). A ball of radius 0.25
// spins about the vertical on the first row's box 0, keeping that row's island awake:
// boxes 1 to 9 of it are held (dynamics/holding.h), standing still. The second row
// touches nothing of the first, rests alone and falls asleep.
//
// Broadphase boxes are the shapes' boxes grown by 2 cm (kBroadphaseMargin) on every
// side: across the rows they overlap (3 cm < 4 cm), and box i of the first row and box j
// of the second overlap along x when |i - j| < 1.04, that is |i - j| <= 1. The pairs of
// a held box and a sleeping one, both still and apart by 3 cm, are thus
//     boxes 1-8: three each (j = i - 1, i, i + 1), box 9: two (8, 9),  26 in all;
// box 0 touches the spinning ball, is solved and never stands still.
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace unchanged_pairs {

constexpr int kBoxes = 10;
constexpr real kRowGap = 0.03;  // m
constexpr int kStillPairs = 8 * 3 + 2;

struct Rows {
    World world;
    std::vector<BodyId> front, back;
    BodyId ball;
};

WorldSettings withUnchangedPairs(bool on) {
    WorldSettings settings;
    settings.debug.unchangedPairs = on;
    return settings;
}

void buildRows(Rows &rows) {
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    ground.material.friction = 0.6;
    rows.world.addBody(ground);
    for (int row = 0; row < 2; ++row) {
        for (int i = 0; i < kBoxes; ++i) {
            BodySettings b;
            b.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            b.position = Vector3(i, 0.5, row * (1 + kRowGap));
            (row == 0 ? rows.front : rows.back).push_back(rows.world.addBody(b));
        }
    }
    BodySettings ball;
    ball.shape = Shape::sphere(0.25);
    ball.position = Vector3(0, 1.25, 0);
    ball.rotation = Vector3(0, 8, 0);
    rows.ball = rows.world.addBody(ball);
}

std::vector<RigidBody> statesOf(const Rows &rows) {
    std::vector<RigidBody> states;
    for (const std::vector<BodyId> *row : {&rows.front, &rows.back})
        for (const BodyId &b : *row) states.push_back(rows.world.body(b));
    states.push_back(rows.world.body(rows.ball));
    return states;
}

TEST(UnchangedPairs, HeldBoxesKeepTheirPairsWithASleepingRowUntestedAndNothingChanges) {
    Rows on{World(withUnchangedPairs(true)), {}, {}, {}};
    Rows off{World(withUnchangedPairs(false)), {}, {}, {}};
    buildRows(on);
    buildRows(off);
    int stillSteps = 0;
    for (int step = 0; step < 600; ++step) {
        on.world.step(kDt);
        off.world.step(kDt);
        const std::vector<RigidBody> a = statesOf(on), b = statesOf(off);
        for (std::size_t k = 0; k < a.size(); ++k) ASSERT_TRUE(sameBits(a[k], b[k])) << "body " << k << ", step " << step;
        const StepStats &s = on.world.stats();
        const StepStats &t = off.world.stats();
        EXPECT_EQ(t.pairsUnchanged, 0);
        EXPECT_EQ(s.pairsTested + s.pairsUnchanged, t.pairsTested) << "step " << step;
        // While boxes 1-9 are held and the back row sleeps, every pair across is kept.
        const bool backAsleep = !on.world.body(on.back[5]).getAwake();
        if (s.heldBodies == kBoxes - 1 && backAsleep && on.world.body(on.front[1]).getAwake()) {
            ++stillSteps;
            // The boxes' velocities are zeroed when they are first held, after that step's
            // tests; the next step tests the pairs standing still; from the one after on,
            // none is tested.
            if (stillSteps > 2) {
                EXPECT_EQ(s.pairsUnchanged, kStillPairs) << "step " << step;
            }
        }
    }
    // The ball spins down within 4.08 s (held_bodies_test.cpp): steps from about 1.5 s.
    EXPECT_GT(stillSteps, 60);
    EXPECT_FALSE(on.world.body(on.front[5]).getAwake());
}

TEST(UnchangedPairs, AStaticWallMovedIntoAHeldBoxIsTestedAndPushesItOut) {
    // A static wall 3 cm in front of held box 5 (its face at z = -0.53) is moved 4 cm
    // closer, 1 cm into the box: the pair must be tested again and the box pushed back
    // by about the overlap, though neither body had a velocity.
    Rows rows{World(withUnchangedPairs(true)), {}, {}, {}};
    buildRows(rows);
    const BodyId wall = addStatic(rows.world, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(5, 0.5, -1 - kRowGap));
    for (int step = 0; step < 120; ++step) rows.world.step(kDt);
    ASSERT_GE(rows.world.stats().heldBodies, 1);
    ASSERT_GT(rows.world.stats().pairsUnchanged, 0);
    const real z0 = rows.world.body(rows.front[5]).getPosition().z();
    rows.world.setPosition(wall, Vector3(5, 0.5, -1 + 0.01));
    // The very next step sees the overlap: untested, the box would stand in the wall for
    // that step, and its waking (a moved static body wakes what it touches) would move it
    // only a step later. A quarter of the overlap at least goes in the first step.
    rows.world.step(kDt);
    EXPECT_GT(rows.world.body(rows.front[5]).getPosition().z() - z0, 0.0025);
    for (int step = 1; step < 60; ++step) rows.world.step(kDt);
    // Out of the wall but for the contact slop (at most 5 mm): at least 5 mm moved.
    EXPECT_GT(rows.world.body(rows.front[5]).getPosition().z() - z0, 0.005);
}

TEST(UnchangedPairs, StepsAfterARestoreRepeatTheFirstRun) {
    // What was kept untested is not saved: after a restore every pair is tested afresh,
    // and the steps repeat the first run bit for bit.
    Rows rows{World(withUnchangedPairs(true)), {}, {}, {}};
    buildRows(rows);
    for (int step = 0; step < 150; ++step) rows.world.step(kDt);
    ASSERT_GT(rows.world.stats().pairsUnchanged, 0);
    const std::vector<std::uint8_t> saved = rows.world.saveState();
    std::vector<std::vector<RigidBody>> first;
    for (int step = 0; step < 240; ++step) {
        rows.world.step(kDt);
        if (step % 60 == 59) first.push_back(statesOf(rows));
    }
    rows.world.restoreState(saved);
    for (int step = 0; step < 240; ++step) {
        rows.world.step(kDt);
        if (step % 60 != 59) continue;
        const std::vector<RigidBody> now = statesOf(rows);
        for (std::size_t k = 0; k < now.size(); ++k)
            EXPECT_TRUE(sameBits(now[k], first[std::size_t(step / 60)][k])) << "body " << k << ", step " << step;
    }
}

}  // namespace unchanged_pairs
}  // namespace cyclone::test
