// CollisionShape::innerRadius: a ball about the shape's origin that the shape holds, which
// lets the normal search skip candidates whose overlap is surely too large
// (Pair::overlapExceeds). Checked by hand and against FCL: a small sphere just inside the
// ball touches the shape wherever it is put; one just past the nearest face does not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision/contact_building.h"
#include "collision_test_support.h"

namespace cyclone::test {
namespace {

bool fclTouches(const CollisionShape &shape, const Vector3 &ballCentre, real ballRadius) {
    const auto ball = detail::compileShape(Shape::sphere(ballRadius));
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    return fcl::collide(shape.geometry().get(), Matrix4::Identity(), ball->geometry().get(), pose(ballCentre), request,
                        result) > 0;
}

// Box: its smallest half extent. Cylinder: the smaller of radius and half length.
// Capsule and sphere: the radius. The pyramid's base lies 0.25 m below its origin and its
// sides x + 0.4 y = 0.3 (through (0.4, -0.25, z) and the apex (0, 0.75, 0)) lie
// 0.3 / sqrt(1.16) = 0.279 m from it: the base is nearest. A hull that misses its origin
// has no ball about it.
TEST(InnerRadius, WorkedOutByHand) {
    EXPECT_DOUBLE_EQ(detail::compileShape(Shape::box(Vector3(0.3, 0.2, 0.25)))->innerRadius(), 0.2);
    EXPECT_DOUBLE_EQ(detail::compileShape(Shape::cylinder(0.3, 0.5))->innerRadius(), 0.25);
    EXPECT_DOUBLE_EQ(detail::compileShape(Shape::cylinder(0.2, 1.0))->innerRadius(), 0.2);
    EXPECT_DOUBLE_EQ(detail::compileShape(Shape::capsule(0.2, 0.4))->innerRadius(), 0.2);
    EXPECT_DOUBLE_EQ(detail::compileShape(Shape::sphere(0.3))->innerRadius(), 0.3);
    EXPECT_NEAR(detail::compileShape(pyramid())->innerRadius(), 0.25, 1e-12);
    std::vector<Vector3> away;
    for (int i = 0; i < 8; ++i) away.emplace_back(i & 1 ? 2.5 : 1.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    EXPECT_EQ(detail::compileShape(Shape::convex(away))->innerRadius(), -1);
    EXPECT_EQ(detail::compileShape(Shape::plane(Vector3::UnitY(), 0))->innerRadius(), -1);
}

// A 1 mm ball centred 2 mm inside the inner ball, in any direction, lies inside the shape:
// FCL finds them touching. For the pyramid one centred 2 mm below its base misses it (the
// ball is as large as it can be).
TEST(InnerRadius, FclFindsTheBallInsideTheShape) {
    std::mt19937 random(62);
    std::uniform_real_distribution<real> uniform(-1, 1);
    for (const Shape &shape : {Shape::box(Vector3(0.3, 0.2, 0.25)), Shape::cylinder(0.3, 0.5), Shape::capsule(0.2, 0.4),
                               pyramid(), convexCube(0.4)}) {
        const auto compiled = detail::compileShape(shape);
        const real r = compiled->innerRadius();
        ASSERT_GT(r, 0);
        for (int trial = 0; trial < 200; ++trial) {
            const Vector3 u = Vector3(uniform(random), uniform(random), uniform(random)).normalized();
            EXPECT_TRUE(fclTouches(*compiled, (r - 0.002) * u, 0.001));
        }
    }
    const auto pyramidShape = detail::compileShape(pyramid());
    EXPECT_FALSE(fclTouches(*pyramidShape, Vector3(0, -0.25 - 0.002, 0), 0.001));
}

// Pair::overlapExceeds never claims more than the overlap by support points: over random
// poses and directions, wherever it says the overlap exceeds a level, it does.
TEST(InnerRadius, OverlapBoundHoldsOnRandomPoses) {
    std::mt19937 random(7);
    std::uniform_real_distribution<real> uniform(-1, 1);
    const auto a = detail::compileShape(Shape::cylinder(0.3, 0.5));
    const auto b = detail::compileShape(pyramid());
    int ruledOut = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Quaternion qa(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
        const Quaternion qb(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
        const Matrix4 poseA = pose(Vector3(uniform(random), uniform(random), uniform(random)), qa);
        const Matrix4 poseB = pose(Vector3(uniform(random), uniform(random), uniform(random)), qb);
        const detail::Pair pair{*a, poseA, -1, *b, poseB, -1, 0.02, 0};
        const Vector3 n = Vector3(uniform(random), uniform(random), uniform(random)).normalized();
        const real level = 0.5 * uniform(random);
        if (!pair.overlapExceeds(n, level)) continue;
        ++ruledOut;
        EXPECT_GT(pair.overlap(n), level);
    }
    EXPECT_GT(ruledOut, 100);
}

}  // namespace
}  // namespace cyclone::test
