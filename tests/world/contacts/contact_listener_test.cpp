// The pre-solve stage: World::setContactListener's listener (disable a manifold, change its
// friction, restitution and surface velocity) and the built-in rules on top of it,
// BodySettings::surfaceVelocity (conveyors) and BodySettings::oneWay (platforms).
#include <string>
#include <utility>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// Calls `change` on every manifold and records which pairs it saw, in order.
template <typename Change>
struct Listener final : ContactListener {
    Change change;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> seen;
    explicit Listener(Change c) : change(std::move(c)) {}
    void preSolve(PreSolveContact &contact) override {
        seen.emplace_back(contact.a.index, contact.b.index);
        change(contact);
    }
};
template <typename Change>
Listener<Change> listen(Change change) {
    return Listener<Change>(std::move(change));
}

BodySettings ledge(const Vector3 &position) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = Shape::box(Vector3(2, 0.1, 2));
    s.position = position;
    s.oneWay = Vector3(0, 1, 0);
    return s;
}

// A listener that disables a box's contacts lets it fall through the ground as if there
// were none: from y = 0.5 (resting), 1 s of free fall by symplectic Euler with sub-steps of
// h <= 1/60 s drops it g t (t + h) / 2, between g / 2 = 4.905 m and g (1 + 1/60) / 2 =
// 4.98675 m. The listener saw the pair (ground, box): a is the ground, added first.
TEST(ContactListener, DisablingAManifoldLetsTheBodiesPass) {
    WorldFixture f(noSleep());
    const BodyId ground = f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    auto listener = listen([](PreSolveContact &c) { c.enabled = false; });
    f.world.setContactListener(&listener);
    EXPECT_EQ(f.world.contactListener(), &listener);
    f.simulate(1);
    EXPECT_LE(f.position(box).y(), 0.5 - kG / 2 + 1e-9);
    EXPECT_GE(f.position(box).y(), 0.5 - kG * (1 + 1.0 / 60) / 2 - 1e-9);
    ASSERT_FALSE(listener.seen.empty());
    EXPECT_EQ(listener.seen.front(), std::make_pair(ground.index, box.index));
    EXPECT_EQ(f.world.stats().manifolds, 0);
}

// Friction 0 set by the listener: a box sliding at 3 m/s on the ground (both materials
// 0.6) keeps its speed, nothing acting along x; without the listener it stops within
// v / (mu g) = 3 / 5.886 = 0.51 s.
TEST(ContactListener, ChangingFrictionActs) {
    for (const bool frictionless : {true, false}) {
        WorldFixture f(noSleep());
        f.ground();
        const BodyId box = f.box(Vector3(0, 0.5, 0));
        f.world.setVelocity(box, Vector3(3, 0, 0));
        auto listener = listen([](PreSolveContact &c) { c.friction = 0; });
        if (frictionless) f.world.setContactListener(&listener);
        f.simulate(1);
        if (frictionless) EXPECT_NEAR(f.world.body(box).getVelocity().x(), 3, 1e-9);
        else EXPECT_NEAR(f.world.body(box).getVelocity().x(), 0, 1e-6);
    }
}

// Restitution 1 set by the listener on a ball dropped from 1 m (its material: 0): it hits
// at sqrt(2 g) = 4.43 m/s, above the 1 m/s threshold, and bounces back nearly as high
// (the first-order step loses a little); without the listener it stays down.
TEST(ContactListener, ChangingRestitutionActs) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId ball = f.sphere(Vector3(0, 1.5, 0));
    auto listener = listen([](PreSolveContact &c) { c.restitution = 1; });
    f.world.setContactListener(&listener);
    real highest = 0;
    bool landed = false;
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        const real y = f.position(ball).y();
        if (y < 0.55) landed = true;
        if (landed) highest = std::max(highest, y);
    }
    EXPECT_GT(highest, 1.4) << "bounced back up nearly 1 m";
}

// The listener's calls come in the same order in two equal worlds (a fixed order on one
// thread, whatever the thread count).
TEST(ContactListener, CallsComeInAFixedOrder) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> runs[2];
    for (int run = 0; run < 2; ++run) {
        WorldSettings settings = noSleep();
        settings.threads = run == 0 ? 1 : 2;
        WorldFixture f(settings);
        f.ground();
        for (int i = 0; i < 5; ++i) f.box(Vector3(0.1 * i, 0.5 + 1.01 * i, 0));
        auto listener = listen([](PreSolveContact &) {});
        f.world.setContactListener(&listener);
        f.simulate(0.5);
        runs[run] = listener.seen;
    }
    EXPECT_FALSE(runs[0].empty());
    EXPECT_EQ(runs[0], runs[1]);
}

// A value out of range from the listener stops the step with InvalidArgument naming it.
TEST(ContactListener, OutOfRangeValuesAreRefused) {
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    auto negative = listen([](PreSolveContact &c) { c.friction = -1; });
    f.world.setContactListener(&negative);
    try {
        f.world.step(kDt);
        FAIL() << "a negative friction was accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "ContactListener::preSolve");
        EXPECT_EQ(e.field(), "friction");
        EXPECT_NE(e.problem().find("-1"), std::string::npos);
    }
    auto bouncy = listen([](PreSolveContact &c) { c.restitution = 2; });
    f.world.setContactListener(&bouncy);
    EXPECT_THROW(f.world.step(kDt), InvalidArgument);
    f.world.setContactListener(nullptr);
    f.world.step(kDt);  // steps again once the listener is gone
}

