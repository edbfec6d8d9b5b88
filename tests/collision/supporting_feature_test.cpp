// Supporting features: which feature each shape gives along a direction, in world space,
// counter-clockwise seen from outside.
#include <gtest/gtest.h>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

detail::SupportFeature feature(const Shape &shape, const Matrix4 &at, const Vector3 &direction, int triangle = -1) {
    detail::SupportFeature f;
    detail::compileShape(shape)->supportingFeature(at, direction.normalized(), triangle, f);
    return f;
}

// The polygon's turning is positive about `outward` at every vertex.
void expectCounterClockwise(const detail::SupportFeature &f, const Vector3 &outward) {
    for (int k = 0; k < f.count; ++k) {
        const Vector3 &p0 = f.points[k];
        const Vector3 &p1 = f.points[(k + 1) % f.count];
        const Vector3 &p2 = f.points[(k + 2) % f.count];
        EXPECT_GT((p1 - p0).cross(p2 - p1).dot(outward), 0) << "at vertex " << k;
    }
}

TEST(SupportingFeature, BoxGivesTheMostAlignedFace) {
    // Box 1 x 2 x 3 at (10, 0, 0); the direction mostly -y picks the bottom face y = -1.
    const Matrix4 at = pose(Vector3(10, 0, 0));
    const auto f = feature(Shape::box(Vector3(0.5, 1, 1.5)), at, Vector3(0.3, -1, 0.2));
    ASSERT_EQ(f.count, 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(f.points[i].y(), -1, 1e-12);
        EXPECT_NEAR(std::abs(f.points[i].x() - 10), 0.5, 1e-12);
        EXPECT_NEAR(std::abs(f.points[i].z()), 1.5, 1e-12);
    }
    expectCounterClockwise(f, -Vector3::UnitY());

    // Rotated 90 degrees about z, local +x points along world +y.
    const auto g = feature(Shape::box(Vector3(0.5, 1, 1.5)), pose(Vector3::Zero(), rotation(kPi / 2, Vector3::UnitZ())),
                           Vector3::UnitY());
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(g.points[i].y(), 0.5, 1e-12);
    expectCounterClockwise(g, Vector3::UnitY());
}

TEST(SupportingFeature, SphereGivesOnePoint) {
    const auto f = feature(Shape::sphere(2), pose(Vector3(1, 1, 1)), Vector3(0, 0, -1));
    ASSERT_EQ(f.count, 1);
    EXPECT_LT((f.points[0] - Vector3(1, 1, -1)).norm(), 1e-12);
}

TEST(SupportingFeature, CapsuleSideIsASegmentEndIsAPoint) {
    // Capsule r = 0.25, L = 1 along world x at the origin.
    const Shape capsule = Shape::capsule(0.25, 1);
    const Matrix4 at = pose(Vector3::Zero(), zAlongX());
    const auto side = feature(capsule, at, -Vector3::UnitY());
    ASSERT_EQ(side.count, 2);
    // The two ends' support points (-0.5, -0.25, 0) and (0.5, -0.25, 0), in either order.
    const real x0 = side.points[0].x();
    EXPECT_NEAR(std::abs(x0), 0.5, 1e-12);
    EXPECT_LT((side.points[0] - Vector3(x0, -0.25, 0)).norm(), 1e-12);
    EXPECT_LT((side.points[1] - Vector3(-x0, -0.25, 0)).norm(), 1e-12);
    // 30 degrees off perpendicular: the end sphere's support point alone.
    const Vector3 d = Vector3(std::sin(kPi / 6), -std::cos(kPi / 6), 0);
    const auto end = feature(capsule, at, d);
    ASSERT_EQ(end.count, 1);
    EXPECT_LT((end.points[0] - (Vector3(0.5, 0, 0) + 0.25 * d)).norm(), 1e-12);
}

TEST(SupportingFeature, CylinderCapSideAndRim) {
    // Cylinder r = 0.4, length 1, axis along world y, centre at the origin.
    const Shape cylinder = Shape::cylinder(0.4, 1);
    const Matrix4 at = pose(Vector3::Zero(), zUp());
    const auto cap = feature(cylinder, at, -Vector3::UnitY());
    ASSERT_GE(cap.count, 12);
    for (int i = 0; i < cap.count; ++i) {
        EXPECT_NEAR(cap.points[i].y(), -0.5, 1e-12);
        EXPECT_NEAR(Vector3(cap.points[i].x(), 0, cap.points[i].z()).norm(), 0.4, 1e-12);
    }
    expectCounterClockwise(cap, -Vector3::UnitY());

    const auto side = feature(cylinder, at, Vector3::UnitX());
    ASSERT_EQ(side.count, 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(side.points[i].x(), 0.4, 1e-12);
        EXPECT_NEAR(std::abs(side.points[i].y()), 0.5, 1e-12);
    }

    // Halfway between: the rim point (0.4, 0.5, 0).
    const auto rim = feature(cylinder, at, Vector3(1, 1, 0));
    ASSERT_EQ(rim.count, 1);
    EXPECT_LT((rim.points[0] - Vector3(0.4, 0.5, 0)).norm(), 1e-12);

    // Tilted 5 degrees: still the cap, and it holds the exact deepest rim point.
    const Vector3 d = Vector3(std::sin(5 * kPi / 180), -std::cos(5 * kPi / 180), 0);
    const auto tilted = feature(cylinder, at, d);
    ASSERT_GE(tilted.count, 12);
    real deepest = -1;
    for (int i = 0; i < tilted.count; ++i) deepest = std::max(deepest, tilted.points[i].dot(d));
    EXPECT_NEAR(deepest, Vector3(0.4, -0.5, 0).dot(d), 1e-12);
    expectCounterClockwise(tilted, -Vector3::UnitY());
}

TEST(SupportingFeature, ConvexGivesTheMostAlignedHullFace) {
    // The pyramid's base (y = -0.25, 0.8 x 0.8) faces -y.
    const auto f = feature(pyramid(), pose(Vector3(0, 1, 0)), Vector3(0.1, -1, 0));
    ASSERT_EQ(f.count, 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(f.points[i].y(), 0.75, 1e-12);
    expectCounterClockwise(f, -Vector3::UnitY());
}

TEST(SupportingFeature, PlaneIsASquareOnItsSurface) {
    // Normal (0, 3, 0), offset 2: the solid 3y <= 2, surface at y = 2/3.
    const auto f = feature(Shape::plane(Vector3(0, 3, 0), 2), Matrix4::Identity(), -Vector3::UnitY());
    ASSERT_EQ(f.count, 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(f.points[i].y(), 2.0 / 3, 1e-9);
    expectCounterClockwise(f, Vector3::UnitY());
}

TEST(SupportingFeature, MeshGivesItsTriangleFacingTheDirection) {
    const auto up = feature(meshFloor(), Matrix4::Identity(), Vector3::UnitY(), 1);
    ASSERT_EQ(up.count, 3);
    expectCounterClockwise(up, Vector3::UnitY());
    // Triangle 1 is (-5,0,-5), (-5,0,5), (5,0,5).
    for (int i = 0; i < 3; ++i) EXPECT_GE(up.points[i].z(), up.points[i].x());
    const auto down = feature(meshFloor(), Matrix4::Identity(), -Vector3::UnitY(), 1);
    expectCounterClockwise(down, -Vector3::UnitY());
    EXPECT_EQ(feature(meshFloor(), Matrix4::Identity(), Vector3::UnitY(), 2).count, 0);
}

}  // namespace
}  // namespace cyclone::test
