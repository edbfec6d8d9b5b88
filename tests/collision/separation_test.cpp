// separation(): the distance and direction between convex solids apart, by GJK on their
// cores, checked on poses worked out by hand and against FCL's distance query on random
// poses (FCL stays the reference).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision/separation.h"
#include "collision_test_support.h"

namespace cyclone::test {
namespace {

struct Gap {
    bool apart = false;
    real distance = 0;
    Vector3 direction = Vector3::Zero();
};

Gap gapOf(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB) {
    const auto compiledA = detail::compileShape(a);
    const auto compiledB = detail::compileShape(b);
    Gap g;
    g.apart = detail::separation(*compiledA, poseA, *compiledB, poseB, g.distance, g.direction);
    return g;
}

// A sphere of radius 0.5 at the origin and a capsule of radius 0.2 standing along z at
// x = 2: the nearest points are on the x axis, 2 - 0.5 - 0.2 = 1.3 m apart.
TEST(Separation, SphereAndCapsuleSideBySide) {
    const Gap g = gapOf(Shape::sphere(0.5), pose(Vector3::Zero()), Shape::capsule(0.2, 1), pose(Vector3(2, 0, 0)));
    ASSERT_TRUE(g.apart);
    EXPECT_NEAR(g.distance, 1.3, 1e-9);
    EXPECT_NEAR(g.direction.x(), 1, 1e-9);
}

// Two capsules of radius 0.2 along z, one 1 m long at the origin (ends at z = +-0.5), one
// 0.6 m long at z = 1.5 (ends at 1.2 and 1.8): end to end, 1.2 - 0.5 - 0.4 = 0.3 m apart.
TEST(Separation, CapsulesEndToEnd) {
    const Gap g = gapOf(Shape::capsule(0.2, 1), pose(Vector3::Zero()), Shape::capsule(0.2, 0.6),
                        pose(Vector3(0, 0, 1.5)));
    ASSERT_TRUE(g.apart);
    EXPECT_NEAR(g.distance, 0.3, 1e-9);
    EXPECT_NEAR(g.direction.z(), 1, 1e-9);
}

// Two cylinders of radius 0.3 with parallel axes (z) 1 m apart along x: their sides are
// 1 - 0.6 = 0.4 m apart. The curved sides are where GJK creeps: 1e-9 m still holds.
TEST(Separation, CylindersSideBySide) {
    const Shape cylinder = Shape::cylinder(0.3, 1);
    const Gap g = gapOf(cylinder, pose(Vector3::Zero()), cylinder, pose(Vector3(1, 0, 0)));
    ASSERT_TRUE(g.apart);
    EXPECT_NEAR(g.distance, 0.4, 1e-9);
    EXPECT_NEAR(g.direction.x(), 1, 1e-9);
}

// A cylinder (radius 0.3, 1 m long along z) under a unit cube whose centre is at z = 2:
// the cap at z = 0.5 faces the cube's bottom face at z = 1.5, 1 m above, and a cube
// turned 45 degrees about z gives the same.
TEST(Separation, CylinderCapUnderABoxFace) {
    const Shape box = Shape::box(Vector3(0.5, 0.5, 0.5));
    for (const Quaternion &turn : {Quaternion::Identity(), rotation(kPi / 4, Vector3::UnitZ())}) {
        const Gap g = gapOf(Shape::cylinder(0.3, 1), pose(Vector3::Zero()), box, pose(Vector3(0, 0, 2), turn));
        ASSERT_TRUE(g.apart);
        EXPECT_NEAR(g.distance, 1, 1e-9);
        EXPECT_NEAR(g.direction.z(), 1, 1e-9);
    }
}

// Overlapping or touching shapes are not apart: two unit cubes 0.9 m apart centre to
// centre overlap by 0.1 m; spheres of radius 0.5 whose centres are 1 m apart touch.
TEST(Separation, OverlappingOrTouchingAreNotApart) {
    const Shape cube = Shape::box(Vector3(0.5, 0.5, 0.5));
    EXPECT_FALSE(gapOf(cube, pose(Vector3::Zero()), cube, pose(Vector3(0.9, 0.1, 0))).apart);
    const Shape ball = Shape::sphere(0.5);
    EXPECT_FALSE(gapOf(ball, pose(Vector3::Zero()), ball, pose(Vector3(1, 0, 0))).apart);
}

// Random shapes and poses, 0.5-2 m apart centre to centre: wherever FCL's distance query
// (libccd) finds them apart by more than 1 mm, separation() must too. Both distances are
// those of a point of A - B, so at or above the true one; the support gap along
// separation()'s direction is at or below it (no line separates two convex sets by more
// than their distance). So the gap must not exceed FCL's distance, separation()'s distance
// must not exceed FCL's (libccd stops within its tolerance, on curved sides up to 0.1 mm
// above: it is the looser bound), and the gap must lie within 1 um of separation()'s
// distance: the true distance is then known to 1 um.
TEST(Separation, AgreesWithFclOnRandomPoses) {
    std::mt19937 random(62);
    std::uniform_real_distribution<real> uniform(-1, 1);
    const std::vector<Vector3> rock = {{0.3, 0, 0}, {-0.25, 0.05, 0}, {0, 0.3, 0.1}, {0, -0.2, 0}, {0, 0, 0.3},
                                       {0.1, 0, -0.3}, {0.2, 0.2, 0.2}, {-0.2, -0.1, 0.2}};
    const std::vector<Shape> shapes = {Shape::box(Vector3(0.3, 0.2, 0.25)), Shape::sphere(0.3), Shape::capsule(0.2, 0.4),
                                       Shape::cylinder(0.3, 0.5), Shape::convex(rock)};
    auto orientation = [&] {
        return Quaternion(
            Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
    };
    fcl::DistanceRequestd request(true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    // Rounding: on a curved side GJK's last simplex has vertices less than a micrometre
    // apart, and its nearest point (either library's) comes out up to ~2e-8 m off.
    constexpr real kRounding = 1e-7;
    int compared = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        const auto a = detail::compileShape(shapes[static_cast<std::size_t>(trial) % shapes.size()]);
        const auto b = detail::compileShape(shapes[static_cast<std::size_t>(trial / 5) % shapes.size()]);
        const Vector3 line = Vector3(uniform(random), uniform(random), uniform(random)).normalized();
        const Matrix4 poseA = pose(Vector3::Zero(), orientation());
        const Matrix4 poseB = pose((1.25 + 0.75 * uniform(random)) * line, orientation());
        fcl::DistanceResultd result;
        const real reference = fcl::distance(a->geometry().get(), poseA, b->geometry().get(), poseB, request, result);
        real distance = 0;
        Vector3 direction;
        const bool apart = detail::separation(*a, poseA, *b, poseB, distance, direction);
        if (!(reference > 1e-3)) continue;
        ++compared;
        ASSERT_TRUE(apart);
        const real gap = -(a->supportPoint(poseA, direction, -1) - b->supportPoint(poseB, -direction, -1)).dot(direction);
        EXPECT_LE(gap, reference + kRounding);
        EXPECT_LE(distance, reference + kRounding);
        EXPECT_LE(gap, distance + kRounding);
        EXPECT_LT(distance - gap, 1e-6);
    }
    // Most random poses at these distances are apart.
    EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace cyclone::test
