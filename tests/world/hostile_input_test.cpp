// Hostile input (issue 34): whatever addBody accepts can be stepped, and what would break
// the solver is refused up front with the field and the range that works.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cyclone/world/game_loop.h"
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

template <class Call>
void expectThrowsAt(Call call, const std::string &field) {
    try {
        call();
        FAIL() << "no throw";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

// A moved-from World used to dereference a null state; now every call throws.
TEST(MustNot, AMovedFromWorldThrows) {
    World from;
    World to(std::move(from));
    expectThrowsAt([&] { from.step(kDt); }, "this");
    expectThrowsAt([&] { from.addBody(unitBox(Vector3::Zero(), 1)); }, "this");
    expectThrowsAt([&] { (void)from.bodyCount(); }, "this");
    // Assigned to, it is a World again.
    from = World();
    EXPECT_EQ(from.bodyCount(), 0u);
    EXPECT_NO_THROW(from.step(kDt));
}

// A FixedStepper keeps a pointer to its World: once that World is moved from, advancing
// throws instead of stepping a null state.
TEST(MustNot, AFixedStepperWhoseWorldMovedThrows) {
    World world;
    FixedStepper stepper(world);
    World elsewhere(std::move(world));
    expectThrowsAt([&] { stepper.advance(0.1); }, "this");
}

// A QueryFilter::accept that removes bodies pulled the broadphase tree from under the walk
// (a segfault); the query now throws as soon as accept returns.
TEST(MustNot, AQueryFilterThatRemovesBodiesThrows) {
    WorldFixture f;
    std::vector<BodyId> boxes;
    for (int i = 0; i < 8; ++i) boxes.push_back(f.box(Vector3(0, 0, 2.0 * i)));
    QueryFilter filter;
    filter.accept = [&](BodyId id) {
        for (BodyId other : boxes)
            if (other != id && f.world.contains(other)) f.world.removeBody(other);
        return true;
    };
    expectThrowsAt([&] { f.world.rayCast(Vector3(0, 0, -5), Vector3(0, 0, 1), 100, filter); }, "filter.accept");
    std::vector<BodyId> out;
    for (int i = 0; i < 8; ++i) boxes.push_back(f.box(Vector3(0, 0, 2.0 * i)));
    expectThrowsAt([&] { f.world.overlap(Shape::box(Vector3(1, 1, 20)), Vector3::Zero(), Quaternion::Identity(), out, filter); },
                   "filter.accept");
    // A filter that only reads is fine.
    QueryFilter reading;
    reading.accept = [&](BodyId id) { return f.world.body(id).getPosition().z() > 100; };
    EXPECT_FALSE(f.world.rayCast(Vector3(0, 0, -5), Vector3(0, 0, 1), 100, reading));
}

// A body isolated for a non-finite state is never simulated again: calls that would
// change it used to succeed without effect (it reported awake, never moved). They are
// refused; it can still be read and removed, and a new body takes its place.
TEST(IsolatedBodies, ChangingOneIsRefusedAndRemovingItWorks) {
    WorldFixture f;
    const BodyId body = f.box(Vector3(0, 5, 0));
    f.world.addForce(body, Vector3(0, 1e308, 0));
    f.world.addForce(body, Vector3(0, 1e308, 0));  // inf: 1e308 + 1e308 overflows
    f.world.step(kDt);
    ASSERT_EQ(f.world.stats().isolatedBodies, 1);
    expectThrowsAt([&] { f.world.setPosition(body, Vector3(0, 1, 0)); }, "id");
    expectThrowsAt([&] { f.world.setVelocity(body, Vector3::Zero()); }, "id");
    expectThrowsAt([&] { f.world.setAwake(body, true); }, "id");
    expectThrowsAt([&] { f.world.applyImpulse(body, Vector3(0, 1, 0)); }, "id");
    EXPECT_NO_THROW((void)f.world.body(body));
    f.world.removeBody(body);
    const BodyId again = f.box(Vector3(0, 5, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().isolatedBodies, 0);
    EXPECT_LT(f.world.body(again).getPosition().y(), 5.0);  // it falls
}

}  // namespace
}  // namespace cyclone::test
