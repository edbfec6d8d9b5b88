// Held bodies (DebugSettings::holding): the still part of an awake island is left out of
// the solve, and nothing a game sees changes for it.
//
// The scene: a row of unit boxes touching face to face on the ground, one island, and a
// ball of radius r = 0.25 m spinning about the vertical on the first box. Spinning
// resistance (5 mm) slows the ball by a torque 0.005 m g at most, against its moment
// 0.4 m r^2, so its spin falls at
//     alpha = 0.005 g / (0.4 r^2) = 1.962 rad/s^2,
// from 8 rad/s to 0 at t = 4.08 s. Until then the ball keeps the row's island awake.
// A box is held when it and every body it shares a pair with could sleep and rest: the
// ball moves, so box 0 (touching it) is solved, and boxes 1 to 9 are held once their
// sleep averages fall below the threshold.
#include <algorithm>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr int kBoxes = 10;
constexpr real kSpin = 8;           // rad/s
constexpr real kAlpha = 0.005 * kG / (0.4 * 0.25 * 0.25);  // rad/s^2

struct Row {
    World world;
    std::vector<BodyId> boxes;
    BodyId ball;
};

// The ground plane y = 0.
void addGround(World &world, real friction) {
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    ground.material.friction = friction;
    world.addBody(ground);
}

void buildRow(Row &row) {
    addGround(row.world, 0.6);
    for (int i = 0; i < kBoxes; ++i) {
        BodySettings b;
        b.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        b.position = Vector3(i, 0.5, 0);
        row.boxes.push_back(row.world.addBody(b));
    }
    BodySettings ball;
    ball.shape = Shape::sphere(0.25);
    ball.position = Vector3(0, 1.25, 0);
    ball.rotation = Vector3(0, kSpin, 0);
    row.ball = row.world.addBody(ball);
}

WorldSettings withHolding(bool on) {
    WorldSettings settings;
    settings.debug.holding = on;
    return settings;
}

// Steps the row from step `from` to `to` (counted from a save or a call) and keeps the
// boxes' states after every 60th step.
std::vector<std::vector<RigidBody>> stepRecording(Row &row, int from, int to) {
    std::vector<std::vector<RigidBody>> kept;
    for (int step = from; step < to; ++step) {
        row.world.step(kDt);
        if (step % 60 != 59) continue;
        kept.emplace_back();
        for (const BodyId &b : row.boxes) kept.back().push_back(row.world.body(b));
    }
    return kept;
}

// Steps the row `steps` times and expects the boxes' states stepRecording kept, bit for bit.
void expectRepeats(Row &row, int steps, const std::vector<std::vector<RigidBody>> &first) {
    for (int step = 0; step < steps; ++step) {
        row.world.step(kDt);
        if (step % 60 != 59) continue;
        const std::vector<RigidBody> &then = first[std::size_t(step / 60)];
        for (std::size_t i = 0; i < row.boxes.size(); ++i)
            EXPECT_TRUE(sameBits(row.world.body(row.boxes[i]), then[i])) << "box " << i << ", step " << step;
    }
}

