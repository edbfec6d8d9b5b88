// The landing correction (contacts/landing.h): after the step's integration, pairs with a
// body that moved fast are tested again at the step's end poses and points deeper than
// the tolerance are pushed apart by position only.
//
// The numbers. A 1 m box has bounding radius sqrt(3) / 2 = 0.866 m; a tenth of it is
// more than 5 mm, so a pair of such boxes (or one and the ground) has the tolerance
// kLandingDepth = 5 mm, and a point deeper than that is pushed back to half of it,
// 2.5 mm. Speculative contacts are switched off in the landing tests and the speculative
// distance set to 1 mm, so that the step's contacts miss the impact entirely (a box found
// 1 cm above what it lands on gets no contact) and the overlap the step makes, v dt less
// the gap (14 / 60 - 0.01 = 223 mm at 14 m/s), is the correction's alone to remove. The
// pair is still a candidate: the broadphase's boxes are grown by 2 cm (kBroadphaseMargin),
// and the correction tests only the step's candidate pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr real kTolerance = 0.005;  // a unit box's pairs (above)
constexpr real kTarget = 0.5 * kTolerance;

WorldSettings withoutSpeculative(bool landing) {
    WorldSettings s = noSleep();
    s.debug.speculativeContacts = false;
    s.speculativeDistance = 0.001;
    s.debug.landingCorrection = landing;
    return s;
}

// How far the unit box at `upper` reaches down into the unit box at `lower` (both axis
// aligned, one above the other): the lower's top less the upper's bottom.
real overlap(const World &world, BodyId lower, BodyId upper) {
    return (world.body(lower).getPosition().y() + 0.5) - (world.body(upper).getPosition().y() - 0.5);
}

TEST(LandingCorrection, OnByDefault) { EXPECT_TRUE(WorldSettings().debug.landingCorrection); }

// No gravity, a box at 14 m/s towards a static box, its bottom 1 cm above the static
// box's top: the step moves it 233 mm, 223 mm into the static box, with no contact. The
// correction moves the dynamic box alone (the static one is immovable) back along the
// face normal (+y), by translation only: the first of its four face points (all equally
// deep) takes it back to kTarget, and the other three are then no deeper. The overlap is
// kTarget to rounding, and the velocity the one it had.
TEST(LandingCorrection, BoxThroughAStaticBoxIsPushedBackToHalfTheTolerance) {
    for (const bool landing : {true, false}) {
        WorldSettings settings = withoutSpeculative(landing);
        settings.gravity = Vector3::Zero();
        WorldFixture f(settings);
        const BodyId base = f.staticBox(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5));
        const BodyId box = f.box(Vector3(0, 1.51, 0));
        f.world.setVelocity(box, Vector3(0, -14, 0));
        f.world.step(kDt);
        if (landing) {
            EXPECT_NEAR(overlap(f.world, base, box), kTarget, 1e-9);
            EXPECT_EQ(f.world.body(box).getVelocity(), Vector3(0, -14, 0));
            EXPECT_EQ(f.world.stats().landingPushes, 1);
        } else {
            EXPECT_NEAR(overlap(f.world, base, box), 14 * kDt - 0.01, 1e-9);
        }
    }
}

// A box lands at 14 m/s on a box that is itself landing on the ground at 7 m/s, each 1 cm
// above what it lands on. In the first step the lower box goes 117 - 10 = 107 mm into
// the ground and the upper one 233 - 117 - 10 = 107 mm into the lower one. The passes go
// lowest first and split each push between two dynamic bodies by their inverse masses
// (equal here): the lower box is pushed out of the ground, then half the upper pair's
// excess back into it, which the next pass takes out again, so the excess halves each
// pass; eight passes leave 1/256 of 0.21 m, under a millimetre above the 2.5 mm target,
// and a second round tests the moved bodies' pairs again. Every overlap after every step:
// at most the tolerance. Without the correction both end the first step about 0.1 m
// deep.
TEST(LandingCorrection, BoxLandingOnALandingBoxIsNeverLeftDeeperThanTheTolerance) {
    real deepest[2] = {0, 0};
    for (const bool landing : {true, false}) {
        WorldFixture f(withoutSpeculative(landing));
        f.ground();
        const BodyId lower = f.box(Vector3(0, 0.51, 0));
        const BodyId upper = f.box(Vector3(0, 1.02 + 0.5, 0));
        f.world.setVelocity(lower, Vector3(0, -7, 0));
        f.world.setVelocity(upper, Vector3(0, -14, 0));
        for (int i = 0; i < 60; ++i) {
            f.world.step(kDt);
            const real intoGround = 0.5 - f.position(lower).y();
            deepest[landing] = std::max({deepest[landing], intoGround, overlap(f.world, lower, upper)});
            if (landing) {
                ASSERT_LE(intoGround, kTolerance) << "after step " << i + 1;
                ASSERT_LE(overlap(f.world, lower, upper), kTolerance) << "after step " << i + 1;
            }
        }
    }
    EXPECT_GT(deepest[false], 0.09);  // what the test would see without the correction
}

