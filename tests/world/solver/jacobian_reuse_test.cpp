// A solver manifold keeps its Jacobians from one step to the next while its anchors and
// both bodies' poses hold (world/src/jacobian_stamp.h), and makes them again as soon as
// either changes: StepStats::jacobiansMade counts the manifolds that made them.
#include <gtest/gtest.h>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// Two boxes on the ground, at rest: after the first step nothing moves by more than
// the 0.5 mm tolerance, so no manifold makes its Jacobians again. With the tolerance at
// 0 every manifold makes them every step.
TEST(JacobianReuse, RestingStackMakesThemOnce) {
    for (const real tolerance : {0.0005, 0.0}) {
        WorldSettings settings = noSleep();
        settings.debug.manifoldReuseTolerance = tolerance;
        WorldFixture f(settings);
        f.ground();
        f.box(Vector3(0, 0.5, 0));
        f.box(Vector3(0, 1.5, 0));
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().manifolds, 2);
        EXPECT_EQ(f.world.stats().jacobiansMade, 2) << "the first step has no Jacobians to keep";
        int made = 0;
        for (int i = 0; i < 60; ++i) {
            f.world.step(kDt);
            EXPECT_EQ(f.world.stats().manifolds, 2);
            made += f.world.stats().jacobiansMade;
        }
        EXPECT_EQ(made, tolerance > 0 ? 0 : 2 * 60) << "tolerance " << tolerance;
    }
}

// Two boxes overlapping by 0.1 mm face to face, without gravity, gliding together at
// 0.012 m/s along the contact plane: their relative pose never changes, so the pair
// keeps its manifold and its anchors, but each body moves 0.2 mm per step. From a
// stamp, the Jacobians hold after 0.2 and 0.4 mm and are made again at 0.6 mm: every
// third step.
TEST(JacobianReuse, BodiesThatMoveTogetherMakeThemAgainPastTheTolerance) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    const Vector3 velocity(0, 0.012, 0);
    for (const BodyId id : {f.box(Vector3(0, 0, 0)), f.box(Vector3(0.9999, 0, 0))}) f.world.setVelocity(id, velocity);
    f.world.step(kDt);
    ASSERT_EQ(f.world.stats().manifolds, 1);
    EXPECT_EQ(f.world.stats().jacobiansMade, 1);
    std::vector<int> made;
    for (int i = 0; i < 9; ++i) {
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().pairsReused, 1) << "step " << i;
        made.push_back(f.world.stats().jacobiansMade);
    }
    EXPECT_EQ(made, (std::vector<int>{0, 0, 1, 0, 0, 1, 0, 0, 1}));
}

// A box moved by hand onto another spot of the box below gets new contacts: that
// manifold makes its Jacobians again, the ground's keeps them.
TEST(JacobianReuse, NewContactsMakeThemAgain) {
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    const BodyId top = f.box(Vector3(0, 1.5, 0));
    f.simulate(0.5);
    f.world.setPosition(top, f.position(top) + Vector3(0.1, 0, 0));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().manifolds, 2);
    EXPECT_EQ(f.world.stats().pairsTested, 1) << "the moved pair goes through the narrowphase";
    EXPECT_EQ(f.world.stats().jacobiansMade, 1);
}

}  // namespace
}  // namespace cyclone::test