TEST(HeldBodies, ASpinningBallOnARowLeavesTheFarBoxesStillAndSpinsDownAsWithoutThem) {
    Row held{World(withHolding(true)), {}, {}};
    Row solved{World(withHolding(false)), {}, {}};
    buildRow(held);
    buildRow(solved);
    std::vector<Vector3> before;
    for (int step = 1; step <= 300; ++step) {  // 5 s
        held.world.step(kDt);
        solved.world.step(kDt);
        EXPECT_EQ(solved.world.stats().heldBodies, 0);
        const real t = step * kDt;
        if (step == 90) {  // 1.5 s: the boxes' sleep averages are below the threshold
            EXPECT_EQ(held.world.stats().heldBodies, kBoxes - 1);
            for (const BodyId &b : held.boxes) before.push_back(held.world.body(b).getPosition());
        }
        if (step > 90 && step <= 210) {  // up to 3.5 s the ball spins; boxes 1-9 do not move at all
            ASSERT_EQ(held.world.stats().heldBodies, kBoxes - 1) << "t = " << t;
            for (int i = 1; i < kBoxes; ++i)
                EXPECT_EQ(held.world.body(held.boxes[std::size_t(i)]).getPosition(), before[std::size_t(i)]) << i;
            EXPECT_TRUE(held.world.body(held.boxes[kBoxes - 1]).getAwake());
        }
        if (step == 180) {  // 3 s: 8 - 1.962 * 3 = 2.114 rad/s, with the row solved or held
            const real expected = kSpin - kAlpha * t;
            EXPECT_NEAR(held.world.body(held.ball).getRotation().y(), expected, 0.05);
            EXPECT_NEAR(solved.world.body(solved.ball).getRotation().y(), expected, 0.05);
        }
    }
    // The ball stopped at 4.08 s; 0.9 s later its island, held boxes and all, sleeps.
    for (Row *row : {&held, &solved}) {
        EXPECT_FALSE(row->world.body(row->ball).getAwake());
        for (const BodyId &b : row->boxes) EXPECT_FALSE(row->world.body(b).getAwake());
    }
}

TEST(HeldBodies, AHitOnAHeldBoxIsAHitOnABodyWithMass) {
    // The row's last box and a 2 kg ball have no friction, so a ball sliding at 6 m/s
    // along -z into the box's side (its centre at the box's, so no turn) meets a 1 kg body
    // that nothing holds along z: plastic (e = 0), both leave at 2 * 6 / 3 = 4 m/s.
    Row row{World(withHolding(true)), {}, {}};
    buildRow(row);
    const BodyId target = row.boxes.back();
    for (int step = 0; step < 90; ++step) row.world.step(kDt);
    EXPECT_EQ(row.world.stats().heldBodies, kBoxes - 1);  // the target is held
    row.world.setMaterial(target, [] {
        Material m;
        m.friction = 0;
        return m;
    }());
    BodySettings ball;
    ball.shape = Shape::sphere(0.5);
    ball.mass = 2;
    ball.position = Vector3(kBoxes - 1, 0.5, 2.5);
    ball.velocity = Vector3(0, 0, -6);
    ball.material.friction = 0;
    const BodyId hitter = row.world.addBody(ball);
    for (int step = 0; step < 30; ++step) row.world.step(kDt);  // the ball arrives after 1.5 / 6 = 0.25 s
    const Vector3 v = row.world.body(target).getVelocity();
    EXPECT_NEAR(v.z(), -4, 0.04);
    EXPECT_NEAR(row.world.body(hitter).getVelocity().z(), -4, 0.04);
    EXPECT_LT(std::abs(v.x()), 0.01);
    // The box it slid away from kept its place, within the contact's last push-out.
    EXPECT_NEAR(row.world.body(row.boxes[kBoxes - 2]).getPosition().x(), kBoxes - 2, 1e-3);
}

// A frictionless row of `count` 1 kg unit boxes along x from x = 0 on a frictionless
// ground, and a 0.1 kg box that may not sleep on the first (it keeps the island awake):
// the row's boxes, then the small box.
std::vector<BodyId> addFrictionlessRow(World &world, int count) {
    addGround(world, 0);
    std::vector<BodyId> bodies;
    for (int i = 0; i < count; ++i) {
        BodySettings b;
        b.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        b.position = Vector3(i, 0.5, 0);
        b.material.friction = 0;
        bodies.push_back(world.addBody(b));
    }
    BodySettings awake;
    awake.shape = Shape::box(Vector3(0.1, 0.1, 0.1));
    awake.position = Vector3(0, 1.1, 0);
    awake.mass = 0.1;
    awake.canSleep = false;
    awake.material.friction = 0;
    bodies.push_back(world.addBody(awake));
    return bodies;
}