// The same with boxes of half extent 0.1 m: bounding radius 0.173 m, tolerance still
// 5 mm, and a body's pushes in a round may move it at most a quarter of its radius,
// 43 mm, before it may be pushed down no more. The step takes the lower box 108 mm into
// the ground and the upper 107 mm into the lower; the first pass pushes the lower box
// 106 mm up, past that budget, so the upper pair, then 213 mm deep, is the upper box's
// alone to undo (given only the lower box's share, nothing, it was left 0.3 m into the
// lower box). After every step both overlaps are within the tolerance.
TEST(LandingCorrection, UpperBoxTakesThePushALowerBoxCanNoLongerTake) {
    WorldFixture f(withoutSpeculative(true));
    f.ground();
    const Vector3 half(0.1, 0.1, 0.1);
    const BodyId lower = f.box(Vector3(0, 0.11, 0), half);
    const BodyId upper = f.box(Vector3(0, 0.32, 0), half);
    f.world.setVelocity(lower, Vector3(0, -7, 0));
    f.world.setVelocity(upper, Vector3(0, -14, 0));
    for (int i = 0; i < 60; ++i) {
        f.world.step(kDt);
        const real intoGround = 0.1 - f.position(lower).y();
        const real intoLower = (f.position(lower).y() + 0.1) - (f.position(upper).y() - 0.1);
        ASSERT_LE(intoGround, kTolerance) << "after step " << i + 1;
        ASSERT_LE(intoLower, kTolerance) << "after step " << i + 1;
    }
}

// A box lands at 14 m/s on a box resting on the ground, 1 cm above it: the step takes
// it 233 - 10 = 223 mm into the resting box, which hardly moved in the step (it rests)
// and so made none of the overlap. The correction pushes the landing box alone back to
// kTarget, taking from its speed the energy of the lift (it touched no other movable body
// in the step: speculative contacts are off here); the resting box ends the step exactly
// where a box alone on the ground does.
// (Split by their inverse masses, the resting box was pushed 110 mm down into the
// ground, whose pair with it the correction had not tested: it moved less than half the
// tolerance. In mixed1000 piles such pushes left boxes 9-30 mm deep in the ground.)
TEST(LandingCorrection, RestingBoxUnderALandingBoxIsNotPushed) {
    WorldFixture f(withoutSpeculative(true));
    WorldFixture alone(withoutSpeculative(true));
    f.ground();
    alone.ground();
    const BodyId resting = f.box(Vector3(0, 0.5, 0));
    const BodyId reference = alone.box(Vector3(0, 0.5, 0));
    const BodyId landing = f.box(Vector3(0, 1.51, 0));
    f.world.setVelocity(landing, Vector3(0, -14, 0));
    f.world.step(kDt);
    alone.world.step(kDt);
    EXPECT_TRUE(sameBits(f.world.body(resting), alone.world.body(reference)));
    // The overlap from the centres: the resting box's contact with the ground leaves it
    // turned by rounding, which the face points' depths see and the centres do not.
    EXPECT_NEAR(overlap(f.world, resting, landing), kTarget, 1e-6);
    // The push lifted the box by `lift` from where the step took it (the same box falling
    // alone, with the World's damping): it pays m g lift out of its downward speed v,
    // v^2 - 2 g lift = v'^2, and keeps the rest.
    WorldFixture free(withoutSpeculative(true));
    const BodyId falling = free.box(Vector3(0, 1.51, 0));
    free.world.setVelocity(falling, Vector3(0, -14, 0));
    free.world.step(kDt);
    const real speed = -free.world.body(falling).getVelocity().y();
    const real lift = f.world.body(landing).getPosition().y() - free.world.body(falling).getPosition().y();
    EXPECT_GT(lift, 0.2);
    EXPECT_NEAR(f.world.body(landing).getVelocity().y(), -std::sqrt(speed * speed - 2 * kG * lift), 1e-9);
}

