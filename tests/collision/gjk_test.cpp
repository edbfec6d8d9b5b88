// GJK's nearest point to the origin (collision/gjk.h), cold and started from the vertices
// of an earlier search, and its proof that a set lies farther than a gap: against a box and
// an upright cylinder placed by hand, whose nearest points are worked out from their faces
// and side.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/gjk.h"

namespace cyclone::test {
namespace {

// A box of half extents h centred at c, moved by `shift`.
struct Box {
    Vector3 c, h, shift = Vector3::Zero();
    Vector3 operator()(const Vector3 &d) const {
        Vector3 p;
        for (int k = 0; k < 3; ++k) p[k] = c[k] + (d[k] >= 0 ? h[k] : -h[k]);
        return p + shift;
    }
};

// A cylinder along z, radius r, half length l, centred at c, moved by `shift`.
struct Cylinder {
    Vector3 c;
    real r, l;
    Vector3 shift = Vector3::Zero();
    Vector3 operator()(const Vector3 &d) const {
        const Vector3 radial(d.x(), d.y(), 0);
        const real length = radial.norm();
        Vector3 p = c + Vector3(0, 0, d.z() >= 0 ? l : -l);
        if (length > 1e-12) p += r / length * radial;
        return p + shift;
    }
    // Whether p lies in the cylinder (within `tolerance`, m).
    bool holds(const Vector3 &p, real tolerance) const {
        const Vector3 q = p - c - shift;
        return std::hypot(q.x(), q.y()) <= r + tolerance && std::abs(q.z()) <= l + tolerance;
    }
};

TEST(Gjk, NearestPointOfABoxIsOnItsNearFace) {
    // Faces at x = 4 .. 6, y = -2 .. 2, z = -3 .. 3: the origin's nearest point is (4, 0, 0).
    const Box box{Vector3(5, 0, 0), Vector3(1, 2, 3)};
    Vector3 closest;
    ASSERT_TRUE(detail::closestToOrigin(box, Vector3::UnitX(), closest));
    EXPECT_NEAR((closest - Vector3(4, 0, 0)).norm(), 0, 1e-12);
}

TEST(Gjk, NearestPointOfACylinderIsOnItsSide) {
    // Axis through (0, 4) from z = -0.5 to 1.5, radius 1: the side's nearest point is (0, 3, 0).
    const Cylinder cylinder{Vector3(0, 4, 0.5), 1, 1};
    Vector3 closest;
    ASSERT_TRUE(detail::closestToOrigin(cylinder, Vector3(0.3, 1, 0.2).normalized(), closest));
    EXPECT_NEAR(closest.norm(), 3, 1e-8);
    EXPECT_NEAR((closest - Vector3(0, 3, 0)).norm(), 0, 1e-4);
}

TEST(Gjk, AWarmStartFindsTheSamePointAndKeepsItsVerticesInTheSet) {
    Cylinder cylinder{Vector3(0, 4, 0.5), 1, 1};
    detail::GjkSimplex simplex;
    Vector3 first;
    ASSERT_TRUE(detail::closestToOrigin(cylinder, Vector3(0.3, 1, 0.2).normalized(), first, &simplex));
    ASSERT_GT(simplex.count, 0);
    ASSERT_LE(simplex.count, 3);
    // The set moved: its nearest point moves with it to (0.2, 2.7, 0) (the side at
    // x = 0.2 is nearest the origin along the line through the axis (0.2, 3.7)).
    const Vector3 shift(0.2, -0.3, 0);
    cylinder.shift = shift;
    for (int k = 0; k < simplex.count; ++k) simplex.points[k] += shift;
    Vector3 warm, cold;
    ASSERT_TRUE(detail::closestToOrigin(cylinder, -Vector3::UnitY(), warm, &simplex));
    ASSERT_TRUE(detail::closestToOrigin(cylinder, -Vector3::UnitY(), cold));
    const Vector3 axis(0.2, 3.7, 0);
    const Vector3 expected = axis - axis.normalized();
    EXPECT_NEAR(warm.norm(), expected.norm(), 1e-8);
    EXPECT_NEAR((warm - expected).norm(), 0, 1e-4);
    EXPECT_NEAR((warm - cold).norm(), 0, 1e-4);
    for (int k = 0; k < simplex.count; ++k) EXPECT_TRUE(cylinder.holds(simplex.points[k], 1e-12)) << "vertex " << k;
}

TEST(Gjk, AnEmptyWarmStartIsTheColdSearch) {
    const Box box{Vector3(3, -2, 1), Vector3(0.5, 1, 0.25)};
    detail::GjkSimplex simplex;
    Vector3 warm, cold;
    ASSERT_TRUE(detail::closestToOrigin(box, Vector3(1, 1, 1).normalized(), warm, &simplex));
    ASSERT_TRUE(detail::closestToOrigin(box, Vector3(1, 1, 1).normalized(), cold));
    EXPECT_EQ(warm, cold);
}

TEST(Gjk, TheOriginInsideEndsTheSearchAndEmptiesTheWarmStart) {
    const Box box{Vector3(0.2, 0, 0), Vector3(1, 1, 1)};
    detail::GjkSimplex simplex;
    simplex.points[0] = Vector3(1.2, 1, 1);  // a corner: in the set
    simplex.count = 1;
    Vector3 closest;
    EXPECT_FALSE(detail::closestToOrigin(box, Vector3::UnitX(), closest, &simplex));
    EXPECT_EQ(simplex.count, 0);
}

TEST(Gjk, FartherThanHoldsJustBelowTheDistanceAndNotAbove) {
    // Side at distance 3 from the origin (axis through (0, 4), radius 1).
    const Cylinder cylinder{Vector3(0, 4, 0.5), 1, 1};
    const Vector3 start = Vector3(0.3, 1, 0.2).normalized();
    EXPECT_TRUE(detail::fartherThan(cylinder, start, 2.999));
    EXPECT_FALSE(detail::fartherThan(cylinder, start, 3.001));
    // Box faces at x = 4 .. 6: distance 4, seen along any start.
    const Box box{Vector3(5, 0, 0), Vector3(1, 2, 3)};
    for (const Vector3 &d : {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(-1, 0, 0)}) {
        EXPECT_TRUE(detail::fartherThan(box, d, 3.999));
        EXPECT_FALSE(detail::fartherThan(box, d, 4.001));
    }
}

TEST(Gjk, FartherThanIsFalseForASetAroundTheOrigin) {
    const Box box{Vector3(0.2, 0, 0), Vector3(1, 1, 1)};
    EXPECT_FALSE(detail::fartherThan(box, Vector3::UnitX(), 0));
    EXPECT_FALSE(detail::fartherThan(box, Vector3::UnitY(), 0));
}

}  // namespace
}  // namespace cyclone::test
