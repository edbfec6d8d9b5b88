// The carrier pass (WorldSettings::shockPropagation): the last pass of each sub-step
// solves each body against the bodies carrying it as immovable. It must change nothing
// where no body carries another: momentum between bodies side by side or without gravity
// is conserved to rounding, as by the plain passes.
#include <cmath>

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

}  // namespace
}  // namespace cyclone::test