// Two boxes at rest, the upper placed 12 mm into the lower, which rests on the ground:
// neither moves fast (the penetration recovery set to 1 % a sub-step, the solver takes
// at most 4 % of the depth out in the step, 0.5 mm), but the pair begins the step deeper
// than 1.6 tolerances (8 mm), so the
// correction tests both bodies' pairs, the ground's too, and pushes the pair back to
// within the tolerance, leaving the lower box no deeper than that in the ground. Placed
// 7 mm deep (under 8 mm) the pair is the solver's alone: nothing is tested.
TEST(LandingCorrection, PairSunkWhileRestingIsPushedOutOnlyBeyondOnePointSixTolerances) {
    for (const real placed : {0.012, 0.007}) {
        SCOPED_TRACE(placed);
        for (const bool landing : {true, false}) {
            WorldSettings settings = noSleep();
            settings.debug.landingCorrection = landing;
            settings.penetrationRecovery = 0.01;
            WorldFixture f(settings);
            f.ground();
            const BodyId lower = f.box(Vector3(0, 0.5, 0));
            const BodyId upper = f.box(Vector3(0, 1.5 - placed, 0));
            f.world.step(kDt);
            const real depth = overlap(f.world, lower, upper);
            if (!landing) {
                EXPECT_GT(depth, 0.95 * placed);  // the solver alone
            } else if (placed > 1.6 * kTolerance) {
                EXPECT_GT(f.world.stats().landingPairs, 0);
                EXPECT_LE(depth, kTolerance);
                EXPECT_LE(0.5 - f.position(lower).y(), kTolerance);
            } else {
                EXPECT_EQ(f.world.stats().landingPairs, 0);
                EXPECT_GT(depth, 0.95 * placed);
            }
        }
    }
}

// A column sunk under its load: the lower box placed 9 mm into the ground (beyond 1.6
// tolerances, so it is pushed), the upper placed 6 mm into it (under 8 mm: not pushed
// for its own sake), neither moving (the recovery at 1 %, as above). The ground pushes
// the lower box up, out to 2.5 mm, which takes it 6.5 mm further into the upper box; the
// upper box must then be lifted, not the lower driven back into the ground (the passes
// ended with it 12.5 mm deep, under the still upper box). After the step both pairs are
// within the tolerance and the upper box still rests on the lower (they overlap).
TEST(LandingCorrection, BoxOnASunkBoxIsLiftedWithIt) {
    WorldSettings settings = noSleep();
    settings.penetrationRecovery = 0.01;
    WorldFixture f(settings);
    f.ground();
    const BodyId lower = f.box(Vector3(0, 0.5 - 0.009, 0));
    const BodyId upper = f.box(Vector3(0, 1.5 - 0.009 - 0.006, 0));
    f.world.step(kDt);
    EXPECT_GT(f.world.stats().landingPushes, 0);
    EXPECT_LE(0.5 - f.position(lower).y(), kTolerance);
    const real depth = overlap(f.world, lower, upper);
    EXPECT_LE(depth, kTolerance);
    EXPECT_GT(depth, 0);
    EXPECT_GT(f.position(upper).y(), 1.5 - 0.009 - 0.006);
}

// A sleeping body is immovable for the step that wakes it: the landing box alone is
// pushed back out of it.
TEST(LandingCorrection, SleepingBodyIsNotMoved) {
    WorldSettings settings = withoutSpeculative(true);
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = Vector3(0, 0.5, 0);
    s.awake = false;
    const BodyId sleeping = f.world.addBody(s);
    const BodyId box = f.box(Vector3(0, 1.51, 0));
    f.world.setVelocity(box, Vector3(0, -14, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.position(sleeping), Vector3(0, 0.5, 0));
    EXPECT_NEAR(overlap(f.world, sleeping, box), kTarget, 1e-9);
}

// A ball flying at 14 m/s 1 cm above a box is tested again each step (it moves
// fast) but is 1 cm apart: nothing is pushed, and the run is the same to the bit as
// without the correction.
TEST(LandingCorrection, BallPassingCloseByIsNotMoved) {
    // No gravity: the ball stays 1 cm above the box's top as it passes.
    WorldSettings onSettings = noSleep();
    onSettings.gravity = Vector3::Zero();
    WorldSettings offSettings = onSettings;
    offSettings.debug.landingCorrection = false;
    WorldFixture on(onSettings), off(offSettings);
    BodyId ids[2][3];
    WorldFixture *worlds[2] = {&on, &off};
    for (int w = 0; w < 2; ++w) {
        WorldFixture &f = *worlds[w];
        ids[w][0] = f.ground();
        ids[w][1] = f.box(Vector3(0, 0.5, 0));
        BodySettings ball;
        ball.shape = Shape::sphere(0.25);
        ball.position = Vector3(-3, 1 + 0.01 + 0.25, 0);
        ball.velocity = Vector3(14, 0, 0);
        ids[w][2] = f.world.addBody(ball);
    }
    int tested = 0;
    for (int i = 0; i < 30; ++i) {
        on.world.step(kDt);
        off.world.step(kDt);
        tested += on.world.stats().landingPairs;
        EXPECT_EQ(on.world.stats().landingPushes, 0);
        for (int k = 1; k < 3; ++k)
            ASSERT_TRUE(sameBits(on.world.body(ids[0][k]), off.world.body(ids[1][k]))) << "step " << i + 1;
    }
    EXPECT_GT(tested, 0);  // the ball's pair with the box was tested, and left alone
}

// A resting stack moves less than half the tolerance a step: nothing is tested, and the
// run is the same to the bit as without the correction.
// Two unit boxes held side by side by a fixed joint (1 kg each, centres 1.2 m apart),
// moving at 14 m/s, without gravity, towards a static box under the first only, 1 cm
// above it: the step takes the first 223 mm into it.
struct JointedBoxes {
    WorldFixture f;
    BodyId base, first, second;
    explicit JointedBoxes(bool landing) : f(withoutGravity(landing)) {
        base = f.staticBox(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5));
        first = f.box(Vector3(0, 1.51, 0));
        second = f.box(Vector3(1.2, 1.51, 0));
        f.joint(JointType::Fixed, first, second, Vector3(0.6, 1.51, 0));
    }
    void step() {
        for (const BodyId id : {first, second}) f.world.setVelocity(id, Vector3(0, -14, 0));
        f.world.step(kDt);
    }
    static WorldSettings withoutGravity(bool landing) {
        WorldSettings s = withoutSpeculative(landing);
        s.gravity = Vector3::Zero();
        return s;
    }
};

