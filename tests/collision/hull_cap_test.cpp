// Hulls of more than kMaxHullVertices corners are simplified (Shape::convex): a hull of
// 20,000 corners made every contact test walk all of them (issue 34, item 7).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "collision/collision_shape.h"
#include "collision/convex_hull.h"

namespace cyclone {
namespace {

// n points on the unit sphere, spread by the golden angle (each one a hull corner).
std::vector<Vector3> sphereCloud(int n) {
    std::vector<Vector3> points;
    const real golden = M_PI * (3 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const real y = 1 - 2 * (i + 0.5) / n;
        const real ring = std::sqrt(1 - y * y);
        points.emplace_back(ring * std::cos(golden * i), y, ring * std::sin(golden * i));
    }
    return points;
}

// 20,000 points on the unit sphere: at most 256 corners remain, each one of the input
// points (so the simplified hull lies inside the true one), and every input point lies
// within R / 4 of a corner: the corners are pairwise r apart, their caps of chord radius
// r / 2 do not overlap and each has area pi (r/2)^2, so 256 pi r^2 / 4 <= 4 pi, r <= 1/4.
TEST(HullCap, ASphereCloudKeepsAtMostTheCapWithinAQuarterRadius) {
    const std::vector<Vector3> cloud = sphereCloud(20000);
    const auto shape = detail::compileShape(Shape::convex(cloud));
    const std::vector<Vector3> &corners = shape->vertices();
    ASSERT_LE(corners.size(), static_cast<std::size_t>(kMaxHullVertices));
    // Qhull merges nothing on a sphere: all the chosen corners stay corners.
    EXPECT_GT(corners.size(), static_cast<std::size_t>(kMaxHullVertices) * 9 / 10);
    for (const Vector3 &c : corners) EXPECT_NEAR(c.norm(), 1.0, 1e-12);
    real farthest = 0;
    for (const Vector3 &p : cloud) {
        real nearest = INFINITY;
        for (const Vector3 &c : corners) nearest = std::min(nearest, (p - c).norm());
        farthest = std::max(farthest, nearest);
    }
    EXPECT_LE(farthest, 0.25);
    // Every face plane keeps the origin inside: the hull still holds the centre.
    for (const std::vector<int> &face : shape->faces()) {
        const Vector3 a = corners[face[0]], b = corners[face[1]], c = corners[face[2]];
        EXPECT_GT((b - a).cross(c - a).normalized().dot(a), 0);
    }
    // Its volume is below the ball's (it is inside it).
    EXPECT_LT(shape->volume(), 4 * M_PI / 3);
}

// A hull at the cap is kept whole: the 256 points of the same spiral all stay corners.
TEST(HullCap, AHullAtTheCapIsKept) {
    const auto shape = detail::compileShape(Shape::convex(sphereCloud(kMaxHullVertices)));
    EXPECT_EQ(shape->vertices().size(), static_cast<std::size_t>(kMaxHullVertices));
}

// Farthest-point sampling on the 8 corners of a cube plus its centre, 2 chosen: the
// first is the corner farthest from the centroid (all tie: the lowest index, corner 0),
// the second the corner opposite it (distance 2 sqrt(3)); every other point is then
// within 2 of one of them (adjacent corners: 2; the centre: sqrt(3)).
TEST(HullCap, SpreadSubsetTakesTheFarthestPoints) {
    std::vector<Vector3> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    points.emplace_back(0, 0, 0);
    real cover = 0;
    const std::vector<Vector3> chosen = detail::spreadSubset(points, 2, cover);
    ASSERT_EQ(chosen.size(), 2u);
    EXPECT_EQ(chosen[0], points[0]);
    EXPECT_EQ(chosen[1], points[7]);
    EXPECT_DOUBLE_EQ(cover, 2.0);
}

}  // namespace
}  // namespace cyclone
