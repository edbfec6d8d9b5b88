// A height field's contacts against the same triangles as a one-sided mesh tested by FCL
// (the reference): the same normals, depths and points; plus hand-worked cases.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "collision/heightfield.h"
#include "collision/mesh_features.h"
#include "collision_test_support.h"

namespace cyclone::test::heightfield_contact {
namespace {

// A rolling 6 x 7 field, 0.5 m cells: h = 0.3 sin(x) cos(0.8 z) + 0.1 z.
Shape rollingField() {
    std::vector<real> heights;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 7; ++j) heights.push_back(0.3 * std::sin(0.5 * j) * std::cos(0.4 * i) + 0.05 * i);
    return Shape::heightfield(6, 7, {0.5, 0.5}, heights);
}

// The same triangles as a mesh, one-sided with its solid behind (below), built from the
// definition in scene-format.md: sample (i, j) at (j dx, h, i dz); each cell split along
// its (i, j)-(i+1, j+1) diagonal, wound to face up.
Shape equivalentMesh(const Shape &f) {
    std::vector<Vector3> vertices;
    for (int i = 0; i < f.rows; ++i)
        for (int j = 0; j < f.columns; ++j)
            vertices.emplace_back(j * f.spacing[0], f.heights[static_cast<std::size_t>(i * f.columns + j)], i * f.spacing[1]);
    std::vector<std::array<int, 3>> triangles;
    for (int i = 0; i + 1 < f.rows; ++i)
        for (int j = 0; j + 1 < f.columns; ++j) {
            const int a = i * f.columns + j, b = a + f.columns, c = a + 1, d = b + 1;
            // (a, b, d): (b - a) = (0, ., dz), (d - a) = (dx, ., dz); their cross product's
            // y is dz dx > 0: up. Likewise (a, d, c).
            triangles.push_back({a, b, d});
            triangles.push_back({a, d, c});
        }
    return Shape::mesh(vertices, triangles, MeshSides::Front);
}

void expectSameManifolds(const std::vector<Manifold> &field, const std::vector<Manifold> &mesh) {
    ASSERT_EQ(field.size(), mesh.size());
    for (std::size_t k = 0; k < field.size(); ++k) {
        EXPECT_LT((field[k].normal - mesh[k].normal).norm(), 1e-6);
        ASSERT_EQ(field[k].count, mesh[k].count);
        // The same points, in any order.
        for (int p = 0; p < field[k].count; ++p) {
            bool matched = false;
            for (int q = 0; q < mesh[k].count; ++q)
                if ((field[k].points[p].pointB - mesh[k].points[q].pointB).norm() < 1e-6 &&
                    std::abs(field[k].points[p].depth - mesh[k].points[q].depth) < 1e-6)
                    matched = true;
            EXPECT_TRUE(matched) << "point " << p << " of manifold " << k;
        }
    }
}

TEST(HeightfieldContact, MatchesTheEquivalentMeshTestedByFcl) {
    const Shape f = rollingField();
    const Shape mesh = equivalentMesh(f);
    struct Case {
        const char *name;
        Shape shape;
        Vector3 at;  // x, z on the field; y: the depth below the surface there
        Quaternion turn;
    };
    const Case cases[] = {
        {"sphere", Shape::sphere(0.3), Vector3(1.1, 0.02, 1.3), Quaternion::Identity()},
        {"box", Shape::box(Vector3(0.3, 0.2, 0.25)), Vector3(1.6, 0.03, 1.1), rotation(0.3, Vector3(1, 2, 0.5))},
        {"capsule", Shape::capsule(0.15, 0.6), Vector3(1.4, 0.01, 1.7), rotation(1.2, Vector3(1, 0.2, 0))},
        {"cylinder", Shape::cylinder(0.25, 0.4), Vector3(0.9, 0.02, 0.8), rotation(0.2, Vector3(0, 0, 1))},
        {"hull", pyramid(), Vector3(2.1, 0.02, 1.2), rotation(2.9, Vector3(1, 0, 0.1))},
    };
    const auto compiledField = detail::compileShape(f);
    const detail::HeightfieldGrid grid(compiledField->shape());
    for (const Case &c : cases) {
        SCOPED_TRACE(c.name);
        // Its lowest point put c.at.y() below the surface point under it (found by a ray
        // down from above).
        const auto shape = detail::compileShape(c.shape);
        Matrix4 p = pose(Vector3(c.at.x(), 0, c.at.z()), c.turn);
        const Vector3 lowest = shape->supportPoint(p, -Vector3::UnitY(), -1);
        real t = 0;
        Vector3 n;
        ASSERT_TRUE(detail::rayHeightfield(Vector3(lowest.x(), 10, lowest.z()), -Vector3::UnitY(), grid,
                                           compiledField->geometry()->aabb_local, 20, t, n));
        p.translation().y() = 10 - t - lowest.y() - c.at.y();
        const std::vector<Manifold> byField = collide(c.shape, p, f, pose(Vector3::Zero()));
        const std::vector<Manifold> byMesh = collide(c.shape, p, mesh, pose(Vector3::Zero()));
        ASSERT_FALSE(byMesh.empty());
        expectSameManifolds(byField, byMesh);
    }
}

TEST(HeightfieldContact, FlatFieldHoldsABoxOnItsFourCorners) {
    // A 0.3 m box 1 cm into a flat field at y = 0.2 across four cells: one manifold,
    // normal down (box to field), its four bottom corners each 0.01 m deep.
    const Shape f = Shape::heightfield(4, 4, {0.5, 0.5}, std::vector<real>(16, 0.2));
    const std::vector<Manifold> out =
        collide(Shape::box(Vector3(0.3, 0.3, 0.3)), pose(Vector3(0.75, 0.49, 0.75)), f, pose(Vector3::Zero()));
    ASSERT_EQ(out.size(), 1u);
    EXPECT_LT((out[0].normal - kDown).norm(), 1e-12);
    ASSERT_EQ(out[0].count, 4);
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(out[0].points[k].depth, 0.01, 1e-9);
        EXPECT_NEAR(std::abs(out[0].points[k].pointA.x() - 0.75), 0.3, 1e-9);
        EXPECT_NEAR(std::abs(out[0].points[k].pointA.z() - 0.75), 0.3, 1e-9);
    }
}

TEST(HeightfieldContact, InnerEdgesAreTheMeshsInnerEdges) {
    // The active features the field computes from its heights are those
    // meshActiveFeatures gives the equivalent mesh, triangle by triangle.
    const Shape f = rollingField();
    const auto field = detail::compileShape(f);
    const auto mesh = detail::compileShape(equivalentMesh(f));
    ASSERT_EQ(field->triangleCount(), mesh->triangleCount());
    for (int t = 0; t < field->triangleCount(); ++t)
        EXPECT_EQ(field->activeFeatures(t), mesh->activeFeatures(t))
            << "triangle " << t;
}

}  // namespace
}  // namespace cyclone::test::heightfield_contact
