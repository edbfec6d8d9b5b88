// Hostile input (issue 34): whatever addBody accepts can be stepped, and what would break
// the solver is refused up front with the field and the range that works.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

BodySettings unitBox(const Vector3 &position, real mass) {
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = position;
    s.mass = mass;
    return s;
}

void expectRefused(World &world, const BodySettings &s, const std::string &field, const std::string &shown) {
    const std::size_t before = world.bodyCount();
    try {
        world.addBody(s);
        FAIL() << "addBody accepted a bad " << field;
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::addBody") << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(e.problem().find(shown), std::string::npos) << e.what();
    }
    EXPECT_EQ(world.bodyCount(), before);
}

// The body: 1e-155 kg with an explicit unit inertia, touching the ground. Its
// inverse mass squared, 1e310, overflowed in the friction block and every step threw.
// It is refused; a mass of 1e-100 (the smallest, kMinMass) with the same inertia steps.
TEST(HostileInput, AMassBelowTheSolversRangeIsRefused) {
    WorldFixture f;
    f.ground();
    BodySettings s = unitBox(Vector3(0, 0.5, 0), 1e-155);
    s.inertia = Matrix3::Identity();
    expectRefused(f.world, s, "mass", "got 1e-155");
    s.mass = 1e-100;
    const BodyId light = f.world.addBody(s);
    const BodyId other = f.box(Vector3(3, 2, 0));
    for (int i = 0; i < 30; ++i) ASSERT_NO_THROW(f.world.step(kDt));
    EXPECT_EQ(f.world.stats().isolatedBodies, 0);
    EXPECT_TRUE(f.world.body(light).getPosition().allFinite());
    // The other box falls freely for 0.5 s: 2 - g t^2 / 2 = 0.774 m (semi-implicit Euler
    // lands a little lower, by g t dt / 2 = 0.04 m).
    EXPECT_LT(f.world.body(other).getPosition().y(), 0.8);
}

// A unit cube's moments are m/6 and its inverse came from cofactors over a determinant
// (m/6)^3, which overflowed from m = 6 (1.8e308)^(1/3) = 3.4e103 kg: masses up to 8e154 kg
// were accepted with a zero inverse inertia. Beyond kMaxMass = 1e100 kg they are refused.
TEST(HostileInput, AMassAboveTheSolversRangeIsRefused) {
    WorldFixture f;
    expectRefused(f.world, unitBox(Vector3::Zero(), 5.6e102), "mass", "got 5.6e+102");
    expectRefused(f.world, unitBox(Vector3::Zero(), 1e120), "mass", "[1e-100, 1e100]");
}

// An explicit inertia whose moments over R^2 (R^2 = 3/4 for the unit cube) leave
// [1e-100, 1e100] kg is refused at the inertia: diag(1e-101) gives 1.33e-101.
TEST(HostileInput, AnInertiaBeyondTheSolversRangeIsRefusedAtTheInertia) {
    WorldFixture f;
    BodySettings s = unitBox(Vector3::Zero(), 1);
    s.inertia = Matrix3::Identity() * 1e-101;
    expectRefused(f.world, s, "inertia", "the solver's range is [1e-100, 1e100] kg");
    s.inertia = Matrix3::Identity() * 1e101;
    expectRefused(f.world, s, "inertia", "R = ");
}

// The two ends of the range meet: a 1e100 kg box resting on a 1e-100 kg one on the ground
// (a mass ratio of 1e200). Nothing throws, nothing is isolated, nothing goes non-finite.
TEST(HostileInput, BodiesAtBothEndsOfTheRangeStepTogether) {
    WorldFixture f;
    f.ground();
    BodySettings light = unitBox(Vector3(0, 0.5, 0), 1e-100);
    light.inertia = Matrix3::Identity();
    const BodyId a = f.world.addBody(light);
    const BodyId b = f.world.addBody(unitBox(Vector3(0.2, 1.5, 0), 1e100));
    for (int i = 0; i < 60; ++i) ASSERT_NO_THROW(f.world.step(kDt));
    EXPECT_EQ(f.world.stats().isolatedBodies, 0);
    for (BodyId id : {a, b}) {
        EXPECT_TRUE(f.world.body(id).getPosition().allFinite());
        EXPECT_TRUE(f.world.body(id).getVelocity().allFinite());
    }
}

// Six unit boxes spawned at one point over a ground plane: C(6, 2) = 15 box pairs and 6
// box-plane pairs. With a budget of 10 pairs the step keeps the 6 plane pairs and the
// first 4 box pairs, drops the other 11 and says so; the plane still holds every box.
WorldSettings budgetOf(int maxPairs) {
    WorldSettings s = noSleep();
    s.maxPairs = maxPairs;
    return s;
}

std::vector<BodyId> spawnSixAtOnePoint(WorldFixture &f) {
    f.ground();
    std::vector<BodyId> boxes;
    for (int i = 0; i < 6; ++i) boxes.push_back(f.box(Vector3(0, 0.5, 0)));
    return boxes;
}

TEST(PairBudget, TheExcessPairsAreDroppedAndReported) {
    WorldFixture f(budgetOf(10));
    const std::vector<BodyId> boxes = spawnSixAtOnePoint(f);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 10);
    EXPECT_NE(f.world.stats().errors & StepError::PairBudgetExceeded, 0u);
    for (int i = 0; i < 120; ++i) f.world.step(kDt);
    // Resting on the plane, each box's centre is half its height up, less the slop.
    for (BodyId id : boxes) EXPECT_GT(f.world.body(id).getPosition().y(), 0.45);
}

TEST(PairBudget, WithinTheBudgetNothingIsReported) {
    WorldFixture f(budgetOf(21));
    spawnSixAtOnePoint(f);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().broadphasePairs, 21);
    EXPECT_EQ(f.world.stats().errors, 0u);
}

// Which pairs are dropped depends only on the world's history: two worlds built alike end
// alike, to the bit.
TEST(PairBudget, TheDroppedPairsAreTheSameEveryRun) {
    WorldFixture one(budgetOf(10)), two(budgetOf(10));
    const std::vector<BodyId> a = spawnSixAtOnePoint(one), b = spawnSixAtOnePoint(two);
    for (int i = 0; i < 60; ++i) {
        one.world.step(kDt);
        two.world.step(kDt);
    }
    for (std::size_t k = 0; k < a.size(); ++k)
        EXPECT_EQ(one.world.body(a[k]).getPosition(), two.world.body(b[k]).getPosition());
}

TEST(PairBudget, ABudgetBelowOneIsRefused) {
    WorldFixture f;
    WorldSettings s;
    s.maxPairs = 0;
    try {
        f.world.setSettings(s);
        FAIL() << "maxPairs 0 accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.field(), "maxPairs");
        EXPECT_NE(e.problem().find("got 0"), std::string::npos);
    }
    EXPECT_EQ(f.world.settings().maxPairs, 65536);
}

}  // namespace
}  // namespace cyclone::test