// A crate on a conveyor whose surface moves at 2 m/s along x: friction (mu = 0.6)
// accelerates it at mu g = 5.886 m/s^2 until it rides at the belt's speed, which it reaches
// in 2 / 5.886 = 0.34 s; after 2 s it moves at 2 m/s (+- 0.05) along x, and not along z.
// The belt, static, stays put. The listener sees the surface velocity as B's relative to A's.
TEST(SurfaceVelocity, ACrateOnAConveyorReachesTheBeltsSpeed) {
    WorldFixture f(noSleep());
    BodySettings belt;
    belt.motion = Motion::Static;
    belt.shape = Shape::box(Vector3(20, 0.5, 1));
    belt.position = Vector3(0, -0.5, 0);
    belt.surfaceVelocity = Vector3(2, 0, 0);
    const BodyId conveyor = f.world.addBody(belt);
    const BodyId crate = f.box(Vector3(0, 0.5, 0));
    Vector3 seen = Vector3::Zero();
    auto listener = listen([&](PreSolveContact &c) { seen = c.surfaceVelocity; });
    f.world.setContactListener(&listener);
    f.simulate(2);
    EXPECT_NEAR(f.world.body(crate).getVelocity().x(), 2, 0.05);
    EXPECT_NEAR(f.world.body(crate).getVelocity().z(), 0, 1e-9);
    EXPECT_NEAR(f.position(crate).y(), 0.5, 0.01);
    EXPECT_EQ(f.position(conveyor), Vector3(0, -0.5, 0));
    EXPECT_EQ(seen, Vector3(-2, 0, 0)) << "the belt is a (added first): the crate's surface moves at -2 relative to it";
}

// A belt turned half a turn about y carries the other way: the surface velocity is in body
// space.
TEST(SurfaceVelocity, IsInBodySpace) {
    WorldFixture f(noSleep());
    BodySettings belt;
    belt.motion = Motion::Static;
    belt.shape = Shape::box(Vector3(20, 0.5, 1));
    belt.position = Vector3(0, -0.5, 0);
    belt.orientation = Quaternion(0, 0, 1, 0);  // 180 degrees about y
    belt.surfaceVelocity = Vector3(2, 0, 0);
    f.world.addBody(belt);
    const BodyId crate = f.box(Vector3(0, 0.5, 0));
    f.simulate(2);
    EXPECT_NEAR(f.world.body(crate).getVelocity().x(), -2, 0.05);
}

// A ball on the ground jumps at 8 m/s under a one-way ledge (top at y = 2.1): its apex
// would be 0.5 + 64 / (2 g) = 3.76 m, so it goes up through the ledge unhindered, falls
// back onto its top and rests there, its centre one radius (0.25 m) above it: 2.35 m.
TEST(OneWay, ABallJumpsUpThroughALedgeAndRestsOnTop) {
    WorldFixture f(noSleep());
    f.ground();
    f.world.addBody(ledge(Vector3(0, 2, 0)));
    const BodyId ball = f.sphere(Vector3(0, 0.5, 0), 0.25);
    f.world.setVelocity(ball, Vector3(0, 8, 0));
    real highest = 0;
    for (int i = 0; i < 240; ++i) {
        f.world.step(kDt);
        highest = std::max(highest, f.position(ball).y());
    }
    EXPECT_GT(highest, 3.6) << "the ledge did not stop it on the way up";
    EXPECT_NEAR(f.position(ball).y(), 2.35, 0.01);
    EXPECT_NEAR(f.world.body(ball).getVelocity().y(), 0, 0.01);
}

// A box that starts overlapping the ledge from below passes until it is out: at rest it
// falls out through the bottom onto the ground (half-height 0.2: rests at 0.2); moving up
// at 6 m/s it comes out at the top (apex about 1.9 + 36 / (2 g) = 3.7 m) and lands on it
// (rests at 2.1 + 0.2 = 2.3 m).
TEST(OneWay, ABodyOverlappingFromBelowPassesUntilItIsOut) {
    for (const real speed : {0.0, 6.0}) {
        WorldFixture f(noSleep());
        f.ground();
        f.world.addBody(ledge(Vector3(0, 2, 0)));
        const BodyId box = f.box(Vector3(0, 1.9, 0), Vector3(0.2, 0.2, 0.2));
        f.world.setVelocity(box, Vector3(0, speed, 0));
        f.simulate(4);
        EXPECT_NEAR(f.position(box).y(), speed > 0 ? 2.3 : 0.2, 0.01) << speed;
    }
}

// A body landing from above on a one-way ledge is held like on any ledge.
TEST(OneWay, LandingFromAboveHolds) {
    WorldFixture f(noSleep());
    f.world.addBody(ledge(Vector3(0, 0, 0)));
    const BodyId box = f.box(Vector3(0, 1, 0), Vector3(0.2, 0.2, 0.2));
    f.simulate(2);
    EXPECT_NEAR(f.position(box).y(), 0.3, 0.01);
}

// Refusals: a zero or non-finite one-way direction, a non-finite surface velocity.
TEST(OneWay, BadDirectionsAreRefused) {
    WorldFixture f;
    BodySettings s = ledge(Vector3::Zero());
    s.oneWay = Vector3::Zero();
    try {
        f.world.addBody(s);
        FAIL() << "a zero one-way direction was accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.field(), "oneWay");
    }
    s.oneWay = Vector3(0, kNaN, 0);
    EXPECT_THROW(f.world.addBody(s), InvalidArgument);
    s.oneWay.reset();
    s.surfaceVelocity = Vector3(kInf, 0, 0);
    try {
        f.world.addBody(s);
        FAIL() << "an infinite surface velocity was accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.field(), "surfaceVelocity");
    }
    EXPECT_EQ(f.world.bodyCount(), 0u);
}

}  // namespace
}  // namespace cyclone::test
