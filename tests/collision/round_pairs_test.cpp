// The round pairs' closed-form contacts (collision/round_pairs.cpp): sphere-capsule,
// capsule-capsule and capsule-box from the closest points of their core features, exact
// at any depth, in both argument orders; their speculative manifolds within the reach;
// and agreement with the FCL path on shallow random contacts.
//
// A capsule's core is the segment along its local z axis, `length` long; zAlongX() lays
// it along world x. Unless a test says otherwise A comes from above, so the normal from
// A to B is -y.
#include <gtest/gtest.h>

#include <random>

#include "collision/round_pairs.h"
#include "collision_test_support.h"

namespace cyclone::test {
namespace {

const Vector3 kDown = -Vector3::UnitY();

ExpectedPoint at(const Vector3 &pointA, const Vector3 &pointB) { return {pointA, pointB}; }

// ---- segments ----

TEST(RoundPairs, ClosestPointsOfSegments) {
    real s = -1, t = -1;
    // Crossing skew segments: [(-1,0,0), (1,0,0)] and [(0.5,1,-1), (0.5,1,1)]: the common
    // perpendicular is at x = 0.5, z = 0: s = 0.75, t = 0.5.
    detail::closestOnSegments(Vector3(-1, 0, 0), Vector3(1, 0, 0), Vector3(0.5, 1, -1), Vector3(0.5, 1, 1), s, t);
    EXPECT_NEAR(s, 0.75, 1e-15);
    EXPECT_NEAR(t, 0.5, 1e-15);
    // The second shifted to z in [1, 3]: its nearest end is q0 = (0.5, 1, 1), whose nearest
    // point on the first is x = 0.5.
    detail::closestOnSegments(Vector3(-1, 0, 0), Vector3(1, 0, 0), Vector3(0.5, 1, 1), Vector3(0.5, 1, 3), s, t);
    EXPECT_NEAR(s, 0.75, 1e-15);
    EXPECT_NEAR(t, 0, 1e-15);
    // Parallel, overlapping in x in [0, 1]: any pair across the overlap is closest; the
    // first segment's end p0 = (0, 0, 0) sits over the second at t = 0.5.
    detail::closestOnSegments(Vector3(0, 0, 0), Vector3(2, 0, 0), Vector3(-1, 1, 0), Vector3(1, 1, 0), s, t);
    EXPECT_NEAR(((Vector3(-1, 1, 0) + t * Vector3(2, 0, 0)) - s * Vector3(2, 0, 0)).norm(), 1, 1e-15);
}

// ---- capsule-capsule ----

TEST(RoundPairs, ParallelCapsulesRestingOnEachOtherGiveTwoPoints) {
    // Radius 0.25, length 1, both along x; A at (0, 0.49, 0), B at (0.3, 0, 0). The cores
    // are 0.49 apart: depth 0.5 - 0.49 = 0.01. A's lowest line y = 0.24, x in
    // [-0.5, 0.5], lies over B's highest y = 0.25, x in [-0.2, 0.8]: the overlap's ends
    // x = -0.2 and x = 0.5 are the points.
    const Shape capsule = Shape::capsule(0.25, 1);
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    for (real x : {-0.2, 0.5}) e.points.push_back(at(Vector3(x, 0.24, 0), Vector3(x, 0.25, 0)));
    expectContact(capsule, pose(Vector3(0, 0.49, 0), zAlongX()), capsule, pose(Vector3(0.3, 0, 0), zAlongX()), e);
}

TEST(RoundPairs, CrossedCapsulesGiveOnePoint) {
    // A along x at (0.1, 0.45, 0.2), B along z at the origin: the cores' closest points are
    // (0, 0.45, 0.2) and (0, 0, 0.2), 0.45 apart: depth 0.05, one point.
    const Shape capsule = Shape::capsule(0.25, 1);
    Expected e;
    e.normal = kDown;
    e.depth = 0.05;
    e.points.push_back(at(Vector3(0, 0.2, 0.2), Vector3(0, 0.25, 0.2)));
    expectContact(capsule, pose(Vector3(0.1, 0.45, 0.2), zAlongX()), capsule, pose(Vector3::Zero()), e);
}

TEST(RoundPairs, DeepCrossedCapsulesKeepTheNormalOfTheirCores) {
    // As above but the cores only 0.1 apart (B at (0, -0.1, 0)): depth 0.5 - 0.1 = 0.4,
    // still straight down, where the old MPR normal was only approximate.
    const Shape capsule = Shape::capsule(0.25, 1);
    Expected e;
    e.normal = kDown;
    e.depth = 0.4;
    e.points.push_back(at(Vector3(0, -0.25, 0), Vector3(0, 0.15, 0)));
    expectContact(capsule, pose(Vector3(0, 0, 0), zAlongX()), capsule, pose(Vector3(0, -0.1, 0)), e);
}

TEST(RoundPairs, CoresThatMeetArePushedApartAcrossBoth) {
    // A's core along x through the origin meets B's, along z through (0.2, 0, 0.1), at
    // (0.2, 0, 0). Across both (the y axis) each core projects to the single value 0, so
    // the overlap there is the radii's sum, 0.5, the least of any axis. Its sign: A's core
    // direction x crossed with B's z is -y (the centres give no side: they are level).
    const Shape capsule = Shape::capsule(0.25, 1);
    Expected e;
    e.normal = kDown;
    e.depth = 0.5;
    e.points.push_back(at(Vector3(0.2, -0.25, 0), Vector3(0.2, 0.25, 0)));
    expectContact(capsule, pose(Vector3::Zero(), zAlongX()), capsule, pose(Vector3(0.2, 0, 0.1)), e);
}

TEST(RoundPairs, DeepParallelCapsulesInAColumn) {
    // Two standing capsules (radius 0.2, length 0.4) side by side, cores 0.1 apart along
    // x: pushed apart along x by 0.4 - 0.1 = 0.3, with two points at the cores' ends'
    // heights y = +-0.2 (the ends overlap exactly).
    const Shape capsule = Shape::capsule(0.2, 0.4);
    Expected e;
    e.normal = Vector3::UnitX();
    e.depth = 0.3;
    for (real y : {-0.2, 0.2}) e.points.push_back(at(Vector3(0.2, y, 0), Vector3(-0.1, y, 0)));
    expectContact(capsule, pose(Vector3::Zero(), zUp()), capsule, pose(Vector3(0.1, 0, 0), zUp()), e);
}

TEST(RoundPairs, EndCapOnACapsuleSide) {
    // A (radius 0.25, length 1) standing at (0.2, 0.97, 0), its core y in [0.47, 1.47];
    // B the same lying along x at the origin. The cores' closest points are A's lower end
    // (0.2, 0.47, 0) and (0.2, 0, 0) on B's core, 0.47 apart: depth 0.5 - 0.47 = 0.03,
    // normal -y, one point: the bottom of A's end cap (0.2, 0.22, 0) over B's top line.
    const Shape capsule = Shape::capsule(0.25, 1);
    Expected e;
    e.normal = kDown;
    e.depth = 0.03;
    e.points.push_back(at(Vector3(0.2, 0.22, 0), Vector3(0.2, 0.25, 0)));
    expectContact(capsule, pose(Vector3(0.2, 0.97, 0), zUp()), capsule, pose(Vector3::Zero(), zAlongX()), e);
}

// ---- capsule-box ----

TEST(RoundPairs, CapsuleLyingOnABoxFaceGivesTheSegmentEnds) {
    // Box of half extents (1, 0.5, 1) at the origin; capsule (radius 0.2, length 0.8)
    // along x at (0.3, 0.69, -0.2): its lowest line y = 0.49, x in [-0.1, 0.7], is 0.01
    // into the top face at y = 0.5: two points, at the segment's ends.
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    for (real x : {-0.1, 0.7}) e.points.push_back(at(Vector3(x, 0.49, -0.2), Vector3(x, 0.5, -0.2)));
    expectContact(Shape::capsule(0.2, 0.8), pose(Vector3(0.3, 0.69, -0.2), zAlongX()), Shape::box(Vector3(1, 0.5, 1)),
                  Matrix4::Identity(), e);
}

TEST(RoundPairs, CapsuleHangingOverABoxEdgeIsClippedToTheFace) {
    // Unit cube (half 0.5); the capsule's lowest line x in [0.2, 1.0] at y = 0.49: the
    // face keeps x in [0.2, 0.5].
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    for (real x : {0.2, 0.5}) e.points.push_back(at(Vector3(x, 0.49, 0), Vector3(x, 0.5, 0)));
    expectContact(Shape::capsule(0.2, 0.8), pose(Vector3(0.6, 0.69, 0), zAlongX()), Shape::box(Vector3(0.5, 0.5, 0.5)),
                  Matrix4::Identity(), e);
}

TEST(RoundPairs, CapsuleAcrossABoxEdge) {
    // The capsule along z, beside the cube's top edge along z at (0.5, 0.5): its core at
    // (0.5 + 0.1, 0.5 + 0.1) is 0.1 sqrt 2 from the edge, diagonally: depth 0.2 - 0.1414,
    // normal from the core to the edge, (-1, -1, 0) / sqrt 2. The cube's top face (the
    // first of the two equally aligned faces) is the reference: one point per core end
    // where the capsule's surface along the normal crosses past the edge.
    const real d = 0.1 * std::sqrt(2.0);
    const Vector3 n = Vector3(-1, -1, 0).normalized();
    Expected e;
    e.normal = n;
    e.depth = 0.2 - d;
    e.minPoints = 1;
    e.maxPoints = 2;
    e.eachPoint = [&](const Vector3 &pointA, const Vector3 &pointB) {
        // A's point on the capsule's surface along n from the core, B's point on the edge.
        EXPECT_NEAR((pointA - Vector3(0.6, 0.6, pointA.z()) - 0.2 * n).norm(), 0, 1e-9);
        EXPECT_NEAR(pointB.x(), 0.5, 1e-9);
        EXPECT_NEAR(pointB.y(), 0.5, 1e-9);
    };
    expectContact(Shape::capsule(0.2, 0.6), pose(Vector3(0.6, 0.6, 0)), Shape::box(Vector3(0.5, 0.5, 0.5)),
                  Matrix4::Identity(), e);
}

TEST(RoundPairs, CapsuleSunkIntoABoxLeavesThroughTheNearestFace) {
    // Box (1, 0.5, 1); capsule (radius 0.2, length 0.8) along x with its core inside the box
    // at y = 0.35: up through the top face takes 0.5 - 0.35 + 0.2 = 0.35, any other way
    // more (sideways 1 + 0.4 + 0.2, down 0.35 + 0.5 + 0.2). The lowest line, y = 0.15, x
    // in [-0.4, 0.4], gives the points.
    Expected e;
    e.normal = kDown;
    e.depth = 0.35;
    for (real x : {-0.4, 0.4}) e.points.push_back(at(Vector3(x, 0.15, 0), Vector3(x, 0.5, 0)));
    expectContact(Shape::capsule(0.2, 0.8), pose(Vector3(0, 0.35, 0), zAlongX()), Shape::box(Vector3(1, 0.5, 1)),
                  Matrix4::Identity(), e);
}

TEST(RoundPairs, CapsuleThroughABoxLeavesAcrossItsSweep) {
    // A long capsule (radius 0.1, length 4) along u = (1, 1, 0) / sqrt 2 through the
    // centre of a flat box (half extents 2, 0.2, 2); its core's ends are +-(sqrt 2, sqrt 2,
    // 0). Overlap along n = the core's largest projection + 0.1 + the box's half width
    // along n: along x 1.414 + 0.1 + 2 = 3.51; along y 1.414 + 0.1 + 0.2 = 1.71; along z
    // (also u crossed with the box's x and y edges) 0 + 0.1 + 2 = 2.1; along u crossed
    // with the box's z edge, (1, -1, 0) / sqrt 2, the core projects to 0 and the box to
    // (2 + 0.2) / sqrt 2: 1.556 + 0.1 = 1.656, the least.
    const Vector3 axis = Vector3(1, 1, 0).normalized();
    const Vector3 across = Vector3(1, -1, 0).normalized();
    Vector3 normal;
    real depth = 0;
    ASSERT_TRUE(detail::capsuleBoxNormal(0.1, -2 * axis, 2 * axis, Vector3(2, 0.2, 2), Matrix4::Identity(), normal,
                                         depth));
    EXPECT_NEAR(std::abs(normal.dot(across)), 1, 1e-12) << normal.transpose();
    EXPECT_NEAR(depth, 2.2 / std::sqrt(2.0) + 0.1, 1e-12);
    // The narrowphase's manifold takes that normal.
    const Quaternion q = Quaternion::FromTwoVectors(Vector3::UnitZ(), axis);
    const std::vector<Manifold> out =
        collide(Shape::capsule(0.1, 4), pose(Vector3::Zero(), q), Shape::box(Vector3(2, 0.2, 2)), Matrix4::Identity());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(std::abs(out[0].normal.dot(across)), 1, 1e-12) << out[0].normal.transpose();
}

// ---- sphere-capsule ----

TEST(RoundPairs, DeepSphereOnACapsuleSide) {
    // Standing capsule (radius 0.25, length 1) at the origin; sphere (radius 0.5) centred
    // 0.1 from its core at (0.1, 0.2, 0): depth 0.75 - 0.1 = 0.65, normal -x.
    Expected e;
    e.normal = -Vector3::UnitX();
    e.depth = 0.65;
    e.points.push_back(at(Vector3(-0.4, 0.2, 0), Vector3(0.25, 0.2, 0)));
    expectContact(Shape::sphere(0.5), pose(Vector3(0.1, 0.2, 0)), Shape::capsule(0.25, 1), pose(Vector3::Zero(), zUp()),
                  e);
}

TEST(RoundPairs, SphereOnACapsuleEndCapAtASlant) {
    // Standing capsule (radius 0.25, length 1), core y in [-0.5, 0.5]; sphere (radius 0.1)
    // at (0, 0.68, 0.24), beyond the core's top end (0, 0.5, 0), 0.3 from it along
    // (0, 0.18, 0.24): depth 0.35 - 0.3 = 0.05 along n = -(0, 0.6, 0.8) (sphere to
    // capsule). The points: the sphere's centre + 0.1 n = (0, 0.62, 0.16) and the end
    // cap's surface end - 0.25 n = (0, 0.65, 0.2).
    Expected e;
    e.normal = Vector3(0, -0.6, -0.8);
    e.depth = 0.05;
    e.points.push_back(at(Vector3(0, 0.62, 0.16), Vector3(0, 0.65, 0.2)));
    expectContact(Shape::sphere(0.1), pose(Vector3(0, 0.68, 0.24)), Shape::capsule(0.25, 1),
                  pose(Vector3::Zero(), zUp()), e);
}

TEST(RoundPairs, SphereCentredOnACapsuleCoreIsPushedAcrossIt) {
    // Every direction across the core is as deep: 0.3 + 0.25; the normal is one of them.
    Manifold m;
    ASSERT_TRUE(detail::sphereCapsule(0.3, Vector3(0, 0.2, 0), 0.25, Vector3(0, -0.5, 0), Vector3(0, 0.5, 0), m));
    EXPECT_NEAR(m.points[0].depth, 0.55, 1e-12);
    EXPECT_NEAR(m.normal.norm(), 1, 1e-12);
    EXPECT_NEAR(m.normal.y(), 0, 1e-12);
}

// ---- speculative contacts ----

TEST(RoundPairs, ApartWithinTheReachGiveNegativeDepths) {
    // The capsule lying on the unit cube 30 mm above its top face: within a 50 mm reach a
    // manifold of two points 30 mm apart (depth -0.03); within 20 mm, nothing.
    const auto capsule = detail::compileShape(Shape::capsule(0.2, 0.8));
    const auto box = detail::compileShape(Shape::box(Vector3(1, 0.5, 1)));
    const Matrix4 poseCapsule = pose(Vector3(0, 0.73, 0), zAlongX());
    for (const real reach : {0.05, 0.02}) {
        detail::NarrowphaseSettings settings;
        settings.reach = reach;
        std::vector<Manifold> out;
        detail::collide(*capsule, poseCapsule, *box, Matrix4::Identity(), settings, out);
        if (reach < 0.03) {
            EXPECT_TRUE(out.empty());
            continue;
        }
        ASSERT_EQ(out.size(), 1u);
        EXPECT_LT((out[0].normal - kDown).norm(), 1e-12);
        ASSERT_EQ(out[0].count, 2);
        for (int i = 0; i < 2; ++i) EXPECT_NEAR(out[0].points[i].depth, -0.03, 1e-12);
    }
    // Two capsules 30 mm apart, and a sphere 30 mm from a capsule, alike.
    const auto ball = detail::compileShape(Shape::sphere(0.3));
    const Matrix4 above = pose(Vector3(0, 0.73, 0), zAlongX());
    const Matrix4 below = pose(Vector3(0, 0.3, 0), zAlongX());
    const Matrix4 ballAbove = pose(Vector3(0, 0.83, 0));
    for (const auto &[a, poseA] : {std::pair{capsule.get(), above}, std::pair{ball.get(), ballAbove}}) {
        detail::NarrowphaseSettings settings;
        settings.reach = 0.05;
        std::vector<Manifold> out;
        detail::collide(*a, poseA, *capsule, below, settings, out);
        ASSERT_EQ(out.size(), 1u);
        EXPECT_NEAR(out[0].points[0].depth, -0.03, 1e-12);
    }
}

// ---- agreement with the FCL path ----

TEST(RoundPairs, AgreeWithTheFclPathOnShallowContacts) {
    // Random orientations, A moved along a random direction until the pair is 1-20 mm deep
    // by the closed form: there FCL's MPR normal, refined, is within a fraction of a
    // degree of the exact one, and its depth within a few micrometres.
    const std::vector<std::pair<Shape, Shape>> pairs = {
        {Shape::capsule(0.25, 0.6), Shape::capsule(0.2, 0.8)},
        {Shape::capsule(0.25, 0.6), Shape::box(Vector3(0.5, 0.3, 0.7))},
        {Shape::box(Vector3(0.5, 0.3, 0.7)), Shape::capsule(0.25, 0.6)},
        {Shape::sphere(0.3), Shape::capsule(0.2, 0.8)},
    };
    std::mt19937 random(21);
    std::uniform_real_distribution<real> uniform(-1, 1);
    for (const auto &[shapeA, shapeB] : pairs) {
        const auto a = detail::compileShape(shapeA);
        const auto b = detail::compileShape(shapeB);
        int close = 0;
        for (int trial = 0; trial < 200; ++trial) {
            SCOPED_TRACE(std::string(shapeTypeName(shapeA.type)) + " against " + shapeTypeName(shapeB.type) +
                         ", trial " + std::to_string(trial));
            const Quaternion qa(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
            const Quaternion qb(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
            const Vector3 direction = Vector3(uniform(random), uniform(random), uniform(random)).normalized();
            const Matrix4 poseB = pose(Vector3::Zero(), qb);
            const real wanted = 0.001 + 0.0095 * (uniform(random) + 1);
            // Bisection on the closed form's depth, which falls as A moves out.
            real lo = 0, hi = 3;
            std::vector<Manifold> n;
            for (int k = 0; k < 60; ++k) {
                const real mid = (lo + hi) / 2;
                n.clear();
                detail::collide(*a, pose(mid * direction, qa), *b, poseB, detail::NarrowphaseSettings(), n);
                real deepest = -1;
                if (!n.empty())
                    for (int i = 0; i < n[0].count; ++i) deepest = std::max(deepest, n[0].points[i].depth);
                (deepest > wanted ? lo : hi) = mid;
            }
            const Matrix4 poseA = pose(hi * direction, qa);
            n.clear();
            detail::collide(*a, poseA, *b, poseB, detail::NarrowphaseSettings(), n);
            detail::NarrowphaseSettings fcl;
            fcl.forceFcl = true;
            std::vector<Manifold> f;
            detail::collide(*a, poseA, *b, poseB, fcl, f);
            ASSERT_EQ(n.size(), 1u);
            EXPECT_EQ(f.size(), 1u);
            if (f.size() != 1) continue;
            real dn = -1, df = -1;
            for (int i = 0; i < n[0].count; ++i) dn = std::max(dn, n[0].points[i].depth);
            for (int i = 0; i < f[0].count; ++i) df = std::max(df, f[0].points[i].depth);
            EXPECT_NEAR(dn, wanted, 1e-6);
            if ((n[0].normal - f[0].normal).norm() < 1e-2 && std::abs(dn - df) < 2e-5) ++close;
        }
        EXPECT_GT(close, 190);
    }
}

}  // namespace
}  // namespace cyclone::test