// A frictionless 2 kg ball of radius 0.5 m on the ground at x, at 6 m/s along -x.
BodyId throwBall(World &world, real x) {
    BodySettings ball;
    ball.shape = Shape::sphere(0.5);
    ball.mass = 2;
    ball.position = Vector3(x, 0.5, 0);
    ball.velocity = Vector3(-6, 0, 0);
    ball.material.friction = 0;
    return world.addBody(ball);
}

TEST(HeldBodies, ABallIntoAHeldRowMovesTheWholeRowAndKeepsMomentum) {
    // Ten boxes in the row, and the ball into the far end. Nothing outside holds the
    // bodies along x, so their momentum, 2 kg at 6 m/s, 12 kg m/s, stays (the small box's
    // share included: it may fall off the first box and meet it), and every box of the
    // row is pushed along -x. A held box that stood as a wall threw the ball back
    // (+1.5 kg m/s without the hit rule).
    World world(withHolding(true));
    std::vector<BodyId> bodies = addFrictionlessRow(world, kBoxes);
    for (int step = 0; step < 90; ++step) world.step(kDt);
    EXPECT_EQ(world.stats().heldBodies, kBoxes - 1);  // boxes 1-9: box 0 touches the small box
    bodies.push_back(throwBall(world, kBoxes + 1));
    for (int step = 0; step < 30; ++step) world.step(kDt);  // it arrives after 1 / 6 s
    real momentum = 0;
    for (const BodyId &b : bodies) momentum += world.body(b).getMass() * world.body(b).getVelocity().x();
    EXPECT_NEAR(momentum, -12, 0.012);
    for (int i = 0; i < kBoxes; ++i) EXPECT_LT(world.body(bodies[i]).getVelocity().x(), -0.1);
}

// The frictionless row of `count` boxes on `threads` threads; after 90 steps (boxes 1 to
// count - 1 held) the ball comes into its far end. Keeps the held counts of the 30 steps
// after the ball is added and every body's state at the end.
struct LongRowHit {
    std::vector<int> held;
    std::vector<RigidBody> end;
};

LongRowHit hitLongRow(int count, int threads) {
    WorldSettings settings = withHolding(true);
    settings.threads = threads;
    World world(settings);
    std::vector<BodyId> bodies = addFrictionlessRow(world, count);
    for (int step = 0; step < 90; ++step) world.step(kDt);
    LongRowHit out;
    out.held.push_back(world.stats().heldBodies);
    bodies.push_back(throwBall(world, count + 0.5));
    for (int step = 0; step < 30; ++step) {
        world.step(kDt);
        out.held.push_back(world.stats().heldBodies);
    }
    for (const BodyId &b : bodies) out.end.push_back(world.body(b));
    return out;
}

TEST(HeldBodies, AHitOnALongHeldRowFreesItWholeInOneStepOnOneThreadOrTwo) {
    // 300 boxes: the hit's flood goes 299 rings deep and its rings span several chunks
    // of the threads' work (Workers::kChunk = 64). The ball's contact closes at 6 m/s,
    // past kHitSpeed, in the step it first touches: every box touches the next, so all
    // are freed in that one step. (Spread over the row, the ball's 12 kg m/s leaves the
    // boxes at 4 cm/s, under the sleep threshold: they are held again later, as they
    // would fall asleep.)
    const int count = 300;
    const LongRowHit one = hitLongRow(count, 1);
    ASSERT_EQ(one.held.front(), count - 1);  // all but the first, which the small box keeps solved
    const auto freed = std::find(one.held.begin(), one.held.end(), 0);
    ASSERT_NE(freed, one.held.end()) << "the row was never freed";
    for (auto it = one.held.begin(); it != freed; ++it) EXPECT_EQ(*it, count - 1) << "freed in part first";
    const LongRowHit two = hitLongRow(count, 2);
    EXPECT_EQ(one.held, two.held);
    ASSERT_EQ(one.end.size(), two.end.size());
    for (std::size_t k = 0; k < one.end.size(); ++k) EXPECT_TRUE(sameBits(one.end[k], two.end[k])) << "body " << k;
}

