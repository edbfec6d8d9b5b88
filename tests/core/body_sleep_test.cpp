// RigidBody sleep and wake: the sleep average, falling asleep, the clamp, what wakes a
// body and what does not, and per-body thresholds.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "body_test_support.h"
#include "cyclone/body.h"

namespace cyclone_test {
namespace {

// A body with sleep threshold `epsilon`, just woken, so its sleep average is 2 * epsilon.
RigidBody wokenBody(real epsilon) {
    RigidBody body;
    body.setSleepEpsilon(epsilon);
    body.setAwake(true);
    return body;
}

// --- Motion average ----------------------------------------------------------------------

TEST(RigidBodySleep, MotionAverageIsRecencyWeighted) {
    RigidBody body = wokenBody(1);
    EXPECT_EQ(body.getSleepAverage(), 2);
    body.setVelocity(1, 0, 0);
    body.setRotation(0, 0, 2);
    body.integrate(2);
    // b = 0.5^2 = 0.25; v.v + w.w = 1 + 4 = 5; 0.25 * 2 + 0.75 * 5 = 4.25.
    EXPECT_DOUBLE_EQ(body.getSleepAverage(), 4.25);
    EXPECT_TRUE(body.getAwake());
}

TEST(RigidBodySleep, MotionAverageUsesTheDampedVelocity) {
    RigidBody body = wokenBody(1);
    body.setLinearDamping(0.5);
    body.setVelocity(2, 0, 0);
    body.integrate(1);
    // v = 2 * 0.5 = 1, so v.v = 1; b = 0.5: 0.5 * 2 + 0.5 * 1 = 1.5.
    EXPECT_DOUBLE_EQ(body.getSleepAverage(), 1.5);
}

TEST(RigidBodySleep, MotionAverageIsClampedAtTenTimesTheThreshold) {
    RigidBody body = wokenBody(1);
    body.setVelocity(10, 0, 0);
    body.integrate(1);
    // 0.5 * 2 + 0.5 * 100 = 51, clamped to 10 * 1.
    EXPECT_EQ(body.getSleepAverage(), 10);
    EXPECT_TRUE(body.getAwake());
}

TEST(RigidBodySleep, DefaultThresholdClamp) {
    RigidBody body;
    body.setVelocity(1, 0, 0);
    body.integrate(1);
    // 0.5 * 0.02 + 0.5 * 1 = 0.51 > 10 * 0.01.
    EXPECT_DOUBLE_EQ(body.getSleepAverage(), 10 * 0.01);
}

TEST(RigidBodySleep, TheClampBoundsHowLongAStoppedBodyStaysAwake) {
    RigidBody body = wokenBody(1);
    body.setVelocity(10, 0, 0);
    body.integrate(1);  // clamped at 10
    body.setVelocity(0, 0, 0);
    // At rest the average is 10 * 0.5^t: above 1 until t = log2(10) = 3.32 s.
    for (int i = 0; i < 6; ++i) body.integrate(0.5);  // 3 s: 10 / 8 = 1.25
    EXPECT_TRUE(body.getAwake());
    EXPECT_NEAR(body.getSleepAverage(), 1.25, 1e-12);
    body.integrate(0.5);  // 3.5 s: 10 / 2^3.5 = 0.88
    EXPECT_FALSE(body.getAwake());
}

TEST(RigidBodySleep, TheMovingCapBoundsTheAverageOnlyWhileTheBodyMoves) {
    RigidBody body = wokenBody(1);
    body.setMovingSleepAverageCap(1.5);
    EXPECT_EQ(body.getMovingSleepAverageCap(), 1.5);
    // At rest the woken average of 2 is not capped: 0.5 * 2 + 0.5 * 0 = 1, awake.
    body.integrate(1, false);
    EXPECT_DOUBLE_EQ(body.getSleepAverage(), 1);
    body.setAwake(true);
    body.setVelocity(10, 0, 0);
    body.integrate(1);  // 0.5 * 2 + 0.5 * 100 = 51, capped at 1.5 * 1 while moving
    EXPECT_EQ(body.getSleepAverage(), 1.5);
    body.setVelocity(0, 0, 0);
    // At rest 1.5 * 0.5^t falls below 1 at t = log2(1.5) = 0.585 s.
    body.integrate(0.5);  // 1.5 / 2^0.5 = 1.06
    EXPECT_TRUE(body.getAwake());
    body.integrate(0.1);  // 1.5 / 2^0.6 = 0.99
    EXPECT_FALSE(body.getAwake());
}

TEST(RigidBodySleep, ASlowBodyIsNotCappedBelowItsOwnMotion) {
    // Moving at v.v = 2 eps with a cap of 1.2 eps the average stays at the cap, above the
    // threshold: a body moving at a steady speed above the threshold never sleeps.
    RigidBody body = wokenBody(0.01);
    body.setMovingSleepAverageCap(1.2);
    body.setVelocity(std::sqrt(0.02), 0, 0);
    for (int i = 0; i < 600; ++i) body.integrate(1.0 / 60);
    EXPECT_TRUE(body.getAwake());
    EXPECT_NEAR(body.getSleepAverage(), 0.012, 1e-15);
}

TEST(RigidBodySleep, SetMovingSleepAverageCapRefusesValuesOutsideOneToTen) {
    RigidBody body;
    for (real bad : {real(0.5), real(10.5), real(NAN), real(INFINITY)}) {
        EXPECT_THROW(body.setMovingSleepAverageCap(bad), std::invalid_argument) << bad;
        EXPECT_EQ(body.getMovingSleepAverageCap(), 10);
    }
    try {
        body.setMovingSleepAverageCap(-1);
        FAIL();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("setMovingSleepAverageCap"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("-1"), std::string::npos);
    }
}

// --- Falling asleep ----------------------------------------------------------------------

TEST(RigidBodySleep, GoesToSleepBelowTheThreshold) {
    RigidBody body = wokenBody(1);
    body.setVelocity(0.5, 0, 0);
    body.integrate(2);
    // 0.25 * 2 + 0.75 * 0.25 = 0.6875 < 1: asleep, with velocity and rotation zeroed after
    // the step moved the body by 0.5 * 2.
    EXPECT_FALSE(body.getAwake());
    EXPECT_EQ(body.getVelocity(), Vector3::Zero());
    EXPECT_EQ(body.getRotation(), Vector3::Zero());
    EXPECT_EQ(body.getPosition(), Vector3(1, 0, 0));
}

TEST(RigidBodySleep, ARestingBodyFallsAsleepAboutOneSecondAfterWaking) {
    RigidBody body;  // motion 0.02 = 2 * threshold
    // At rest the average is 0.02 * 0.5^t: below 0.01 once t > 1 s.
    body.integrate(0.4);
    body.integrate(0.4);  // 0.8 s: 0.0115
    EXPECT_TRUE(body.getAwake());
    body.integrate(0.4);  // 1.2 s: 0.0087
    EXPECT_FALSE(body.getAwake());

    body.setAwake(true);  // woken again, the same second of grace
    body.integrate(0.4);
    body.integrate(0.4);
    EXPECT_TRUE(body.getAwake());
    body.integrate(0.4);
    EXPECT_FALSE(body.getAwake());
}

TEST(RigidBodySleep, SlowSlidingBodyStaysAwakeAtTheDefaultThreshold) {
    // The default threshold is 0.01 (m/s)^2: a body sliding at 0.5 m/s averages
    // 0.25 and stays awake (cyclone's 0.3 would have put it to sleep).
    RigidBody body;
    body.setVelocity(0.5, 0, 0);
    for (int i = 0; i < 600; ++i) body.integrate(1.0 / 60);
    EXPECT_TRUE(body.getAwake());
    EXPECT_NEAR(body.getPosition().x(), 5, 1e-9);
}

TEST(RigidBodySleep, ASleepingBodyIsNotIntegrated) {
    RigidBody body;
    body.setAwake(false);
    // Neither of these wakes the body.
    body.setVelocity(1, 2, 3);
    body.setRotation(0, 0, 1);
    body.setAcceleration(0, -10, 0);
    const Snapshot before(body);
    body.integrate(1);
    body.integrate(0.5, false);
    EXPECT_TRUE(identical(before, Snapshot(body)));
    EXPECT_FALSE(body.getAwake());
}

TEST(RigidBodySleep, IntegrateWithoutPermissionNeverSleeps) {
    RigidBody body;
    for (int i = 0; i < 100; ++i) body.integrate(0.1, false);
    // 10 s at rest: 0.02 * 0.5^10, far below the threshold, and still awake.
    EXPECT_TRUE(body.getAwake());
    EXPECT_NEAR(body.getSleepAverage(), 0.02 / 1024, 1e-15);
    body.integrate(0.1);
    EXPECT_FALSE(body.getAwake());
}

TEST(RigidBodySleep, ABodyThatMayNotSleepStaysAwake) {
    RigidBody body;
    body.setCanSleep(false);
    EXPECT_FALSE(body.getCanSleep());
    for (int i = 0; i < 100; ++i) body.integrate(0.1);
    EXPECT_TRUE(body.getAwake());
    EXPECT_LT(body.getSleepAverage(), body.getSleepEpsilon());
}

// --- setAwake ----------------------------------------------------------------------------

TEST(RigidBodySleep, SetAwakeTrueSetsMotionToTwiceTheThreshold) {
    RigidBody body;
    body.setSleepEpsilon(0.5);
    body.setAwake(false);
    EXPECT_FALSE(body.getAwake());
    body.setAwake(true);
    EXPECT_TRUE(body.getAwake());
    EXPECT_EQ(body.getSleepAverage(), 1);
    // Also on an awake body, and through the default argument.
    body.setVelocity(10, 0, 0);
    body.integrate(1);  // clamped at 5
    body.setAwake();
    EXPECT_TRUE(body.getAwake());
    EXPECT_EQ(body.getSleepAverage(), 1);
}

TEST(RigidBodySleep, SetAwakeFalseZeroesVelocityAndRotation) {
    RigidBody body;
    body.setPosition(1, 2, 3);
    body.setOrientation(0, 0, 1, 0);
    body.setVelocity(4, 5, 6);
    body.setRotation(-1, 0, 1);
    body.setAwake(false);
    EXPECT_FALSE(body.getAwake());
    Vector3 v, w;
    body.getVelocity(&v);
    body.getRotation(&w);
    EXPECT_EQ(v, Vector3::Zero());
    EXPECT_EQ(w, Vector3::Zero());
    // Where it is stays as it was.
    EXPECT_EQ(body.getPosition(), Vector3(1, 2, 3));
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(0, 0, 1, 0), 0));
}

