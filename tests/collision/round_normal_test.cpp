// Newton's descent to the normal of least overlap for round pairs with a cylinder
// (collision/round_normal.cpp): a sphere on a cylinder's rim (a smooth minimum), a
// cylinder's and a capsule's side on a rim (a minimum on the side's crease), parallel
// sides (one crease for both), a sphere over a cap (the descent approaches the cap's
// normal), each worked out by hand and carried by one rigid motion of both shapes;
// degenerate starts; over random overlapping cylinder pairs, what it ends on is a local
// minimum of the overlap, which FCL's collide confirms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "collision/round_normal.h"
#include "collision_test_support.h"

namespace cyclone::test {
namespace {

struct Descent {
    Vector3 normal;
    real overlap;
    bool convex;
};

// Both shapes carried by `motion`; the descent starts at `start` (before the motion).
Descent descend(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB, const Matrix4 &motion,
                const Vector3 &start) {
    const auto sa = detail::compileShape(a), sb = detail::compileShape(b);
    const Matrix4 movedA = motion * poseA, movedB = motion * poseB;
    const detail::Pair pair{*sa, movedA, -1, *sb, movedB, -1, 0.02, 0};
    Descent d{motion.linear() * start.normalized(), 0, false};
    d.overlap = pair.overlap(d.normal);
    d.convex = detail::roundNormal(pair, d.normal, d.overlap);
    return d;
}

Matrix4 someMotion() { return pose(Vector3(3, -2, 7), rotation(0.7, Vector3(1, 2, -0.5))); }

TEST(RoundNormal, SphereOnARimReachesTheLineThroughTheRimPoint) {
    // A: cylinder radius 0.5, length 1, axis z, at the origin; its rim point nearest the
    // sphere B (radius 0.3, centre (0.7, 0, 0.65)) is (0.5, 0, 0.5), 0.25 away along
    // (0.8, 0, 0.6): depth 0.3 - 0.25 = 0.05 along it. Along z the overlap is
    // 0.5 + 0.3 - 0.65 = 0.15 and along x 0.5 + 0.3 - 0.7 = 0.1, both deeper.
    const Matrix4 motion = someMotion();
    const Descent d = descend(Shape::cylinder(0.5, 1), pose(Vector3::Zero()), Shape::sphere(0.3),
                              pose(Vector3(0.7, 0, 0.65)), motion, Vector3(0.5, 0.2, 0.9));
    EXPECT_TRUE(d.convex);
    EXPECT_NEAR(d.overlap, 0.05, 1e-12);
    EXPECT_LT((d.normal - motion.linear() * Vector3(0.8, 0, 0.6)).norm(), 1e-9);
}

TEST(RoundNormal, RimOnALyingSideStopsOnTheSidesCrease) {
    // A as above; B (radius 0.5, length 2) lies along y at (0.8, 0, 0.85). A's rim point
    // (0.5, 0, 0.5) is sqrt(0.3^2 + 0.35^2) = 0.460977 from B's axis: depth 0.039023 along
    // (0.3, 0, 0.35) / 0.460977, across B's axis (its side's crease). Along x the overlap
    // is 0.5 + 0.5 - 0.8 = 0.2, along z 0.15. The same holds for a capsule B, whose side
    // there is the cylinder's. The start has a y part: the descent must find the crease.
    const real distance = std::hypot(0.3, 0.35);
    const Matrix4 motion = someMotion();
    for (const Shape &b : {Shape::cylinder(0.5, 2), Shape::capsule(0.5, 2)}) {
        const Descent d = descend(Shape::cylinder(0.5, 1), pose(Vector3::Zero()), b,
                                  pose(Vector3(0.8, 0, 0.85), zUp()), motion, Vector3(0.35, 0.1, 0.3));
        EXPECT_TRUE(d.convex);
        EXPECT_NEAR(d.overlap, 0.5 - distance, 1e-12);
        EXPECT_LT((d.normal - motion.linear() * Vector3(0.3, 0, 0.35) / distance).norm(), 1e-9);
    }
}

TEST(RoundNormal, SphereOverACapApproachesTheCapsNormal) {
    // A sphere (radius 0.3) centred at (0.1, 0, 0.7) over the cylinder's cap (z = 0.5)
    // overlaps it by 0.5 + 0.3 - 0.7 = 0.1 along z; tilting n by t towards x adds about
    // 0.4 t (a crease of the cap's rim cone), so the descent ends near z.
    const Matrix4 motion = someMotion();
    const Descent d = descend(Shape::cylinder(0.5, 1), pose(Vector3::Zero()), Shape::sphere(0.3),
                              pose(Vector3(0.1, 0, 0.7)), motion, Vector3(0.1, 0.05, 1));
    EXPECT_NEAR(d.overlap, 0.1, 1e-6);
    EXPECT_LT((d.normal - motion.linear() * Vector3::UnitZ()).norm(), 1e-5);
}

TEST(RoundNormal, ParallelSidesReachTheLineBetweenTheAxes) {
    // A and B (radius 0.25, length 1) stand side by side along z, 0.4 apart along x: their
    // sides overlap by 0.5 - 0.4 = 0.1 along x (along y by 0.5, along z by 1). Both
    // creases (normals across the axes) are one circle: the descent lands on it and goes
    // on along it to x.
    const Matrix4 motion = someMotion();
    for (const Shape &b : {Shape::cylinder(0.25, 1), Shape::capsule(0.25, 1)}) {
        const Descent d = descend(Shape::cylinder(0.25, 1), pose(Vector3::Zero()), b, pose(Vector3(0.4, 0, 0)),
                                  motion, Vector3(1, 0.3, 0.2));
        EXPECT_TRUE(d.convex);
        EXPECT_NEAR(d.overlap, 0.1, 1e-12);
        EXPECT_LT((d.normal - motion.linear() * Vector3::UnitX()).norm(), 1e-9);
    }
}

TEST(RoundNormal, DegenerateStartsGiveAUnitNormalNoDeeperThanTheStart) {
    // Coincident centres, a start along an axis, a start exactly across both axes: the
    // normal stays a unit vector and the overlap finite and no more than at the start.
    const Shape cylinder = Shape::cylinder(0.3, 0.8);
    const Matrix4 tilted = pose(Vector3::Zero(), rotation(0.9, Vector3(1, 0, 0)));
    for (const Matrix4 &poseB : {pose(Vector3::Zero()), tilted, pose(Vector3(0, 0, 0.5))}) {
        for (const Vector3 &start :
             {Vector3(Vector3::UnitZ()), Vector3(Vector3::UnitX()), Vector3(1, 1, 0), Vector3(0, 1, 1)}) {
            const auto sa = detail::compileShape(cylinder), sb = detail::compileShape(Shape::sphere(0.2));
            for (const detail::CollisionShape *b : {sa.get(), sb.get()}) {
                const Matrix4 poseA = pose(Vector3::Zero());
                const detail::Pair pair{*sa, poseA, -1, *b, poseB, -1, 0.02, 0};
                Vector3 n = start.normalized();
                const real before = pair.overlap(n);
                real f = before;
                detail::roundNormal(pair, n, f);
                EXPECT_NEAR(n.norm(), 1, 1e-12);
                EXPECT_TRUE(std::isfinite(f));
                EXPECT_LE(f, before);
                EXPECT_NEAR(f, pair.overlap(n), 1e-12);
            }
        }
    }
}

// Draws in a fixed order (a function's arguments are evaluated in any order).
struct Draw {
    std::mt19937 random{11};
    real operator()(real low, real high) { return std::uniform_real_distribution<real>(low, high)(random); }
    Vector3 vector() {
        const real x = (*this)(-1, 1), y = (*this)(-1, 1), z = (*this)(-1, 1);
        return Vector3(x, y, z);
    }
    Quaternion orientation() {
        const real w = (*this)(-1, 1);
        const Vector3 v = vector();
        return Quaternion(w, v.x(), v.y(), v.z()).normalized();
    }
    Shape cylinder() {
        const real radius = (*this)(0.2, 0.5);
        return Shape::cylinder(radius, (*this)(0.3, 1.5));
    }
};

// Random overlapping cylinder pairs (radii 0.2-0.5, lengths 0.3-1.5) from random
// normals: where the descent settles, no direction within 0.02 rad overlaps less, and
// FCL agrees that B moved along the normal by the overlap just clears A. (FCL's EPA,
// GST_INDEP, is no reference for the depth: on 18 of these pairs its depth exceeded an
// overlap we found along some normal, which bounds the depth from above.)
TEST(RoundNormal, EndsOnALocalMinimumOfRandomCylinderPairs) {
    Draw draw;
    int checked = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Shape a = draw.cylinder(), b = draw.cylinder();
        const auto sa = detail::compileShape(a), sb = detail::compileShape(b);
        const Matrix4 poseA = pose(Vector3::Zero(), draw.orientation());
        const Quaternion qb = draw.orientation();
        const Matrix4 poseB = pose(0.6 * draw.vector(), qb);
        const detail::Pair pair{*sa, poseA, -1, *sb, poseB, -1, 0.02, 0};
        Vector3 n = draw.vector().normalized();
        real f = pair.overlap(n);
        if (f <= 0 || !detail::roundNormal(pair, n, f)) continue;
        ++checked;
        for (int k = 0; k < 200; ++k) {
            const Vector3 nearby = (n + draw(0, 0.02) * draw.vector()).normalized();
            EXPECT_GE(pair.overlap(nearby), f - 1e-9) << "trial " << trial;
        }
        // FCL as the reference for the overlap along n: B moved along n by 0.1 mm less
        // than it still touches A, by 0.1 mm more it does not.
        for (const real beyond : {-1e-4, 1e-4}) {
            Matrix4 movedB = poseB;
            movedB.translation() += (f + beyond) * n;
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            fcl::collide(sa->geometry().get(), fcl::Transform3d(poseA.matrix()), sb->geometry().get(),
                         fcl::Transform3d(movedB.matrix()), request, result);
            EXPECT_EQ(result.isCollision(), beyond < 0) << "trial " << trial;
        }
    }
    EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace cyclone::test
