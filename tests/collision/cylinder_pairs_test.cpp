// Cylinder pairs (collision/cylinder_pairs.cpp): two round sides from their closest
// features at any depth (one point crossed, two parallel), a capsule on a cylinder's
// side, pairs apart; and through FCL's path, a tilted cylinder's rim on a lying
// cylinder's side (with its other end's point) and a lying cylinder on a standing one's
// cap. Every expectation worked out by hand, in both argument orders.
//
// A cylinder's axis is its local z; zAlongX() lays it along world x, the identity pose
// along world z, zUp() along world y. Unless a test says otherwise A comes from above,
// so the normal from A to B is -y.
#include <gtest/gtest.h>

#include <cmath>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

ExpectedPoint pointPair(const Vector3 &pointA, const Vector3 &pointB) { return {pointA, pointB}; }

TEST(CylinderPairs, CrossedLyingCylindersAtAnyDepth) {
    // A (radius 0.25, length 1) along x at (0, y, 0) lies across B (the same) along z at
    // the origin. The axes' closest points are (0, y, 0) and the origin, inside both
    // segments: the normal is -y and the depth 0.25 + 0.25 - y, one point where A's lowest
    // line (y - 0.25) crosses B's highest (0.25). Along either axis the projections overlap
    // by 0.5 + 0.25 = 0.75, more than any depth here. At 0.4 m (y = 0.1) MPR's normal is
    // only approximate; the cores' is exact at any depth.
    const Shape cylinder = Shape::cylinder(0.25, 1);
    for (const real y : {0.49, 0.4, 0.25, 0.1}) {
        SCOPED_TRACE(y);
        Expected e;
        e.normal = kDown;
        e.depth = 0.5 - y;
        e.points.push_back(pointPair(Vector3(0, y - 0.25, 0), Vector3(0, 0.25, 0)));
        expectContact(cylinder, pose(Vector3(0, y, 0), zAlongX()), cylinder, pose(Vector3::Zero()), e);
    }
}

TEST(CylinderPairs, ParallelLyingCylindersGiveTwoPoints) {
    // Both (radius 0.25, length 1) along x; A at (0, y, 0), B at (0.3, 0, 0). The axes
    // are parallel, y apart: normal -y, depth 0.5 - y (taken across the middle of the
    // common stretch, x = 0.15, 0.35 from either end). A's lowest line x in [-0.5, 0.5]
    // over B's highest, x in [-0.2, 0.8]: the overlap's ends x = -0.2 and 0.5 are the
    // points. Along x the projections overlap by 0.5 + 0.2 = 0.7, more than either depth.
    const Shape cylinder = Shape::cylinder(0.25, 1);
    for (const real y : {0.49, 0.3}) {
        SCOPED_TRACE(y);
        Expected e;
        e.normal = kDown;
        e.depth = 0.5 - y;
        for (const real x : {-0.2, 0.5}) e.points.push_back(pointPair(Vector3(x, y - 0.25, 0), Vector3(x, 0.25, 0)));
        expectContact(cylinder, pose(Vector3(0, y, 0), zAlongX()), cylinder, pose(Vector3(0.3, 0, 0), zAlongX()), e);
    }
}