TEST(HeldBodies, APlankLeftOverAnEdgeWhenItsSupportIsRemovedFalls) {
    // A plank 1.2 m long across boxes 6 and 7 (x from 6.2 to 7.4, short of box 8 at
    // 7.5), its centre 0.3 m past box 6's far edge (x = 6.5): held with the far boxes
    // while the ball spins. Box 7 removed, only box 6 is under it and its centre of mass
    // overhangs: it must tip into the gap, not stay held in the air. World::removeBody wakes the bodies that touched the removed one, and a woken
    // held body is solved for about a second, as a woken sleeping one.
    Row row{World(withHolding(true)), {}, {}};
    buildRow(row);
    BodySettings plank;
    plank.shape = Shape::box(Vector3(0.6, 0.1, 0.4));
    plank.position = Vector3(6.8, 1.1, 0);
    const BodyId id = row.world.addBody(plank);
    for (int step = 0; step < 100; ++step) row.world.step(kDt);
    ASSERT_EQ(row.world.stats().heldBodies, kBoxes - 1 + 1);
    const real before = row.world.body(id).getPosition().y();
    row.world.removeBody(row.boxes[7]);
    for (int step = 0; step < 90; ++step) row.world.step(kDt);
    // Turned about the edge at x = 6.5 to upright, its centre (0.3 m out) is 0.3 m lower
    // than it was less the plank's half-thickness; in the 1 m gap it then slides on down.
    EXPECT_LT(row.world.body(id).getPosition().y(), before - 0.3);
}

TEST(HeldBodies, StepsAfterARestoreRepeatTheFirstRunWhileBodiesAreHeld) {
    // Which bodies are held follows from the saved state (velocities, sleep averages, the
    // step each manifold was last solved in): the steps after a restore repeat the first
    // run bit for bit, through the ball's stop and the island's sleep.
    Row row{World(withHolding(true)), {}, {}};
    buildRow(row);
    for (int step = 0; step < 100; ++step) row.world.step(kDt);
    ASSERT_EQ(row.world.stats().heldBodies, kBoxes - 1);
    const std::vector<std::uint8_t> saved = row.world.saveState();
    const std::vector<std::vector<RigidBody>> first = stepRecording(row, 0, 240);
    row.world.restoreState(saved);
    expectRepeats(row, 240, first);
}

TEST(HeldBodies, AWakeCallRightAfterARestoreActsAsAtTheSavedStep) {
    // setAwake on a held box gives it a sleeping body's waking sleep average (twice the
    // threshold), so it is solved again for about a second. Called right after a restore,
    // it must act on the saved state's held boxes, not on the run's latest: the steps
    // after it repeat a run that made the call at the saved step, bit for bit.
    Row row{World(withHolding(true)), {}, {}};
    buildRow(row);
    for (int step = 0; step < 100; ++step) row.world.step(kDt);
    ASSERT_EQ(row.world.stats().heldBodies, kBoxes - 1);
    const std::vector<std::uint8_t> saved = row.world.saveState();
    const BodyId box = row.boxes[5];
    row.world.setAwake(box, true);
    row.world.step(kDt);
    // Box 5 is solved again, and so are boxes 4 and 6, which touch it: 1-3 and 7-9 held.
    EXPECT_EQ(row.world.stats().heldBodies, 6);
    const std::vector<std::vector<RigidBody>> first = stepRecording(row, 1, 480);
    ASSERT_FALSE(row.world.body(box).getAwake());  // slept, so no box is held now
    row.world.restoreState(saved);
    row.world.setAwake(box, true);
    expectRepeats(row, 480, first);
}

}  // namespace
}  // namespace cyclone::test