// --- What wakes a body -------------------------------------------------------------------

class RigidBodyWake : public ::testing::Test {
protected:
    void SetUp() override {
        body.setSleepEpsilon(0.5);
        body.setPosition(1, 0, 0);
        body.setAwake(false);
        ASSERT_FALSE(body.getAwake());
    }
    // Awake as after setAwake(true): motion 2 * 0.5.
    void expectWoken() const {
        EXPECT_TRUE(body.getAwake());
        EXPECT_EQ(body.getSleepAverage(), 1);
    }
    RigidBody body;
};

TEST_F(RigidBodyWake, AddForce) {
    body.addForce(Vector3(0, 0, 1));
    expectWoken();
    EXPECT_EQ(body.getAccumulatedForce(), Vector3(0, 0, 1));
}

TEST_F(RigidBodyWake, AddForceAtPoint) {
    body.addForceAtPoint(Vector3(0, 0, 1), Vector3(2, 0, 0));
    expectWoken();
    // Lever (1,0,0) x (0,0,1) = (0,-1,0).
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3(0, -1, 0));
}

TEST_F(RigidBodyWake, AddForceAtBodyPoint) {
    body.addForceAtBodyPoint(Vector3(0, 0, 1), Vector3(1, 0, 0));
    expectWoken();
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3(0, -1, 0));
}

