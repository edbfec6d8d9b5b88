// Helpers of the collision tests: poses, shapes used across tests, and checks of a
// manifold against hand-worked expectations in both argument orders.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "collision/collision_shape.h"
#include "collision/narrowphase.h"

namespace cyclone::test {

using detail::CollisionShape;
using detail::Manifold;

constexpr real kPi = 3.14159265358979323846;

/// Straight down: the normal the tests expect for a shape resting on one below it.
inline const Vector3 kDown = -Vector3::UnitY();

inline Matrix4 pose(const Vector3 &position, const Quaternion &orientation = Quaternion::Identity()) {
    Matrix4 m = Matrix4::Identity();
    m.linear() = orientation.toRotationMatrix();
    m.translation() = position;
    return m;
}

inline Quaternion rotation(real angle, const Vector3 &axis) { return Quaternion(Eigen::AngleAxis<real>(angle, axis.normalized())); }

/// Local z (the axis of capsules and cylinders) turned onto world +y.
inline Quaternion zUp() { return rotation(-kPi / 2, Vector3::UnitX()); }
/// Local z turned onto world +x.
inline Quaternion zAlongX() { return rotation(kPi / 2, Vector3::UnitY()); }

/// A square pyramid: base 0.8 x 0.8 at y = -0.25, apex at y = 0.75, plus points inside.
inline Shape pyramid() {
    return Shape::convex({Vector3(-0.4, -0.25, -0.4), Vector3(0.4, -0.25, -0.4), Vector3(0.4, -0.25, 0.4),
                          Vector3(-0.4, -0.25, 0.4), Vector3(0, 0.75, 0), Vector3(0, 0, 0), Vector3(0.1, 0, -0.1)});
}

/// The cube [-h, h]^3 as a convex hull of its corners plus interior points.
inline Shape convexCube(real h) {
    std::vector<Vector3> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    points.emplace_back(0, 0, 0);
    points.emplace_back(0.5 * h, -0.25 * h, 0.1 * h);
    return Shape::convex(points);
}

/// A 10 m x 10 m floor at y = 0 of two triangles meeting along the diagonal x = z,
/// wound so that their normals point up.
inline Shape meshFloor() {
    return Shape::mesh({Vector3(-5, 0, -5), Vector3(5, 0, -5), Vector3(5, 0, 5), Vector3(-5, 0, 5)}, {{0, 2, 1}, {0, 3, 2}});
}

inline std::vector<Manifold> collide(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB,
                                     real speculative = 0.02) {
    const auto compiledA = detail::compileShape(a);
    const auto compiledB = detail::compileShape(b);
    detail::NarrowphaseSettings settings;
    settings.speculativeDistance = speculative;
    std::vector<Manifold> out;
    const int appended = detail::collide(*compiledA, poseA, *compiledB, poseB, settings, out);
    EXPECT_EQ(appended, static_cast<int>(out.size()));
    return out;
}

/// One expected contact point, A's and B's side.
struct ExpectedPoint {
    Vector3 pointA;
    Vector3 pointB;
};

/// What a test expects of the single manifold of a pair.
struct Expected {
    Vector3 normal;           ///< From A to B.
    real depth = 0;           ///< Depth of every point (flat contacts) or of the deepest.
    bool allSameDepth = true; ///< Every point at `depth`; else only the deepest.
    int minPoints = 1;
    int maxPoints = 4;
    std::vector<ExpectedPoint> points;  ///< When not empty: exactly these, any order.
    real normalTolerance = 1e-9;
    real depthTolerance = 1e-6;
    real pointTolerance = 1e-6;
    /// When set: called with every point, A's and B's side as in the order (a, b).
    std::function<void(const Vector3 &pointA, const Vector3 &pointB)> eachPoint;
};

// The depth of a manifold's deepest point, m (-1e300 for none).
inline real deepestDepth(const Manifold &m) {
    real d = -1e300;
    for (int i = 0; i < m.count; ++i) d = std::max(d, m.points[i].depth);
    return d;
}

inline bool nonCollinear(const Manifold &m, real minArea = 1e-4) {
    for (int i = 0; i < m.count; ++i)
        for (int j = i + 1; j < m.count; ++j)
            for (int k = j + 1; k < m.count; ++k) {
                const Vector3 &p = m.points[i].pointB;
                const real area = 0.5 * (m.points[j].pointB - p).cross(m.points[k].pointB - p).norm();
                if (area > minArea) return true;
            }
    return false;
}

/// Checks the manifold of (a, b) against `e`, and that of (b, a) against `e` with the
/// normal flipped and the points' sides swapped.
inline void expectContact(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB, const Expected &e) {
    for (int order = 0; order < 2; ++order) {
        SCOPED_TRACE(order == 0 ? "order (a, b)" : "order (b, a)");
        const std::vector<Manifold> out = order == 0 ? collide(a, poseA, b, poseB) : collide(b, poseB, a, poseA);
        ASSERT_EQ(out.size(), 1u);
        const Manifold &m = out[0];
        const Vector3 normal = order == 0 ? e.normal : Vector3(-e.normal);
        EXPECT_NEAR(m.normal.norm(), 1, 1e-12);
        EXPECT_LT((m.normal - normal).norm(), e.normalTolerance) << "normal " << m.normal.transpose();
        EXPECT_GE(m.count, e.minPoints);
        EXPECT_LE(m.count, e.maxPoints);
        real deepest = -1e300;
        for (int i = 0; i < m.count; ++i) {
            const detail::ContactPoint &p = m.points[i];
            const Vector3 &pointA = order == 0 ? p.pointA : p.pointB;
            const Vector3 &pointB = order == 0 ? p.pointB : p.pointA;
            EXPECT_NEAR((p.pointA - p.pointB).dot(m.normal), p.depth, 1e-9) << "depth = (pointA - pointB).normal";
            if (e.allSameDepth) {
                EXPECT_NEAR(p.depth, e.depth, e.depthTolerance) << "point " << i;
            }
            deepest = std::max(deepest, p.depth);
            if (e.eachPoint) e.eachPoint(pointA, pointB);
            if (!e.points.empty()) {
                bool found = false;
                for (const ExpectedPoint &x : e.points)
                    found = found || ((x.pointA - pointA).norm() < e.pointTolerance &&
                                      (x.pointB - pointB).norm() < e.pointTolerance);
                EXPECT_TRUE(found) << "unexpected point A " << pointA.transpose() << " B " << pointB.transpose();
            }
        }
        EXPECT_NEAR(deepest, e.depth, e.depthTolerance);
        if (!e.points.empty()) {
            EXPECT_EQ(m.count, static_cast<int>(e.points.size()));
        }
        if (e.minPoints >= 3) {
            EXPECT_TRUE(nonCollinear(m)) << "face-on-face contact needs a spread of points";
        }
    }
}

}  // namespace cyclone::test
