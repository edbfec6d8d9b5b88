// Pairs that FCL would test (convex hulls, a cylinder and a hull) lying apart: within the
// reach they get a speculative manifold along the line between their nearest faces, beyond
// it none. The narrowphase rules the second out by a separating axis before FCL runs (the
// placed boxes, the extents along the line between the origins, or GJK's lower bound on
// the distance: narrowphase.cpp), which must never drop a pair within the reach.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

// The pair's manifolds; `wasApart` as for a pair that had none at its last test.
std::vector<Manifold> collideWithReach(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB,
                                       real reach, bool wasApart = true) {
    const auto compiledA = detail::compileShape(a);
    const auto compiledB = detail::compileShape(b);
    detail::NarrowphaseSettings settings;
    settings.reach = reach;
    settings.wasApart = wasApart;
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

// A cylinder (radius 0.5, along z) at the origin and a unit hull cube turned 45 degrees
// about z at (1.1, 0.6, 0). Their boxes overlap, and along the line between their origins
// they are only 0.13 m apart. The cube's face nearest the axis lies on x + y = 1.7 - h
// (h = sqrt(0.5), the corner's reach from the cube's centre), (1.7 - h) h from the axis:
// the solids are that less 0.5 apart, 0.2021 m, along (1, 1, 0) / sqrt(2).
TEST(SeparatedPairs, CylinderAndHullApartByTheirNearestPointsMeetWithinTheReachOnly) {
    const Shape cylinder = Shape::cylinder(0.5, 1.0);
    const Matrix4 poseA = pose(Vector3::Zero());
    const Matrix4 poseB = pose(Vector3(1.1, 0.6, 0), rotation(kPi / 4, Vector3::UnitZ()));
    const real h = std::sqrt(0.5);
    const real gap = (1.7 - h) * h - 0.5;
    EXPECT_TRUE(collideWithReach(cylinder, poseA, convexCube(0.5), poseB, gap - 0.01).empty());
    EXPECT_TRUE(collideWithReach(cylinder, poseA, convexCube(0.5), poseB, gap - 0.01, false).empty());
    const std::vector<Manifold> within = collideWithReach(cylinder, poseA, convexCube(0.5), poseB, gap + 0.01);
    ASSERT_EQ(within.size(), 1u);
    EXPECT_NEAR(within[0].normal.x(), h, 1e-4);
    EXPECT_NEAR(within[0].normal.y(), h, 1e-4);
    EXPECT_NEAR(deepestDepth(within[0]), -gap, 1e-6);
}

// Random poses of the pairs FCL tests, within about a reach of each other: whenever FCL
// finds them touching, or apart by less than the reach, they get a manifold.
TEST(SeparatedPairs, NoRuleDropsAPairThatFclFindsWithinTheReach) {
    const std::vector<std::shared_ptr<const detail::CollisionShape>> shapes = {
        detail::compileShape(Shape::cylinder(0.3, 0.8)), detail::compileShape(Shape::capsule(0.25, 0.5)),
        detail::compileShape(Shape::box(Vector3(0.4, 0.2, 0.3))), detail::compileShape(pyramid()),
        detail::compileShape(Shape::sphere(0.3))};
    std::mt19937 random(5);
    std::uniform_real_distribution<real> uniform(-1, 1);
    fcl::DistanceRequestd request(true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    int within = 0, beyond = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        // A cylinder against each of the others (cylinder pairs are the ones FCL tests).
        const detail::CollisionShape &a = *shapes[0];
        const detail::CollisionShape &b = *shapes[trial % shapes.size()];
        const Quaternion qa(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
        const Quaternion qb(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
        const Matrix4 poseA = pose(Vector3::Zero(), qa);
        const Matrix4 poseB = pose(0.9 * Vector3(uniform(random), uniform(random), uniform(random)), qb);
        const real reach = 0.05;
        fcl::DistanceResultd result;
        const real distance = fcl::distance(a.geometry().get(), fcl::Transform3d(poseA.matrix()), b.geometry().get(),
                                            fcl::Transform3d(poseB.matrix()), request, result);
        within += distance < reach - 1e-6;
        beyond += distance > reach + 0.002;
        for (const bool wasApart : {true, false}) {
            detail::NarrowphaseSettings settings;
            settings.reach = reach;
            settings.wasApart = wasApart;
            std::vector<Manifold> out;
            detail::collide(a, poseA, b, poseB, settings, out);
            if (distance < reach - 1e-6) {
                EXPECT_FALSE(out.empty()) << "FCL's distance " << distance << " m";
            } else if (distance > reach + 0.002) {
                EXPECT_TRUE(out.empty()) << "FCL's distance " << distance << " m";
            }
        }
    }
    // Both kinds are common at these poses.
    EXPECT_GT(within, 1000);
    EXPECT_GT(beyond, 500);
}

}  // namespace
}  // namespace cyclone::test
