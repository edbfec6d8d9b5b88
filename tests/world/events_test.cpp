// Events: contact begin / end and sleep / wake, read after a step.
#include <algorithm>
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


int count(const std::vector<BodyId> &ids, BodyId id) {
    return static_cast<int>(std::count(ids.begin(), ids.end(), id));
}

// A ball of radius 0.5 with its bottom 1 m above the ground falls in sub-steps of
// h = 1/240 s: after N sub-steps its bottom is at 1 - g h^2 N (N + 1) / 2 and its speed
// g h N. After step 26 (N = 104) the gap is 1 - g h^2 5460 = 70.094 mm and the speed
// 4.2510 m/s, which covers 70.85 mm in step 27: step 27's narrowphase gives the pair a
// speculative contact, and its begin is in step 27's events, the depth negative (the gap)
// and the approach speed the ball's speed then. After step 25 (N = 100) the gap is
// 139.8 mm against 4.0875 / 60 = 68.1 mm of reach: no contact yet.
TEST(Events, ContactBeginsOnTheStepThatCanCloseTheGap) {
    WorldFixture f;
    const BodyId ground = f.ground();
    const BodyId ball = f.sphere(Vector3(0, 1.5, 0));
    for (int step = 1; step <= 26; ++step) {
        f.world.step(kDt);
        ASSERT_TRUE(f.world.events().contactBegins.empty()) << "step " << step;
    }
    f.world.step(kDt);
    const std::vector<ContactBegin> &begins = f.world.events().contactBegins;
    ASSERT_EQ(begins.size(), 1u);
    const ContactBegin &b = begins[0];
    EXPECT_EQ(b.a, ground);  // the smaller index
    EXPECT_EQ(b.b, ball);
    EXPECT_NEAR(b.normal.y(), 1, 1e-9);  // from the ground towards the ball
    const double h = kDt / 4;
    const double depth = kG * h * h * 104 * 105 / 2 - 1;  // -70.094 mm: apart
    EXPECT_NEAR(b.depth, depth, 1e-9);
    EXPECT_NEAR(b.point.x(), 0, 1e-9);
    EXPECT_NEAR(b.point.y(), -depth / 2, 1e-9);  // midway between the two surfaces
    EXPECT_NEAR(b.point.z(), 0, 1e-9);
    EXPECT_NEAR(b.approachSpeed, kG * h * 104, 1e-9);
    EXPECT_TRUE(f.world.events().contactEnds.empty());
}

// A box landing flat and resting: one begin, then nothing while it rests and sleeps
// (its sleep average, high from the fall, takes some 3.5 s to halve down to the
// threshold).
TEST(Events, RestingContactReportsOneBeginAndNoFlicker) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.75, 0));
    int begins = 0, ends = 0;
    for (int i = 0; i < 300; ++i) {
        f.world.step(kDt);
        begins += static_cast<int>(f.world.events().contactBegins.size());
        ends += static_cast<int>(f.world.events().contactEnds.size());
    }
    EXPECT_FALSE(f.awake(box));
    EXPECT_EQ(begins, 1);
    EXPECT_EQ(ends, 0);
}

// Thrown up at 5 m/s from rest, the ball's first step lifts it 5/60 - g/240 * (4/60) m
// ~ 8 cm: beyond the plane's 2 cm reach, so the next step's broadphase drops the pair
// and the contact ends.
TEST(Events, ContactEndsWhenBodiesSeparate) {
    WorldFixture f;
    const BodyId ground = f.ground();
    const BodyId ball = f.sphere(Vector3(0, 0.5, 0));
    f.simulate(2);
    ASSERT_FALSE(f.awake(ball));
    f.world.setVelocity(ball, Vector3(0, 5, 0));
    f.world.step(kDt);
    EXPECT_EQ(count(f.world.events().wokeUp, ball), 1);
    EXPECT_TRUE(f.world.events().contactEnds.empty());  // this step's narrowphase still saw the contact
    f.world.step(kDt);
    const std::vector<ContactEnd> &ends = f.world.events().contactEnds;
    ASSERT_EQ(ends.size(), 1u);
    EXPECT_EQ(ends[0].a, ground);
    EXPECT_EQ(ends[0].b, ball);
    f.world.step(kDt);
    EXPECT_TRUE(f.world.events().contactEnds.empty());  // reported once
}

TEST(Events, RemovingABodyEndsItsContacts) {
    WorldFixture f;
    const BodyId ground = f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(0.5);
    f.world.removeBody(box);
    f.world.step(kDt);
    const std::vector<ContactEnd> &ends = f.world.events().contactEnds;
    ASSERT_EQ(ends.size(), 1u);
    EXPECT_EQ(ends[0].a, ground);
    EXPECT_EQ(ends[0].b, box);
    EXPECT_FALSE(f.world.contains(ends[0].b));  // the handle of the removed body
}

