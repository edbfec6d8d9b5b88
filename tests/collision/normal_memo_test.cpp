// collide()'s NormalMemo: what FCL found for two convex solids, and the normal chosen,
// kept for a later test of the same shapes at the same poses (the landing correction's
// test, then the next step's narrowphase at other settings). Taken from the memo, the
// manifold must be the one the full test builds, bit for bit; at any other pose the memo
// must not be used.
#include <gtest/gtest.h>

#include <cstring>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

using detail::NarrowphaseSettings;
using detail::NormalMemo;

// The landing correction's settings: no reach, points kept up to the speculative distance.
NarrowphaseSettings landingSettings() {
    NarrowphaseSettings s;
    s.touchMargin = s.speculativeDistance;
    return s;
}

// The narrowphase's: a reach for a pair closing in, the slop as touch margin.
NarrowphaseSettings stepSettings() {
    NarrowphaseSettings s;
    s.reach = 0.01;
    s.touchMargin = 0.005;
    return s;
}

void expectSameBits(const std::vector<Manifold> &x, const std::vector<Manifold> &y) {
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
        EXPECT_EQ(std::memcmp(x[k].normal.data(), y[k].normal.data(), sizeof(Vector3)), 0) << "manifold " << k;
        ASSERT_EQ(x[k].count, y[k].count) << "manifold " << k;
        for (int i = 0; i < x[k].count; ++i) {
            const detail::ContactPoint &p = x[k].points[static_cast<std::size_t>(i)];
            const detail::ContactPoint &q = y[k].points[static_cast<std::size_t>(i)];
            EXPECT_EQ(std::memcmp(p.pointA.data(), q.pointA.data(), sizeof(Vector3)), 0) << "point " << i;
            EXPECT_EQ(std::memcmp(p.pointB.data(), q.pointB.data(), sizeof(Vector3)), 0) << "point " << i;
            EXPECT_EQ(std::memcmp(&p.depth, &q.depth, sizeof(real)), 0) << "point " << i;
        }
    }
}

// A cylinder (r = 0.4, 1 m long) standing tilted 0.3 rad on a convex unit cube, its lowest
// rim point 2 cm into the cube's top (y = 0.5): a pair whose normal FCL's MPR only starts
// and the refinement finishes (the costliest kind to test).
struct TiltedCylinderOnCube {
    std::shared_ptr<const CollisionShape> cylinder = detail::compileShape(Shape::cylinder(0.4, 1));
    std::shared_ptr<const CollisionShape> cube = detail::compileShape(convexCube(0.5));
    Matrix4 poseCylinder = pose(Vector3::Zero(), rotation(0.3, Vector3::UnitX()) * zUp());
    Matrix4 poseCube = pose(Vector3::Zero());

    TiltedCylinderOnCube() {
        const real lowest = cylinder->supportPoint(poseCylinder, -Vector3::UnitY(), -1).y();
        poseCylinder.translation().y() = 0.5 - 0.02 - lowest;
    }
};

TEST(NormalMemo, TheNextTestAtTheSamePosesBuildsTheFullTestsManifold) {
    const TiltedCylinderOnCube pair;
    NormalMemo memo;
    std::vector<Manifold> landing;
    detail::collide(*pair.cylinder, pair.poseCylinder, *pair.cube, pair.poseCube, landingSettings(), landing, &memo);
    ASSERT_EQ(landing.size(), 1u);
    EXPECT_TRUE(memo.holds(*pair.cylinder, pair.poseCylinder, *pair.cube, pair.poseCube));
    EXPECT_TRUE(memo.touching);
    // The rim stands on the cube's top face: the normal, A to B, points down.
    EXPECT_LT((memo.normal - kDown).norm(), 1e-6);

    std::vector<Manifold> full, fromMemo;
    detail::collide(*pair.cylinder, pair.poseCylinder, *pair.cube, pair.poseCube, stepSettings(), full);
    detail::collide(*pair.cylinder, pair.poseCylinder, *pair.cube, pair.poseCube, stepSettings(), fromMemo, &memo);
    ASSERT_EQ(full.size(), 1u);
    EXPECT_NEAR(deepestDepth(full[0]), 0.02, 1e-6);
    expectSameBits(full, fromMemo);
}

// A memo planted with a normal no test would choose (+x, across the stacking): it is
// taken at exactly its poses, and at a pose a nanometre off the pair is tested afresh and
// the memo replaced. An upright cylinder (r = 0.4, 1 m long) stands on a convex unit cube
// (a pair FCL tests: boxes and hulls have a test of their own).
TEST(NormalMemo, IsTakenAtItsPosesOnlyAndReplacedElsewhere) {
    const auto cube = detail::compileShape(convexCube(0.5));
    const auto cylinder = detail::compileShape(Shape::cylinder(0.4, 1));
    const Matrix4 below = pose(Vector3::Zero());
    const Matrix4 above = pose(Vector3(0, 0.95, 0), zUp());  // 5 cm into the cube
    NormalMemo memo;
    memo.keep(*cylinder, above, *cube, below, true, Vector3::UnitX());

    std::vector<Manifold> planted;
    detail::collide(*cylinder, above, *cube, below, stepSettings(), planted, &memo);
    ASSERT_EQ(planted.size(), 1u);
    EXPECT_EQ(planted[0].normal, Vector3::UnitX());

    const Matrix4 moved = pose(Vector3(0, 0.95 + 1e-9, 0), zUp());
    std::vector<Manifold> fresh;
    detail::collide(*cylinder, moved, *cube, below, stepSettings(), fresh, &memo);
    ASSERT_EQ(fresh.size(), 1u);
    EXPECT_LT((fresh[0].normal - kDown).norm(), 1e-9);
    EXPECT_NEAR(deepestDepth(fresh[0]), 0.05, 1e-6);
    EXPECT_TRUE(memo.holds(*cylinder, moved, *cube, below));
    EXPECT_FALSE(memo.holds(*cylinder, above, *cube, below));
    EXPECT_LT((memo.normal - kDown).norm(), 1e-9);
    // Another pair of shapes at the same poses is not the memo's either.
    const auto other = detail::compileShape(Shape::cylinder(0.4, 1));
    EXPECT_FALSE(memo.holds(*other, moved, *cube, below));
}

// A convex unit cube and an upright cylinder (r = 0.5) whose side lies 0.3 m beyond the
// cube's +x face: FCL finds no contact, and the memo says so; taken from it, the
// speculative manifold within the reach is the full test's.
TEST(NormalMemo, RemembersShapesApartAndGivesTheSameSpeculativeManifold) {
    const auto cube = detail::compileShape(convexCube(0.5));
    const auto cylinder = detail::compileShape(Shape::cylinder(0.5, 1));
    const Matrix4 poseA = pose(Vector3::Zero());
    const Matrix4 poseB = pose(Vector3(1.3, 0, 0), zUp());
    NarrowphaseSettings reaching;
    reaching.reach = 0.31;
    NormalMemo memo;
    std::vector<Manifold> first, second;
    detail::collide(*cube, poseA, *cylinder, poseB, reaching, first, &memo);
    EXPECT_TRUE(memo.holds(*cube, poseA, *cylinder, poseB));
    EXPECT_FALSE(memo.touching);
    ASSERT_EQ(first.size(), 1u);
    EXPECT_NEAR(first[0].normal.x(), 1, 1e-6);
    EXPECT_NEAR(deepestDepth(first[0]), -0.3, 1e-6);
    detail::collide(*cube, poseA, *cylinder, poseB, reaching, second, &memo);
    expectSameBits(first, second);
}

}  // namespace
}  // namespace cyclone::test