// The joint's bodies move as one group: the push takes the group's mass (2 kg) against
// the immovable static box, so the first box goes back to kTarget as a box alone would,
// and the second moves by the same translation, so that the joint stays as closed as
// without the correction. Velocities are left alone. (Before joint groups, a jointed body
// was never moved: 223 mm deep.)
TEST(LandingCorrection, JointGroupIsPushedOutAsOne) {
    Vector3 between[2];
    for (const bool landing : {true, false}) {
        JointedBoxes boxes(landing);
        boxes.step();
        const World &world = boxes.f.world;
        between[landing] = boxes.f.position(boxes.second) - boxes.f.position(boxes.first);
        if (landing) {
            EXPECT_NEAR(overlap(world, boxes.base, boxes.first), kTarget, 1e-9);
            EXPECT_EQ(world.stats().landingPushes, 1);
            for (const BodyId id : {boxes.first, boxes.second})
                EXPECT_NEAR((world.body(id).getVelocity() - Vector3(0, -14, 0)).norm(), 0, 1e-9);
        } else {
            EXPECT_NEAR(overlap(world, boxes.base, boxes.first), 14 * kDt - 0.01, 1e-9);
        }
    }
    EXPECT_NEAR((between[true] - between[false]).norm(), 0, 1e-12);
}

// The same boxes, the second also tied to the world by a slack rope (a distance joint of
// up to 100 m, which never pulls here): a push would drag the world's anchor along, so
// the group does not move and the first box stays where the step left it.
TEST(LandingCorrection, JointGroupHeldByTheWorldIsNotMoved) {
    JointedBoxes boxes(true);
    JointSettings rope;
    rope.type = JointType::Distance;
    rope.a = boxes.second;
    rope.anchor = Vector3(1.2, 1.51, 0);
    rope.anchorB = Vector3(1.2, 10, 0);
    rope.minDistance = 0;
    rope.maxDistance = 100;
    boxes.f.world.addJoint(rope);
    boxes.step();
    EXPECT_NEAR(overlap(boxes.f.world, boxes.base, boxes.first), 14 * kDt - 0.01, 1e-9);
    EXPECT_EQ(boxes.f.world.stats().landingPushes, 0);
}

TEST(LandingCorrection, RestingStackIsUntouchedToTheBit) {
    WorldFixture on(noSleep());
    WorldSettings offSettings = noSleep();
    offSettings.debug.landingCorrection = false;
    WorldFixture off(offSettings);
    BodyId ids[2][4];
    WorldFixture *worlds[2] = {&on, &off};
    for (int w = 0; w < 2; ++w) {
        ids[w][0] = worlds[w]->ground();
        for (int k = 1; k < 4; ++k) ids[w][k] = worlds[w]->box(Vector3(0.01 * k, 0.5 + (k - 1), 0));
    }
    for (int i = 0; i < 240; ++i) {
        on.world.step(kDt);
        off.world.step(kDt);
        EXPECT_EQ(on.world.stats().landingPairs, 0);
        for (int k = 1; k < 4; ++k)
            ASSERT_TRUE(sameBits(on.world.body(ids[0][k]), off.world.body(ids[1][k]))) << "step " << i + 1;
    }
}

}  // namespace
}  // namespace cyclone::test