// A box removed and another added in its place between two steps: the new pair takes the
// freed pair slot, touching as the old one was. The old contact ends and the new one
// begins, though the slot's touching state is the same before and after.
TEST(Events, ABodyReplacedInPlaceEndsOneContactAndBeginsAnother) {
    WorldFixture f;
    const BodyId ground = f.ground();
    const BodyId first = f.box(Vector3(0, 0.5, 0));
    f.simulate(0.5);
    f.world.removeBody(first);
    const BodyId second = f.box(Vector3(0, 0.5, 0));
    f.world.step(kDt);
    const WorldEvents &events = f.world.events();
    ASSERT_EQ(events.contactEnds.size(), 1u);
    EXPECT_EQ(events.contactEnds[0].a, ground);
    EXPECT_EQ(events.contactEnds[0].b, first);
    ASSERT_EQ(events.contactBegins.size(), 1u);
    EXPECT_EQ(events.contactBegins[0].a, ground);
    EXPECT_EQ(events.contactBegins[0].b, second);
}

// A body at rest falls asleep about one second after it stops (sleep_test.cpp); the
// event comes once, in the step that put it to sleep.
TEST(Events, FallingAsleepIsReportedOnce) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    int reports = 0;
    bool wasAwake = true;
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        const int now = count(f.world.events().fellAsleep, box);
        reports += now;
        EXPECT_EQ(now == 1, wasAwake && !f.awake(box)) << "step " << i + 1;
        wasAwake = f.awake(box);
    }
    EXPECT_EQ(reports, 1);
    EXPECT_FALSE(f.awake(box));
}

// Calls between steps report in the next step's events: those of the last step stay
// readable until then.
TEST(Events, CallsBetweenStepsReportInTheNextStep) {
    WorldFixture f;
    f.ground();
    const BodyId a = f.box(Vector3(0, 0.5, 0));
    const BodyId b = f.box(Vector3(5, 0.5, 0));
    f.world.step(kDt);
    f.world.setAwake(a, false);
    EXPECT_TRUE(f.world.events().fellAsleep.empty());
    f.world.step(kDt);
    EXPECT_EQ(f.world.events().fellAsleep, std::vector<BodyId>{a});
    f.world.applyImpulse(a, Vector3(0, 0.1, 0));
    f.world.setAwake(b, false);
    f.world.step(kDt);
    EXPECT_EQ(f.world.events().wokeUp, std::vector<BodyId>{a});
    EXPECT_EQ(f.world.events().fellAsleep, std::vector<BodyId>{b});
    f.world.step(kDt);
    EXPECT_TRUE(f.world.events().wokeUp.empty());
    EXPECT_TRUE(f.world.events().fellAsleep.empty());
}

TEST(Events, BodyAddedAsleepIsNotReported) {
    WorldFixture f;
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = Vector3(0, 3, 0);
    s.awake = false;
    f.world.addBody(s);
    f.world.step(kDt);
    EXPECT_TRUE(f.world.events().fellAsleep.empty());
    EXPECT_TRUE(f.world.events().wokeUp.empty());
}

// A sleeping stack hit by an awake ball wakes as one island: every member reported once.
TEST(Events, TouchWakesTheWholeIsland) {
    WorldFixture f;
    f.ground();
    const BodyId bottom = f.box(Vector3(0, 0.5, 0));
    const BodyId top = f.box(Vector3(0, 1.5, 0));
    f.simulate(3);
    ASSERT_FALSE(f.awake(bottom));
    ASSERT_FALSE(f.awake(top));
    const BodyId ball = f.sphere(Vector3(0, 3.0, 0), 0.25);
    std::vector<BodyId> woken;
    int ballBegins = 0;
    for (int i = 0; i < 60; ++i) {
        f.world.step(kDt);
        const WorldEvents &e = f.world.events();
        woken.insert(woken.end(), e.wokeUp.begin(), e.wokeUp.end());
        for (const ContactBegin &c : e.contactBegins) ballBegins += (c.a == ball || c.b == ball) ? 1 : 0;
    }
    EXPECT_EQ(count(woken, bottom), 1);
    EXPECT_EQ(count(woken, top), 1);
    EXPECT_EQ(count(woken, ball), 0);  // awake from the start
    EXPECT_GE(ballBegins, 1);
}

TEST(Events, EmptyBeforeTheFirstStepAndInAQuietStep) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    EXPECT_TRUE(f.world.events().contactBegins.empty());
    f.simulate(3);
    ASSERT_FALSE(f.awake(box));
    f.world.step(kDt);
    const WorldEvents &e = f.world.events();
    EXPECT_TRUE(e.contactBegins.empty() && e.contactEnds.empty() && e.fellAsleep.empty() && e.wokeUp.empty());
}

}  // namespace
}  // namespace cyclone::test