TEST_F(RigidBodyWake, AddTorque) {
    body.addTorque(Vector3(0, 2, 0));
    expectWoken();
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3(0, 2, 0));
}

TEST_F(RigidBodyWake, SetCanSleepFalse) {
    body.setCanSleep(false);
    expectWoken();
    EXPECT_FALSE(body.getCanSleep());
    // Allowing sleep again does not put it to sleep by itself.
    body.setCanSleep();
    EXPECT_TRUE(body.getCanSleep());
    EXPECT_TRUE(body.getAwake());
}

TEST_F(RigidBodyWake, ImpulsesAndStateSettersDoNotWake) {
    body.addVelocity(Vector3(1, 0, 0));
    body.addRotation(Vector3(0, 1, 0));
    body.setPosition(0, 0, 0);
    body.setAcceleration(0, -10, 0);
    EXPECT_FALSE(body.getAwake());
    EXPECT_EQ(body.getVelocity(), Vector3(1, 0, 0));
    EXPECT_EQ(body.getRotation(), Vector3(0, 1, 0));
}

TEST_F(RigidBodyWake, AWokenBodyIsIntegratedAgain) {
    body.addForce(Vector3(2, 0, 0));
    body.integrate(0.5);
    // v = 2 N / 1 kg * 0.5 s = 1 m/s; x = 1 + 1 * 0.5.
    EXPECT_EQ(body.getVelocity(), Vector3(1, 0, 0));
    EXPECT_EQ(body.getPosition(), Vector3(1.5, 0, 0));
}

// --- Thresholds are per body -------------------------------------------------------------

TEST(RigidBodySleepThreshold, SetAndGet) {
    RigidBody body;
    body.setSleepEpsilon(0.25);
    EXPECT_EQ(body.getSleepEpsilon(), 0.25);
}

TEST(RigidBodySleepThreshold, TwoBodiesDoNotInterfere) {
    RigidBody coarse = wokenBody(1);  // motion 2
    RigidBody fine;                   // threshold 0.01, motion 0.02
    coarse.setVelocity(0.5, 0, 0);
    fine.setVelocity(0.5, 0, 0);
    coarse.integrate(2);
    fine.integrate(2);
    // Same motion, v.v = 0.25, b = 0.25:
    //   coarse: 0.25 * 2 + 0.75 * 0.25 = 0.6875 < 1: asleep;
    //   fine: 0.25 * 0.02 + 0.75 * 0.25 = 0.1925 > 0.1: clamped at 0.1, awake.
    EXPECT_FALSE(coarse.getAwake());
    EXPECT_TRUE(fine.getAwake());
    EXPECT_DOUBLE_EQ(fine.getSleepAverage(), 0.1);
    EXPECT_EQ(coarse.getSleepEpsilon(), 1);
    EXPECT_EQ(fine.getSleepEpsilon(), cyclone::kDefaultSleepEpsilon);
    // A body made afterwards still has the default.
    const RigidBody later;
    EXPECT_EQ(later.getSleepEpsilon(), cyclone::kDefaultSleepEpsilon);
    EXPECT_DOUBLE_EQ(later.getSleepAverage(), 2 * cyclone::kDefaultSleepEpsilon);
}

}  // namespace
}  // namespace cyclone_test