TEST(CylinderPairs, TiltedRimOnALyingCylinderSide) {
    // B (radius R = 0.25, length 2) lies along x at the origin. A (radius r = 0.2, length
    // 1) is tilted alpha = 9 degrees from lying, its axis a = (cos alpha, -sin alpha, 0),
    // its lower end's centre at E = (0.3, h, 0). The axes lie in the plane z = 0 and meet
    // beyond E, so the closest points are E and (0.3, 0, 0) on B's axis. A's lowest point
    // is the rim point P = E + r (-sin alpha, -cos alpha, 0) (of the rim E + r (cos t u +
    // sin t z), u = (-sin alpha, -cos alpha, 0), the height h - r cos alpha cos t is least
    // at t = 0), the rim point nearest B's axis too (the squared distance to the axis has
    // derivative 2 r sin t (h cos alpha + r cos t sin^2 alpha), zero only at t = 0 and pi
    // for h > 0). So the normal is -y, B's surface normal under P, and the depth
    // R - P_y = R - h + r cos alpha; along either axis the projections overlap by more
    // than 1.2 m. (A's closest axis point is its end: FCL's path finds this normal.) The
    // axes are within 20 degrees of parallel and the normal within 20 degrees of across
    // both, so A's upper end E' = E - a (over B's side at x = 0.3 - cos alpha) has a
    // point too when within the speculative distance (2 cm): its rim point nearest B's
    // axis, by the same argument E' + r (-sin alpha, -cos alpha, 0), sin alpha (A's
    // length 1 times it) higher than P, at depth `depth` - sin alpha = -0.0064 for the
    // deepest case, a gap of 0.07 m and more for the others. Each point's B side is B's
    // highest line under it.
    const real alpha = 9 * kPi / 180, r = 0.2, R = 0.25;
    const Shape a = Shape::cylinder(r, 1);
    const Shape b = Shape::cylinder(R, 2);
    const Vector3 axis(std::cos(alpha), -std::sin(alpha), 0);
    const Quaternion tilt = rotation(-alpha, Vector3::UnitZ()) * zAlongX();
    for (const real depth : {0.01, 0.08, 0.15}) {
        SCOPED_TRACE(depth);
        const real h = R + r * std::cos(alpha) - depth;
        const Vector3 end(0.3, h, 0);
        const Vector3 lowest = end + r * Vector3(-std::sin(alpha), -std::cos(alpha), 0);
        Expected e;
        e.normal = kDown;
        e.depth = depth;
        e.allSameDepth = false;
        // FCL's path refines MPR's normal to within 1e-3 rad here, not exactly.
        e.normalTolerance = 1e-3;
        e.depthTolerance = 1e-4;
        e.pointTolerance = 1e-3;
        const Vector3 upper = lowest - axis;
        ASSERT_NEAR(R - upper.y(), depth - std::sin(alpha), 1e-12);
        e.points.push_back(pointPair(lowest, Vector3(lowest.x(), R, 0)));
        if (depth - std::sin(alpha) >= -0.02) e.points.push_back(pointPair(upper, Vector3(upper.x(), R, 0)));
        expectContact(a, pose(end - 0.5 * axis, tilt), b, pose(Vector3::Zero(), zAlongX()), e);
    }
}

TEST(CylinderPairs, LyingCylinderOnAStandingCylinderCap) {
    // A (radius 0.2, length 2) along x at (0, h, 0) lies across the cap (y = 0.5, radius
    // 0.4) of B standing at the origin (length 1). A's axis point over B's lies inside A's
    // segment but at B's end: A's side against B's cap, normal -y (B's axis), depth
    // 0.5 + 0.2 - h. A's lowest line crosses the cap's rim at x = +-0.4 (a vertex of the
    // cap's polygon lies on each end of that diameter): two points.
    const Shape a = Shape::cylinder(0.2, 2);
    const Shape b = Shape::cylinder(0.4, 1);
    for (const real depth : {0.005, 0.1}) {
        SCOPED_TRACE(depth);
        const real h = 0.7 - depth;
        Expected e;
        e.normal = kDown;
        e.depth = depth;
        for (const real x : {-0.4, 0.4}) e.points.push_back(pointPair(Vector3(x, h - 0.2, 0), Vector3(x, 0.5, 0)));
        expectContact(a, pose(Vector3(0, h, 0), zAlongX()), b, pose(Vector3::Zero(), zUp()), e);
    }
}

TEST(CylinderPairs, CapsuleAcrossACylinderSideAtAnyDepth) {
    // A capsule (radius 0.15, length 1) along x at (0, y, 0) across a cylinder (radius
    // 0.25, length 1) along z at the origin: the cores' closest points (0, y, 0) and the
    // origin lie inside both segments, so the normal is -y and the depth 0.4 - y, one
    // point below the capsule's core and on the cylinder's highest line.
    const Shape capsule = Shape::capsule(0.15, 1);
    const Shape cylinder = Shape::cylinder(0.25, 1);
    for (const real y : {0.39, 0.2}) {
        SCOPED_TRACE(y);
        Expected e;
        e.normal = kDown;
        e.depth = 0.4 - y;
        e.points.push_back(pointPair(Vector3(0, y - 0.15, 0), Vector3(0, 0.25, 0)));
        expectContact(capsule, pose(Vector3(0, y, 0), zAlongX()), cylinder, pose(Vector3::Zero()), e);
    }
}

