// Manifold reuse (DebugSettings::manifoldReuseTolerance): a pair whose relative pose has
// hardly changed since its last narrowphase keeps its manifold, refreshed from its
// anchors; a pair that moves is tested again; a reused stack stays where it rests.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

WorldSettings reuseAt(real tolerance) {
    WorldSettings s;
    s.sleep = false;
    s.debug.manifoldReuseTolerance = tolerance;
    return s;
}

TEST(ManifoldReuse, RestingStackIsReused) {
    // Three unit boxes resting on each other and the ground: three touching pairs. Once
    // settled they move by micrometres per step, far below 1 mm, so almost every step
    // reuses the manifolds instead of testing.
    WorldFixture f(reuseAt(0.001));
    f.ground();
    for (int i = 0; i < 3; ++i) f.box(Vector3(0, 0.5 + i, 0));
    f.simulate(1.0);
    int tested = 0, reused = 0;
    for (int i = 0; i < 60; ++i) {
        f.world.step(kDt);
        const StepStats &s = f.world.stats();
        EXPECT_EQ(s.pairsTested + s.pairsReused, 3) << "step " << i;
        EXPECT_EQ(s.manifolds, 3);
        tested += s.pairsTested;
        reused += s.pairsReused;
    }
    EXPECT_GT(reused, 0);
    EXPECT_GT(reused, 9 * tested);
}

TEST(ManifoldReuse, MovingPairIsTestedEveryStep) {
    // A frictionless box sliding at 2 m/s moves 2/60 = 33 mm per step relative to the
    // ground, more than the 1 mm tolerance: its pair is tested every step, never reused.
    WorldFixture f(reuseAt(0.001));
    f.ground(0);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = Vector3(0, 0.5, 0);
    s.velocity = Vector3(2, 0, 0);
    s.material.friction = 0;
    f.world.addBody(s);
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().pairsTested, 1) << "step " << i;
        EXPECT_EQ(f.world.stats().pairsReused, 0) << "step " << i;
    }
}

TEST(ManifoldReuse, PairWithoutContactIsNotReused) {
    // A box 1 cm above the ground is a broadphase pair (within the speculative distance)
    // without a contact. Falling, it would touch within the tolerance of a pose that gave no
    // contact: such a pair is always tested, and lands on the ground.
    WorldFixture f(reuseAt(0.05));
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.51, 0));
    int apart = 0;
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        if (f.world.stats().manifolds > 0) continue;
        ++apart;
        EXPECT_EQ(f.world.stats().pairsTested, 1) << "step " << i;
        EXPECT_EQ(f.world.stats().pairsReused, 0) << "step " << i;
    }
    // 1 cm of free fall from rest takes sqrt(2 x 0.01 / 9.81) = 0.045 s: 2.7 steps.
    EXPECT_GE(apart, 2);
    EXPECT_NEAR(f.position(box).y(), 0.5, 0.005);
}

TEST(ManifoldReuse, OffsetTowerStaysInPlace) {
    // The 12-box tower of examples/stacking (alternate boxes 1 cm left and right), 10 s
    // with reuse at 1 mm. Each contact settles about one slop deep (12 x 0.2 mm) and the
    // tower sways a few mm without reuse; 1 cm bounds both. A reused manifold that kept
    // its points in one order made Gauss-Seidel favour the same corner step after step,
    // and this tower then moved 3 cm.
    WorldFixture f(reuseAt(0.001));
    f.ground();
    BodyId top;
    for (int i = 0; i < 12; ++i) top = f.box(Vector3(i % 2 ? 0.01 : -0.01, 0.5 + i, 0));
    const Vector3 start = f.position(top);
    int reused = 0, tested = 0;
    for (int i = 0; i < 600; ++i) {
        f.world.step(kDt);
        reused += f.world.stats().pairsReused;
        tested += f.world.stats().pairsTested;
    }
    EXPECT_LT((f.position(top) - start).norm(), 0.01);
    EXPECT_GT(reused, 9 * tested);
}

}  // namespace
}  // namespace cyclone::test
