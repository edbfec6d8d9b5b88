// Sleep and wake of islands (after Jolt's TestPhysicsActivationDeactivation).
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A body at rest is woken with a sleep average of 2 eps, which halves every second
// (b = 0.5^t) while v.v + w.w stays ~0: it crosses eps at t = 1 s.
TEST(Sleep, BodyAtRestSleepsAfterAboutOneSecond) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(0.9);
    EXPECT_TRUE(f.awake(box));
    f.simulate(0.35);
    EXPECT_FALSE(f.awake(box));
    EXPECT_EQ(f.world.stats().awakeBodies, 0);
}

TEST(Sleep, RestingOnStaticBoxDoesNotKeepAwake) {
    WorldFixture f;
    f.staticBox(Vector3(0, -0.5, 0), Vector3(3, 0.5, 3));
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(1.5);
    EXPECT_FALSE(f.awake(box));
}

// Thrown up at 10 m/s the ball stops at the apex (t = 1.02 s); the sleep average, which
// remembers the last second or so of speed, stays far above the threshold there.
TEST(Sleep, DoesNotSleepAtTopOfVerticalThrow) {
    WorldFixture f;
    const BodyId ball = f.sphere(Vector3(0, 100, 0), 0.2);
    f.world.setVelocity(ball, Vector3(0, 10, 0));
    for (int i = 0; i < 150; ++i) {
        f.world.step(kDt);
        ASSERT_TRUE(f.awake(ball)) << "fell asleep at t = " << (i + 1) * kDt;
    }
}

TEST(Sleep, CanSleepFalseNeverSleeps) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.world.setCanSleep(box, false);
    f.simulate(5);
    EXPECT_TRUE(f.awake(box));
}

TEST(Sleep, SleepOffInSettingsNeverSleeps) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(5);
    EXPECT_TRUE(f.awake(box));
}

// An island sleeps only when all of it may: a box resting on a box that must stay awake
// stays awake too, while an unrelated box nearby sleeps.
TEST(Sleep, IslandSleepsTogether) {
    WorldFixture f;
    f.ground();
    const BodyId bottom = f.box(Vector3(0, 0.5, 0));
    const BodyId top = f.box(Vector3(0, 1.5, 0));
    const BodyId alone = f.box(Vector3(5, 0.5, 0));
    f.world.setCanSleep(bottom, false);
    f.simulate(3);
    EXPECT_TRUE(f.awake(bottom));
    EXPECT_TRUE(f.awake(top));
    EXPECT_FALSE(f.awake(alone));
}

TEST(Sleep, SleepingBodiesAreNotIntegratedNorTested) {
    WorldFixture f;
    f.ground();
    const BodyId a = f.box(Vector3(0, 0.5, 0));
    const BodyId b = f.box(Vector3(0, 1.5, 0));
    f.simulate(3);
    ASSERT_FALSE(f.awake(a));
    ASSERT_FALSE(f.awake(b));
    const Vector3 pa = f.position(a);
    const Vector3 pb = f.position(b);
    f.simulate(1);
    EXPECT_EQ(f.position(a), pa);  // bit for bit
    EXPECT_EQ(f.position(b), pb);
    const StepStats &s = f.world.stats();
    EXPECT_EQ(s.integratedBodies, 0);
    EXPECT_EQ(s.pairsTested, 0);
    EXPECT_EQ(s.pairsReused, 0);
    EXPECT_EQ(s.contacts, 0);
}

TEST(Sleep, WakesWhenHit) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(2);
    ASSERT_FALSE(f.awake(box));
    const BodyId ball = f.sphere(Vector3(-3, 0.5, 0), 0.25);
    f.world.setVelocity(ball, Vector3(10, 0, 0));
    bool woke = false;
    for (int i = 0; i < 30 && !woke; ++i) {
        f.world.step(kDt);
        woke = f.awake(box);
    }
    EXPECT_TRUE(woke);
}

TEST(Sleep, WakesWhenSupportRemoved) {
    WorldFixture f;
    f.ground();
    const BodyId bottom = f.box(Vector3(0, 0.5, 0));
    const BodyId top = f.box(Vector3(0, 1.5, 0));
    f.simulate(2);
    ASSERT_FALSE(f.awake(top));
    f.world.removeBody(bottom);
    EXPECT_TRUE(f.awake(top));
    f.simulate(0.5);
    // Free fall from rest for 0.5 s drops it g t^2 / 2 = 1.23 m, onto the ground at y = 0.5.
    EXPECT_NEAR(f.position(top).y(), 0.5, 0.02);
}