TEST(CylinderPairs, CrossedCylindersApartGiveASpeculativePointWithinTheReach) {
    // As CrossedLyingCylindersAtAnyDepth with A at y = 0.51: 1 cm apart along -y. With a
    // reach of 2 cm the manifold has one point at depth -0.01; with 5 mm, none.
    const Shape cylinder = Shape::cylinder(0.25, 1);
    const auto compiled = detail::compileShape(cylinder);
    const Matrix4 poseA = pose(Vector3(0, 0.51, 0), zAlongX());
    const Matrix4 poseB = pose(Vector3::Zero());
    detail::NarrowphaseSettings settings;
    settings.reach = 0.02;
    std::vector<Manifold> out;
    ASSERT_EQ(detail::collide(*compiled, poseA, *compiled, poseB, settings, out), 1);
    EXPECT_LT((out[0].normal - kDown).norm(), 1e-9);
    ASSERT_EQ(out[0].count, 1);
    EXPECT_NEAR(out[0].points[0].depth, -0.01, 1e-9);
    settings.reach = 0.005;
    out.clear();
    EXPECT_EQ(detail::collide(*compiled, poseA, *compiled, poseB, settings, out), 0);
}

TEST(CylinderPairs, StandingCylindersSideBySideApartHaveNoContact) {
    // Two standing cylinders (radius 0.25, length 1) with parallel axes 0.6 sqrt 2 = 0.85
    // apart, more than the radii's sum 0.5: apart at every height, also where A is raised
    // so far (y = 0.9) that only its lower rim is level with B's upper one.
    const Shape cylinder = Shape::cylinder(0.25, 1);
    for (const real y : {0.9, 0.5, 0.0}) {
        SCOPED_TRACE(y);
        const Matrix4 poseA = pose(Vector3(0, y, 0), zUp()), poseB = pose(Vector3(0.6, 0, 0.6), zUp());
        EXPECT_TRUE(collide(cylinder, poseA, cylinder, poseB, 0).empty());
    }
}

TEST(CylinderPairs, RimsMicronsApartClaimNoDepth) {
    // Two tilted cylinders whose rims are a few micrometres apart (poses of a mixed1000
    // pile, seeds 3 and 7, where they meet rim to rim): FCL finds no contact, and its
    // distance gives nearest points so close that the line between them has no
    // direction; along it the shapes overlap by 31 and 93 mm. The shapes are apart, so no
    // point may claim more depth than rounding (apartContact's 0.1 mm). Within a reach of
    // 6 mm or more (apartContact asks the distance from 5 mm) they are closer than it, so
    // they get a speculative contact: along the normal of least overlap.
    struct Case {
        real radiusA, lengthA, radiusB, lengthB;
        Vector3 positionA, positionB;
        Quaternion orientationA, orientationB;
    };
    const Case cases[] = {
        {0.28621331456470789, 0.44496822868947777, 0.28466241533115866, 0.41192729371501124,
         Vector3(3.5992305040507619, 0.24121216095336587, 1.6891250928771462),
         Vector3(3.3004844940493485, 0.77005067592884346, 1.3387358371878866),
         Quaternion(0.71317017816891226, -0.68174634612481699, -0.094698620152361204, -0.13282465078900788),
         Quaternion(0.30756239645804567, 0.70398601411250838, -0.43998896510401125, 0.46499330619447427)},
        {0.29545628367344901, 0.45201247737566358, 0.26034946740216047, 0.41321704681562399,
         Vector3(-2.1778550354377972, 1.6076141901747678, 0.18493483288620063),
         Vector3(-2.1747390450960298, 1.7871671375829656, -0.46465047013316285),
         Quaternion(-0.38290392706411491, 0.68510494162866786, 0.60835979821856889, -0.11795828714558748),
         Quaternion(0.10763918782586011, 0.19850605726996512, -0.90038945092189837, 0.37189781814348566)},
    };
    for (const Case &c : cases) {
        const auto a = detail::compileShape(Shape::cylinder(c.radiusA, c.lengthA));
        const auto b = detail::compileShape(Shape::cylinder(c.radiusB, c.lengthB));
        const Matrix4 poseA = pose(c.positionA, c.orientationA.normalized());
        const Matrix4 poseB = pose(c.positionB, c.orientationB.normalized());
        for (const real reach : {0.0, 0.006, 0.02, 0.1}) {
            SCOPED_TRACE(reach);
            detail::NarrowphaseSettings settings;
            settings.reach = reach;
            for (int order = 0; order < 2; ++order) {
                std::vector<Manifold> out;
                if (order == 0) detail::collide(*a, poseA, *b, poseB, settings, out);
                else detail::collide(*b, poseB, *a, poseA, settings, out);
                if (reach > 0.005) {
                    EXPECT_FALSE(out.empty());
                }
                for (const Manifold &m : out)
                    for (int i = 0; i < m.count; ++i) EXPECT_LE(m.points[i].depth, 1e-4);
            }
        }
    }
}

}  // namespace
}  // namespace cyclone::test
