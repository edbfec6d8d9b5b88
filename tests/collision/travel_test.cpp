// travel() and its quick bound travelWithin() (collision/time_of_impact.h), which the
// landing correction uses to pass over bodies that surely did not move fast.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision/time_of_impact.h"

namespace cyclone::test {
namespace {

using detail::travel;
using detail::travelWithin;

Matrix4 pose(const Vector3 &position, const Quaternion &orientation) {
    Matrix4 m = Matrix4::Identity();
    m.linear() = orientation.toRotationMatrix();
    m.translation() = position;
    return m;
}

// 3 mm straight along x: travel is 3 mm; the bound clears 4 mm, not 3 mm (its margin).
TEST(Travel, TranslationAloneIsItsLength) {
    const Matrix4 from = pose(Vector3(1, 2, 3), Quaternion::Identity());
    const Matrix4 to = pose(Vector3(1.003, 2, 3), Quaternion::Identity());
    EXPECT_NEAR(travel(from, to, 0.5), 0.003, 1e-12);
    EXPECT_TRUE(travelWithin(from, to, 0.5, 0.004));
    EXPECT_FALSE(travelWithin(from, to, 0.5, 0.003));
}

// A turn of 0.01 rad with radius 0.5 m: travel 5 mm. The bound is about pi / 2 times it
// (7.85 mm): it clears 7.9 mm but not 7.8 mm.
TEST(Travel, SmallTurnIsBoundedByHalfPiTimesIt) {
    const Matrix4 from = pose(Vector3::Zero(), Quaternion::Identity());
    const Matrix4 to = pose(Vector3::Zero(), Quaternion(Eigen::AngleAxis<real>(0.01, Vector3(1, 2, 2) / 3)));
    EXPECT_NEAR(travel(from, to, 0.5), 0.005, 1e-12);
    EXPECT_TRUE(travelWithin(from, to, 0.5, 0.0079));
    EXPECT_FALSE(travelWithin(from, to, 0.5, 0.0078));
}

// Whenever the bound clears a limit, travel() is below it: random poses of every turn
// up to pi, radii 0.01-3 m, limits around the travel.
TEST(Travel, BoundNeverClearsALimitTheTravelReaches) {
    std::mt19937 random(7);
    std::uniform_real_distribution<real> unit(-1, 1);
    int cleared = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vector3 axis = Vector3(unit(random), unit(random), unit(random)).normalized();
        const real angle = std::abs(unit(random)) * (i % 2 ? 3.14159 : 0.001);
        const Quaternion start(Eigen::AngleAxis<real>(3 * unit(random), Vector3(unit(random), 1, unit(random)).normalized()));
        const Matrix4 from = pose(Vector3(unit(random), unit(random), unit(random)), start);
        const Matrix4 to = pose(from.translation() + 0.01 * Vector3(unit(random), unit(random), unit(random)),
                                Quaternion(Eigen::AngleAxis<real>(angle, axis)) * start);
        const real radius = 0.01 + 1.5 * (1 + unit(random));
        const real exact = travel(from, to, radius);
        const real limit = exact * (1 + unit(random));  // 0 to twice the travel
        if (travelWithin(from, to, radius, limit)) {
            ++cleared;
            ASSERT_LT(exact, limit) << "case " << i;
        }
    }
    EXPECT_GT(cleared, 1000);  // the bound does clear limits well above the travel
}

}  // namespace
}  // namespace cyclone::test
