// Unit inertia of each shape against hand formulas, and the convex hull's faces.
#include <gtest/gtest.h>

#include "collision_test_support.h"
#include "collision/convex_hull.h"

namespace cyclone::test {
namespace {

void expectInertia(const Shape &shape, const Matrix3 &expected, real tolerance = 1e-12) {
    const Matrix3 actual = detail::compileShape(shape)->unitInertia();
    EXPECT_LT((actual - expected).cwiseAbs().maxCoeff(), tolerance) << "got\n" << actual << "\nexpected\n" << expected;
}

TEST(UnitInertia, Box) {
    // Full sizes 1 x 2 x 3: Ixx = (2^2 + 3^2)/12, Iyy = (1 + 9)/12, Izz = (1 + 4)/12.
    expectInertia(Shape::box(Vector3(0.5, 1, 1.5)), Vector3(13.0 / 12, 10.0 / 12, 5.0 / 12).asDiagonal());
}

TEST(UnitInertia, Sphere) {
    // 2/5 r^2 with r = 2: 1.6.
    expectInertia(Shape::sphere(2), Matrix3::Identity() * 1.6);
}

TEST(UnitInertia, Cylinder) {
    // r = 0.5, total length 2 along z: Izz = r^2/2 = 0.125; Ixx = (3 r^2 + L^2)/12 = 4.75/12.
    expectInertia(Shape::cylinder(0.5, 2), Vector3(4.75 / 12, 4.75 / 12, 0.125).asDiagonal());
}

TEST(UnitInertia, Capsule) {
    // r = 1, cylindrical part L = 2. Volumes: cylinder 2 pi, two hemispheres 4/3 pi, so the
    // cylinder has 0.6 kg and the hemispheres 0.4 kg.
    // Axis: 0.6 * r^2/2 + 0.4 * 2/5 r^2 = 0.3 + 0.16 = 0.46.
    // Across: cylinder 0.6 (3 + 4)/12 = 0.35; each hemisphere about its centre of mass
    // (83/320) m r^2, at 3r/8 = 0.375 beyond the cylinder's end at 1 m:
    // 0.4 (83/320 + 1.375^2) = 0.4 * 2.15 = 0.86. Total 1.21.
    expectInertia(Shape::capsule(1, 2), Vector3(1.21, 1.21, 0.46).asDiagonal());
    // With no cylindrical part it is a sphere.
    expectInertia(Shape::capsule(0.5, 0), Matrix3::Identity() * 0.1);
}

TEST(UnitInertia, ConvexCubeEqualsBox) {
    // Cube of side 1: 1/6 about each axis.
    expectInertia(convexCube(0.5), Matrix3::Identity() / 6);
}

TEST(UnitInertia, ConvexBoxOfCornersAndInteriorPoints) {
    std::vector<Vector3> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 1 : -1, i & 4 ? 1.5 : -1.5);
    points.emplace_back(0.1, 0.2, 0.3);
    points.emplace_back(-0.2, 0.5, -1.0);
    expectInertia(Shape::convex(points), Vector3(13.0 / 12, 10.0 / 12, 5.0 / 12).asDiagonal());
}

TEST(UnitInertia, ConvexIsAboutTheFrameOrigin) {
    // The unit cube [0, 1]^3 has its centre at c = (1/2, 1/2, 1/2); about the origin
    // I = 1/6 + (c.c - c_x^2) = 1/6 + 1/2 = 2/3 on the diagonal and -c_x c_y = -1/4 off it.
    std::vector<Vector3> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    Matrix3 expected;
    expected << 2.0 / 3, -0.25, -0.25, -0.25, 2.0 / 3, -0.25, -0.25, -0.25, 2.0 / 3;
    expectInertia(Shape::convex(points), expected);
}

TEST(UnitInertia, Tetrahedron) {
    // Corners 0, e1, e2, e3: volume 1/6, integral of x^2 over it 1/60 and of xy 1/120, so per
    // kilogram x^2 averages 1/10 and xy 1/20: Ixx = 2/10, Ixy = -1/20, about the origin.
    Matrix3 expected;
    expected << 0.2, -0.05, -0.05, -0.05, 0.2, -0.05, -0.05, -0.05, 0.2;
    expectInertia(Shape::convex({Vector3::Zero(), Vector3::UnitX(), Vector3::UnitY(), Vector3::UnitZ()}), expected);
}

TEST(UnitInertia, PlaneAndMeshAreIdentity) {
    expectInertia(Shape::plane(Vector3::UnitY(), 0), Matrix3::Identity());
    expectInertia(meshFloor(), Matrix3::Identity());
}

TEST(ConvexHull, CubeWithInteriorPointsHasSixQuadFaces) {
    const auto cube = detail::compileShape(convexCube(0.5));
    EXPECT_EQ(cube->vertices().size(), 8u);
    ASSERT_EQ(cube->faces().size(), 6u);
    ASSERT_EQ(cube->faceNormals().size(), 6u);
    for (size_t f = 0; f < 6; ++f) {
        const std::vector<int> &face = cube->faces()[f];
        ASSERT_EQ(face.size(), 4u);
        const Vector3 &normal = cube->faceNormals()[f];
        // An axis direction, and every vertex on the face at distance 0.5 along it.
        EXPECT_NEAR(normal.cwiseAbs().maxCoeff(), 1, 1e-12);
        for (int index : face) EXPECT_NEAR(cube->vertices()[index].dot(normal), 0.5, 1e-12);
        // Counter-clockwise seen from outside: each turn is positive about the normal.
        for (size_t k = 0; k < 4; ++k) {
            const Vector3 &p0 = cube->vertices()[face[k]];
            const Vector3 &p1 = cube->vertices()[face[(k + 1) % 4]];
            const Vector3 &p2 = cube->vertices()[face[(k + 2) % 4]];
            EXPECT_GT((p1 - p0).cross(p2 - p1).dot(normal), 0.99);
        }
    }
    // The FCL geometry is the same polytope: 6 faces of 4 indices each.
    const auto &convex = static_cast<const fcl::Convexd &>(*cube->geometry());
    EXPECT_EQ(convex.getFaceCount(), 6);
    EXPECT_EQ(convex.getFaces().size(), 30u);
    EXPECT_EQ(convex.getVertices().size(), 8u);
}

TEST(ConvexHull, PointsOnFacesAndEdgesAreNotVertices) {
    std::vector<Vector3> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    points.emplace_back(0, 0, 1);   // Centre of the top face.
    points.emplace_back(1, 0, -1);  // Middle of an edge.
    detail::ConvexHull hull;
    ASSERT_TRUE(detail::computeConvexHull(points, hull));
    EXPECT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.faces.size(), 6u);
}

TEST(ConvexHull, PyramidHasASquareBaseAndFourTriangles) {
    const auto p = detail::compileShape(pyramid());
    EXPECT_EQ(p->vertices().size(), 5u);
    ASSERT_EQ(p->faces().size(), 5u);
    int squares = 0, triangles = 0;
    for (const auto &face : p->faces()) {
        if (face.size() == 4) ++squares;
        if (face.size() == 3) ++triangles;
    }
    EXPECT_EQ(squares, 1);
    EXPECT_EQ(triangles, 4);
    // Volume by the pyramid formula: base 0.64 m^2 times height 1 m over 3.
    real volume = 0;
    Matrix3 inertia;
    Vector3 centroid;
    detail::polyhedronMassProperties(p->vertices(), p->faces(), volume, inertia, centroid);
    EXPECT_NEAR(volume, 0.64 / 3, 1e-12);
}

}  // namespace
}  // namespace cyclone::test