TEST(Sleep, DistantSleepingStackStaysAsleepWhenAnotherIsHit) {
    WorldFixture f;
    f.ground();
    std::vector<BodyId> near, far;
    for (int i = 0; i < 3; ++i) {
        near.push_back(f.box(Vector3(0, 0.5 + i, 0)));
        far.push_back(f.box(Vector3(20, 0.5 + i, 0)));
    }
    f.simulate(2.5);
    for (BodyId id : near) ASSERT_FALSE(f.awake(id));
    for (BodyId id : far) ASSERT_FALSE(f.awake(id));
    const BodyId ball = f.sphere(Vector3(-3, 1.5, 0), 0.25, 3);
    f.world.setVelocity(ball, Vector3(12, 0, 0));
    f.simulate(0.5);
    bool nearWoke = false;
    for (BodyId id : near) nearWoke = nearWoke || f.awake(id);
    EXPECT_TRUE(nearWoke);
    for (BodyId id : far) EXPECT_FALSE(f.awake(id));
}

TEST(Sleep, ApiCallsWakeTheIsland) {
    WorldFixture f;
    f.ground();
    const BodyId bottom = f.box(Vector3(0, 0.5, 0));
    const BodyId top = f.box(Vector3(0, 1.5, 0));
    f.simulate(2);
    ASSERT_FALSE(f.awake(top));
    f.world.applyImpulse(bottom, Vector3(0, 0, 0));
    EXPECT_TRUE(f.awake(bottom));
    EXPECT_TRUE(f.awake(top));
}

TEST(Sleep, SetAwakeFalsePutsIslandToSleep) {
    WorldFixture f;
    f.ground();
    const BodyId bottom = f.box(Vector3(0, 0.5, 0));
    const BodyId top = f.box(Vector3(0, 1.5, 0));
    f.simulate(0.2);
    ASSERT_TRUE(f.awake(top));
    f.world.setAwake(bottom, false);
    EXPECT_FALSE(f.awake(bottom));
    EXPECT_FALSE(f.awake(top));
}

// --- Sleep after coming to rest (WorldSettings::sleepDelay) ----------------------------

// Steps a body until it sleeps or `seconds` pass. `rest` is the time of the last step at
// which it moved faster than 1 cm/s (or turned faster than 0.01 rad/s); `asleep` the
// time of the first step after which it slept (both -1 if never).
struct RestAndSleep {
    double rest = -1;
    double asleep = -1;
    double lowestAwakeHeight = 1e9;  // where it was at the steps it was awake
};

RestAndSleep runUntilAsleep(WorldFixture &f, BodyId id, double seconds) {
    RestAndSleep r;
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 1; i <= steps; ++i) {
        f.world.step(kDt);
        const RigidBody &b = f.world.body(id);
        if (!b.getAwake()) {
            r.asleep = i * kDt;
            break;
        }
        if (b.getVelocity().norm() > 0.01 || b.getRotation().norm() > 0.01) r.rest = i * kDt;
    }
    return r;
}

// A box launched at 6 m/s on ground with friction 0.6 decelerates at mu g = 5.89 m/s^2
// and stops at t = 6 / 5.89 = 1.02 s, 3.06 m on; it sleeps within sleepDelay = 0.4 s of
// stopping (plus the step that sees it), not while it slides.
TEST(Sleep, ABoxThatSlidToAStopSleepsWithinHalfASecond) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.world.setVelocity(box, Vector3(6, 0, 0));
    const RestAndSleep r = runUntilAsleep(f, box, 5);
    const double stop = 6 / (0.6 * 9.81);
    EXPECT_NEAR(r.rest, stop, 3 * kDt);
    ASSERT_GT(r.asleep, 0);
    EXPECT_GT(r.asleep, r.rest);
    EXPECT_LE(r.asleep - r.rest, 0.4 + 2 * kDt);
    EXPECT_NEAR(f.position(box).x(), 6 * 6 / (2 * 0.6 * 9.81), 0.05);
}

