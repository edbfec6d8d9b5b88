// Pairs that FCL would test (here two convex hulls) lying apart: within the reach they get
// a speculative manifold along the line between their nearest faces, beyond it none. The
// narrowphase rules the second out by a separating axis before FCL runs (the placed
// boxes, or the extents along the line between the origins: narrowphase.cpp), which must
// never drop a pair within the reach.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

std::vector<Manifold> collideWithReach(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB,
                                       real reach) {
    const auto compiledA = detail::compileShape(a);
    const auto compiledB = detail::compileShape(b);
    detail::NarrowphaseSettings settings;
    settings.reach = reach;
    std::vector<Manifold> out;
    detail::collide(*compiledA, poseA, *compiledB, poseB, settings, out);
    return out;
}

// Unit cubes 1.3 m apart along x: their facing faces are 0.3 m apart, and so are their
// boxes.
TEST(SeparatedPairs, HullsApartAlongAnAxisMeetWithinTheReachOnly) {
    const Shape cube = convexCube(0.5);
    const Matrix4 poseA = pose(Vector3(0, 0, 0));
    const Matrix4 poseB = pose(Vector3(1.3, 0, 0));
    EXPECT_TRUE(collideWithReach(cube, poseA, cube, poseB, 0.29).empty());
    const std::vector<Manifold> within = collideWithReach(cube, poseA, cube, poseB, 0.31);
    ASSERT_EQ(within.size(), 1u);
    EXPECT_NEAR(within[0].normal.x(), 1, 1e-6);
    EXPECT_NEAR(deepestDepth(within[0]), -0.3, 1e-6);
}

// Both cubes turned 45 degrees about z, B at (1.2, 1.2, 0): their boxes (0.707 m half
// wide) overlap, but along the diagonal (1, 1, 0)/sqrt(2), the line between their
// origins, the facing faces are 1.2 sqrt(2) - 1 = 0.697 m apart.
TEST(SeparatedPairs, HullsApartAlongTheLineBetweenThemMeetWithinTheReachOnly) {
    const Shape cube = convexCube(0.5);
    const Quaternion turned = rotation(kPi / 4, Vector3::UnitZ());
    const Matrix4 poseA = pose(Vector3(0, 0, 0), turned);
    const Matrix4 poseB = pose(Vector3(1.2, 1.2, 0), turned);
    const real gap = 1.2 * std::sqrt(2.0) - 1;
    EXPECT_TRUE(collideWithReach(cube, poseA, cube, poseB, gap - 0.01).empty());
    const std::vector<Manifold> within = collideWithReach(cube, poseA, cube, poseB, gap + 0.01);
    ASSERT_EQ(within.size(), 1u);
    EXPECT_NEAR(within[0].normal.x(), std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(within[0].normal.y(), std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(deepestDepth(within[0]), -gap, 1e-6);
}

}  // namespace
}  // namespace cyclone::test
