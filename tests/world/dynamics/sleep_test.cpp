// Sleep and wake of islands (after Jolt's TestPhysicsActivationDeactivation).
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A body at rest is woken with a motion average of 2 eps, which halves every second
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

// Thrown up at 10 m/s the ball stops at the apex (t = 1.02 s); the motion average, which
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

}  // namespace
}  // namespace cyclone::test
