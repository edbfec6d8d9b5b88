// Capsules at rest through the closed-form round pairs (collision/round_pairs.cpp): a
// capsule lying on a box and a pile of three capsule logs stay where they were put and
// sleep as soon as a body at rest does.
//
// The bound: a body added at rest starts with a sleep average of twice the sleep
// threshold, which halves every second while v.v + w.w stays ~0 (Sleep.
// BodyAtRestSleepsAfterAboutOneSecond), so it crosses the threshold at t = 1 s. Contacts
// that rock or jitter keep v.v + w.w up and the average with it: then the body is still
// awake at 1.5 s.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A capsule lying with its core along x (its local z turned onto x).
BodyId logAlongX(WorldFixture &f, const Vector3 &position, real radius, real length) {
    BodySettings s;
    s.shape = Shape::capsule(radius, length);
    s.position = position;
    s.orientation = Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
    s.mass = 1;
    return f.world.addBody(s);
}

TEST(RoundPairsAtRest, CapsuleLyingOnABoxSleepsWhereItWasPut) {
    WorldFixture f;
    f.staticBox(Vector3(0, -0.5, 0), Vector3(2, 0.5, 2));  // top face at y = 0
    // Radius 0.2: its core 0.2 above the face, touching it along the whole segment.
    const Vector3 start(0.1, 0.2, -0.3);
    const BodyId capsule = logAlongX(f, start, 0.2, 1);
    f.simulate(0.9);
    EXPECT_TRUE(f.awake(capsule));
    f.simulate(0.6);
    EXPECT_FALSE(f.awake(capsule));
    // Still where it was put: within the contacts' slop (0.2 mm) of the face, not rolled.
    EXPECT_LT((f.position(capsule) - start).norm(), 1e-3);
}

TEST(RoundPairsAtRest, ALogOnTwoLogsSleepsWhereItWasPut) {
    WorldFixture f;
    f.ground();
    // Two logs (radius 0.2) side by side on the ground, touching at z = 0, and a third on
    // them: its core 0.4 from each lower core, so 0.2 + sqrt(0.4^2 - 0.2^2) = 0.5464 m
    // high. Each upper contact's normal is 30 degrees from the vertical; it pushes a lower
    // log sideways with tan 30 / 2 = 0.29 of the upper log's weight, far below what the
    // ground's and the logs' friction (0.6) hold, so the pile stands.
    const real r = 0.2;
    const Vector3 left(0, r, -r), right(0, r, r), top(0, r + std::sqrt(0.4 * 0.4 - r * r), 0);
    const BodyId a = logAlongX(f, left, r, 1);
    const BodyId b = logAlongX(f, right, r, 1);
    const BodyId c = logAlongX(f, top, r, 1);
    f.simulate(0.9);
    EXPECT_TRUE(f.awake(c));
    f.simulate(0.6);
    EXPECT_FALSE(f.awake(a));
    EXPECT_FALSE(f.awake(b));
    EXPECT_FALSE(f.awake(c));
    EXPECT_LT((f.position(a) - left).norm(), 1e-3);
    EXPECT_LT((f.position(b) - right).norm(), 1e-3);
    EXPECT_LT((f.position(c) - top).norm(), 1e-3);
}

}  // namespace
}  // namespace cyclone::test