// On ice (friction 0.05: 0.49 m/s^2) a box from 1 m/s creeps below 0.1 m/s for its last
// 0.2 s: it must not sleep before it stops (t = 2.04 s), and sleeps within 0.5 s after.
TEST(Sleep, ABoxSlowingDownOnIceSleepsOnlyAfterItStops) {
    WorldFixture f;
    f.ground(0.05);
    const BodyId box = f.box(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5), 1, 0.05);
    f.world.setVelocity(box, Vector3(1, 0, 0));
    const RestAndSleep r = runUntilAsleep(f, box, 5);
    const double stop = 1 / (0.05 * 9.81);
    EXPECT_NEAR(r.rest, stop, 3 * kDt);
    ASSERT_GT(r.asleep, 0);
    EXPECT_GT(r.asleep, stop);
    EXPECT_LE(r.asleep - r.rest, 0.5);
}

// A box sliding without friction at 0.15 m/s (v.v = 2.25 sleepEpsilon) never sleeps.
TEST(Sleep, ABoxSlidingSlowlyAtASteadySpeedStaysAwake) {
    WorldFixture f;
    f.ground(0);
    const BodyId box = f.box(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5), 1, 0);
    f.world.setVelocity(box, Vector3(0.15, 0, 0));
    f.simulate(5);
    EXPECT_TRUE(f.awake(box));
    EXPECT_NEAR(f.position(box).x(), 0.75, 0.01);
}

// A ball thrown up at 5 m/s from the ground lands after 2 v / g = 1.02 s (it does not
// bounce: restitution 0); it sleeps within 0.5 s of landing and never in the air.
TEST(Sleep, ABallThrownUpSleepsWithinHalfASecondOfLanding) {
    WorldFixture f;
    f.ground();
    const BodyId ball = f.sphere(Vector3(0, 0.25, 0), 0.25);
    f.world.setVelocity(ball, Vector3(0, 5, 0));
    RestAndSleep r;
    bool sleptInTheAir = false;
    for (int i = 1; i <= 300 && r.asleep < 0; ++i) {
        f.world.step(kDt);
        const RigidBody &b = f.world.body(ball);
        if (!b.getAwake()) {
            r.asleep = i * kDt;
            sleptInTheAir = b.getPosition().y() > 0.26;
        } else if (b.getVelocity().norm() > 0.01 || b.getRotation().norm() > 0.01) {
            r.rest = i * kDt;
        }
    }
    EXPECT_NEAR(r.rest, 2 * 5 / 9.81, 2 * kDt);
    ASSERT_GT(r.asleep, 0);
    EXPECT_FALSE(sleptInTheAir);
    EXPECT_LE(r.asleep - r.rest, 0.4 + 2 * kDt);
}

// Thrown up slowly (1 m/s), the ball moves slower than 0.1 m/s (v.v < sleepEpsilon) for
// 20 ms around the apex: far less than sleepDelay, so it stays awake.
TEST(Sleep, DoesNotSleepAtTheTopOfASlowThrow) {
    WorldFixture f;
    const BodyId ball = f.sphere(Vector3(0, 100, 0), 0.2);
    f.world.setVelocity(ball, Vector3(0, 1, 0));
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        ASSERT_TRUE(f.awake(ball)) << "fell asleep at t = " << (i + 1) * kDt;
    }
}

// At sleepDelay = log2(10) the cap is the seed's clamp, 10 thresholds, which halves to the
// threshold in 3.32 s of rest: the box that slid from 6 m/s sleeps that long after it stops.
TEST(Sleep, ASleepDelayOfLog2TenIsTheSeedsClamp) {
    WorldSettings settings;
    settings.sleepDelay = std::log2(10.0);
    WorldFixture f(settings);
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.world.setVelocity(box, Vector3(6, 0, 0));
    const RestAndSleep r = runUntilAsleep(f, box, 8);
    ASSERT_GT(r.asleep, 0);
    EXPECT_NEAR(r.asleep - r.rest, std::log2(10.0), 0.1);
}

// sleepDelay 0 is allowed (sleep as soon as the average drops below the threshold);
// outside [0, 3.3] is refused, naming the field and the value.
TEST(Sleep, SleepDelayOutOfRangeIsRefused) {
    WorldSettings s;
    s.sleepDelay = -0.1;
    try {
        World w(s);
        FAIL();
    } catch (const InvalidArgument &e) {
        EXPECT_NE(std::string(e.what()).find("sleepDelay"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("-0.1"), std::string::npos);
    }
    s.sleepDelay = 3.33;
    EXPECT_THROW(World{s}, InvalidArgument);
    World w;
    EXPECT_THROW(w.setSettings(s), InvalidArgument);
    EXPECT_EQ(w.settings().sleepDelay, 0.4);
    s.sleepDelay = 0;
    EXPECT_NO_THROW(World{s});
}

}  // namespace
}  // namespace cyclone::test
