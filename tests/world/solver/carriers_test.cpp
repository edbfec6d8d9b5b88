// The carrier pass (DebugSettings::carrierPass): the last pass of each sub-step
// solves each body against the bodies carrying it as immovable. It must change nothing
// where no body carries another: momentum between bodies side by side or without gravity
// is conserved to rounding, as by the plain passes.
#include <cmath>
#include <numeric>
#include <vector>

#include "solver/carriers.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// Two boxes meet head on at height y: 10 kg at 2 m/s against 1 kg at rest, frictionless,
// restitution 0. Momentum 20 kg m/s is conserved to rounding at every step; afterwards the
// light box is ahead of the heavy one (no interpenetration) and no kinetic energy was
// gained (20 J before).
void expectInelasticHeadOn(WorldFixture &f, real y) {
    const BodyId heavy = f.box(Vector3(-1.2, y, 0), Vector3::Constant(0.5), 10, 0);
    const BodyId light = f.box(Vector3(0, y, 0), Vector3::Constant(0.5), 1, 0);
    f.world.setVelocity(heavy, Vector3(2, 0, 0));
    for (int i = 0; i < 60; ++i) {
        f.world.step(kDt);
        const real momentum = 10 * f.world.body(heavy).getVelocity().x() + f.world.body(light).getVelocity().x();
        ASSERT_NEAR(momentum, 20.0, 1e-9) << "step " << i;
    }
    const real vh = f.world.body(heavy).getVelocity().x();
    const real vl = f.world.body(light).getVelocity().x();
    EXPECT_GE(vl, vh);
    EXPECT_LE(0.5 * 10 * vh * vh + 0.5 * vl * vl, 20.0);
}

TEST(Support, HeadOnWithoutGravityConservesMomentum) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    expectInelasticHeadOn(f, 0);
}

// The same on a frictionless floor under gravity: both boxes rest on the floor (the same
// level of the contact graph) and their contact is a side contact, so neither carries
// the other and the horizontal momentum is exactly that of the plain passes.
TEST(Support, SideContactOnTheFloorConservesMomentum) {
    WorldFixture f(noSleep());
    f.ground(0);
    expectInelasticHeadOn(f, 0.4999);
}

// A 100 kg box dropped 0.25 m onto a 1 kg box resting on the ground: the light box is not
// pushed into the ground or out from under, and the heavy box comes to rest on it at
// y = 1.5 (within the slop and the first contact's depth) without moving sideways.
TEST(Support, HeavyBoxDroppedOnLightBoxComesToRest) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId light = f.box(Vector3(0, 0.4999, 0), Vector3::Constant(0.5), 1);
    const BodyId heavy = f.box(Vector3(0, 1.75, 0), Vector3::Constant(0.5), 100);
    f.simulate(3);
    const Vector3 l = f.position(light);
    const Vector3 h = f.position(heavy);
    EXPECT_NEAR(l.y(), 0.5, 0.001);
    EXPECT_NEAR(h.y(), 1.5, 0.001);
    EXPECT_LT(std::hypot(l.x(), l.z()), 0.001);
    EXPECT_LT(std::hypot(h.x(), h.z()), 0.001);
    EXPECT_LT(f.world.body(heavy).getVelocity().norm(), 0.01);
}

// A 1000 kg box on a 1 kg box on the ground, its side against a static wall that the
// light box does not reach. The wall does not carry the heavy box (their normal is
// horizontal): the light box does, so the carrier pass holds the 1:1000 ratio as in a
// free column. At every step the light box stays within 1 mm of y = 0.5 (on the ground,
// not pressed into it) and the heavy box within 1 mm of y = 1.5, and neither is pushed
// out along the ground; at the end the heavy box is at rest.
TEST(Support, ColumnAgainstAWallIsCarriedByTheBoxUnderIt) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId light = f.box(Vector3(0, 0.4999, 0), Vector3::Constant(0.5), 1);
    const BodyId heavy = f.box(Vector3(0, 1.4998, 0), Vector3::Constant(0.5), 1000);
    f.staticBox(Vector3(1.00005, 1.6, 0), Vector3(0.5, 0.35, 1));  // face at x = 0.50005, y 1.25-1.95
    for (int i = 0; i < 300; ++i) {
        f.world.step(kDt);
        ASSERT_NEAR(f.position(light).y(), 0.5, 0.001) << "step " << i;
        ASSERT_NEAR(f.position(heavy).y(), 1.5, 0.001) << "step " << i;
        ASSERT_LT(std::abs(f.position(light).x()), 0.001) << "step " << i;
        ASSERT_LT(std::abs(f.position(heavy).x()), 0.001) << "step " << i;
    }
    EXPECT_LT(f.world.body(heavy).getVelocity().norm(), 0.01);
}

