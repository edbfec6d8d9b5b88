// The coordinate range (kMaxCoordinate = 1e12 m) is where contacts hold: at 1e14 m a ball
// and a crate fell through a static floor while positions up to 1e30 m were accepted
// (issue 34, item 5). Beyond the range positions are refused, and a body that flies out
// of it is isolated.
#include <gtest/gtest.h>

#include <string>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A ball and a crate dropped 0.1 m onto a static floor whose top face is at `corner`
// (every coordinate near the edge of the range) come to rest on it after 2 s: the
// ball's centre 0.5 m above the face, the crate's 0.5 m (its half height). Doubles there
// are 2^-13 m = 1.2e-4 m apart, so within 5 mm is a real rest, not rounding.
void expectRestAt(const Vector3 &corner) {
    WorldSettings settings;
    settings.sleep = false;  // asleep, they would give the solver no contact to count
    WorldFixture f(settings);
    f.staticBox(corner + Vector3(0, -0.5, 0), Vector3(20, 0.5, 20));
    const BodyId ball = f.sphere(corner + Vector3(-2, 0.6, 0));
    const BodyId crate = f.box(corner + Vector3(2, 0.6, 0));
    f.simulate(2.0);
    EXPECT_GT(f.world.stats().contacts, 0);
    EXPECT_NEAR(f.position(ball).y() - corner.y(), 0.5, 0.005);
    EXPECT_NEAR(f.position(crate).y() - corner.y(), 0.5, 0.005);
    EXPECT_EQ(f.world.stats().isolatedBodies, 0);
}

TEST(CoordinateRange, ContactsHoldAtTheEdgeOfTheRange) {
    const real edge = kMaxCoordinate - 100;
    expectRestAt(Vector3(edge, edge, edge));
    expectRestAt(Vector3(-edge, -edge, edge));
}

TEST(CoordinateRange, PositionsBeyondTheRangeAreRefused) {
    WorldFixture f;
    BodySettings s;
    s.position = Vector3(0, 2e12, 0);
    try {
        f.world.addBody(s);
        FAIL() << "a position of 2e12 m was accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::addBody");
        EXPECT_EQ(e.field(), "position");
        EXPECT_NE(e.problem().find("1e12 m"), std::string::npos) << e.what();
        EXPECT_NE(e.problem().find("2e+12"), std::string::npos) << e.what();
    }
    EXPECT_EQ(f.world.bodyCount(), 0u);
    const BodyId box = f.box(Vector3(0, 0, 0));
    try {
        f.world.setPosition(box, Vector3(-1.5e12, 0, 0));
        FAIL() << "setPosition accepted -1.5e12 m";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.field(), "position");
        EXPECT_NE(e.problem().find("1e12 m"), std::string::npos) << e.what();
    }
    EXPECT_EQ(f.position(box), Vector3::Zero());
}

// A box 1 m inside the range moving out at 600 m/s crosses it in one 1/60 s step (10 m):
// it is isolated like a non-finite body, and a box elsewhere goes on falling.
TEST(CoordinateRange, ABodyThatLeavesTheRangeIsIsolated) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    BodySettings s;
    s.position = Vector3(kMaxCoordinate - 1, 0, 0);
    s.velocity = Vector3(600, 0, 0);
    const BodyId runaway = f.world.addBody(s);
    s.position = Vector3(0, 0, 0);
    s.velocity = Vector3(0, -1, 0);
    const BodyId other = f.world.addBody(s);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().isolatedBodies, 1);
    EXPECT_THROW(f.world.setVelocity(runaway, Vector3::Zero()), InvalidArgument);
    f.world.step(kDt);
    // Two steps at -1 m/s: -2/60 m.
    EXPECT_NEAR(f.position(other).y(), -2.0 / 60, 1e-12);
}

}  // namespace
}  // namespace cyclone::test