// assignCarriers on contact graphs made by hand, up +y: solver body 0 is everything
// static (the ground and a wall at -x), the others are moving bodies.
detail::SolverManifold contact(int a, int b, const Vector3 &normalFromAToB) {
    detail::SolverManifold m;
    m.a = a;
    m.b = b;
    m.normal = normalFromAToB.normalized();
    m.count = 1;
    return m;
}

std::vector<detail::Carrier> carriersOf(detail::SolverManifolds manifolds, int bodyCount) {
    std::vector<int> order(manifolds.size());
    std::iota(order.begin(), order.end(), 0);
    detail::CarrierScratch scratch;
    detail::CarrierRuns runs;
    detail::assignCarriers(bodyCount, bodyCount, Vector3(0, 1, 0), manifolds, order, scratch, runs);
    std::vector<detail::Carrier> carriers;
    for (const detail::SolverManifold &m : manifolds) carriers.push_back(m.carrier);
    return carriers;
}

// Body 1 stands on the ground; body 2 lies on a face of body 1 turned 45 degrees, which
// pushes it into the wall; body 3 stands on body 2. Body 2 cannot rest on that face alone
// (it would slide down a 45 degree slope unless its friction coefficient were 1 or more):
// the wall holds it too, so body 1 does not carry it. Body 2 still carries body 3.
TEST(Support, BodyOnASteepFaceAgainstAWallIsNotCarriedByIt) {
    const std::vector<detail::Carrier> carriers = carriersOf({contact(0, 1, Vector3(0, 1, 0)),
                                                              contact(1, 2, Vector3(-1, 1, 0)),
                                                              contact(0, 2, Vector3(1, 0, 0)),
                                                              contact(2, 3, Vector3(0, 1, 0))},
                                                             4);
    EXPECT_EQ(carriers[0], detail::Carrier::A);  // the ground carries body 1
    EXPECT_EQ(carriers[1], detail::Carrier::None);
    EXPECT_EQ(carriers[2], detail::Carrier::A);  // the wall, immovable
    EXPECT_EQ(carriers[3], detail::Carrier::A);
}

// A column of bodies 1, 2, 3 on the ground; body 4 touches only the wall; body 5 leans on
// the column's top (a face 53 degrees from level) and on body 4. Body 5 is held by body 4
// as much as by the column: its level comes from its lowest neighbour (body 4, level 1,
// found only over its side contact with the wall), not from the column's top (level 3),
// so the column does not carry it.
TEST(Support, BodyLeaningOnAColumnTakesItsLevelFromItsLowestNeighbour) {
    const std::vector<detail::Carrier> carriers = carriersOf({contact(0, 1, Vector3(0, 1, 0)),
                                                              contact(1, 2, Vector3(0, 1, 0)),
                                                              contact(2, 3, Vector3(0, 1, 0)),
                                                              contact(0, 4, Vector3(1, 0, 0)),
                                                              contact(3, 5, Vector3(-0.8, 0.6, 0)),
                                                              contact(5, 4, Vector3(-1, 0, 0))},
                                                             6);
    EXPECT_EQ(carriers[1], detail::Carrier::A);
    EXPECT_EQ(carriers[2], detail::Carrier::A);
    EXPECT_EQ(carriers[4], detail::Carrier::None);
    EXPECT_EQ(carriers[5], detail::Carrier::None);
}

}  // namespace
}  // namespace cyclone::test
