// compileShape refuses every bad field with InvalidArgument naming the field.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "collision/collision_shape.h"
#include "cyclone/world/error.h"

namespace cyclone::test {
namespace {

constexpr real kNan = std::numeric_limits<real>::quiet_NaN();
constexpr real kInf = std::numeric_limits<real>::infinity();

// Compiles `shape` expecting a refusal of `field`; returns the problem text.
std::string refusal(const Shape &shape, const std::string &field) {
    try {
        detail::compileShape(shape);
    } catch (const InvalidArgument &error) {
        EXPECT_EQ(error.function(), "");
        EXPECT_EQ(error.field(), field) << error.what();
        return error.problem();
    }
    ADD_FAILURE() << "no refusal of " << field;
    return "";
}

TEST(ShapeValidation, NamedConstructorsSetTheirFields) {
    const Shape box = Shape::box(Vector3(1, 2, 3));
    EXPECT_EQ(box.type, ShapeType::Box);
    EXPECT_EQ(box.halfExtents, Vector3(1, 2, 3));
    const Shape capsule = Shape::capsule(0.25, 2);
    EXPECT_EQ(capsule.type, ShapeType::Capsule);
    EXPECT_EQ(capsule.radius, 0.25);
    EXPECT_EQ(capsule.length, 2);
    const Shape plane = Shape::plane(Vector3(0, 0, 2), 1.5);
    EXPECT_EQ(plane.type, ShapeType::Plane);
    EXPECT_EQ(plane.normal, Vector3(0, 0, 2));
    EXPECT_EQ(plane.offset, 1.5);
    const Shape mesh = Shape::mesh({Vector3::Zero(), Vector3::UnitX(), Vector3::UnitZ()}, {{0, 2, 1}});
    EXPECT_EQ(mesh.type, ShapeType::Mesh);
    EXPECT_EQ(mesh.vertices.size(), 3u);
    EXPECT_EQ(mesh.triangles.size(), 1u);
}

TEST(ShapeValidation, TypeNames) {
    EXPECT_STREQ(shapeTypeName(ShapeType::Box), "box");
    EXPECT_STREQ(shapeTypeName(ShapeType::Sphere), "sphere");
    EXPECT_STREQ(shapeTypeName(ShapeType::Capsule), "capsule");
    EXPECT_STREQ(shapeTypeName(ShapeType::Cylinder), "cylinder");
    EXPECT_STREQ(shapeTypeName(ShapeType::Convex), "convex");
    EXPECT_STREQ(shapeTypeName(ShapeType::Plane), "plane");
    EXPECT_STREQ(shapeTypeName(ShapeType::Mesh), "mesh");
}

TEST(ShapeValidation, ValidShapesCompileWithTheirFclGeometry) {
    EXPECT_EQ(detail::compileShape(Shape::box(Vector3(1, 2, 3)))->geometry()->getNodeType(), fcl::GEOM_BOX);
    EXPECT_EQ(detail::compileShape(Shape::sphere(1))->geometry()->getNodeType(), fcl::GEOM_SPHERE);
    EXPECT_EQ(detail::compileShape(Shape::capsule(1, 0))->geometry()->getNodeType(), fcl::GEOM_CAPSULE);
    EXPECT_EQ(detail::compileShape(Shape::cylinder(1, 2))->geometry()->getNodeType(), fcl::GEOM_CYLINDER);
    EXPECT_EQ(detail::compileShape(Shape::plane(Vector3(0, 3, 0), 1))->geometry()->getNodeType(), fcl::GEOM_HALFSPACE);
    EXPECT_EQ(detail::compileShape(Shape::mesh({Vector3::Zero(), Vector3::UnitX(), Vector3::UnitZ()}, {{0, 2, 1}}))
                  ->geometry()
                  ->getNodeType(),
              fcl::BV_OBBRSS);

    // FCL's Box takes full sizes; its Cylinder the total length; its Halfspace a unit
    // normal, the offset divided by the normal's length (0,3,4).x <= 2 is (0,0.6,0.8).x <= 0.4.
    const auto box = detail::compileShape(Shape::box(Vector3(1, 2, 3)));
    EXPECT_EQ(static_cast<const fcl::Boxd &>(*box->geometry()).side, fcl::Vector3d(2, 4, 6));
    const auto cylinder = detail::compileShape(Shape::cylinder(0.5, 2));
    EXPECT_EQ(static_cast<const fcl::Cylinderd &>(*cylinder->geometry()).lz, 2);
    const auto capsule = detail::compileShape(Shape::capsule(0.5, 2));
    EXPECT_EQ(static_cast<const fcl::Capsuled &>(*capsule->geometry()).lz, 2);
    const auto plane = detail::compileShape(Shape::plane(Vector3(0, 3, 4), 2));
    const auto &halfspace = static_cast<const fcl::Halfspaced &>(*plane->geometry());
    EXPECT_NEAR((halfspace.n - fcl::Vector3d(0, 0.6, 0.8)).norm(), 0, 1e-15);
    EXPECT_NEAR(halfspace.d, 0.4, 1e-15);
    EXPECT_NEAR((plane->planeNormal() - Vector3(0, 0.6, 0.8)).norm(), 0, 1e-15);
    EXPECT_NEAR(plane->planeOffset(), 0.4, 1e-15);
}

TEST(ShapeValidation, BoxHalfExtents) {
    EXPECT_EQ(refusal(Shape::box(Vector3(1, -1, 1)), "shape.half_extents[1]"), "must be finite and > 0, got -1");
    refusal(Shape::box(Vector3(0, 1, 1)), "shape.half_extents[0]");
    refusal(Shape::box(Vector3(1, 1, kNan)), "shape.half_extents[2]");
    refusal(Shape::box(Vector3(1, kInf, 1)), "shape.half_extents[1]");
}

TEST(ShapeValidation, SphereRadius) {
    EXPECT_EQ(refusal(Shape::sphere(-1), "shape.radius"), "must be finite and > 0, got -1");
    refusal(Shape::sphere(0), "shape.radius");
    refusal(Shape::sphere(kNan), "shape.radius");
    refusal(Shape::sphere(kInf), "shape.radius");
}

TEST(ShapeValidation, CapsuleRadiusAndLength) {
    refusal(Shape::capsule(0, 1), "shape.radius");
    refusal(Shape::capsule(kNan, 1), "shape.radius");
    EXPECT_EQ(refusal(Shape::capsule(1, -0.5), "shape.length"), "must be finite and >= 0, got -0.5");
    refusal(Shape::capsule(1, kInf), "shape.length");
    EXPECT_NO_THROW(detail::compileShape(Shape::capsule(1, 0)));  // A sphere-like capsule is fine.
}

TEST(ShapeValidation, CylinderRadiusAndLength) {
    refusal(Shape::cylinder(-2, 1), "shape.radius");
    EXPECT_EQ(refusal(Shape::cylinder(1, 0), "shape.length"), "must be finite and > 0, got 0");
    refusal(Shape::cylinder(1, kNan), "shape.length");
}

TEST(ShapeValidation, ConvexPoints) {
    std::vector<Vector3> tetrahedron = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
    EXPECT_NO_THROW(detail::compileShape(Shape::convex(tetrahedron)));

    std::vector<Vector3> three(tetrahedron.begin(), tetrahedron.begin() + 3);
    EXPECT_EQ(refusal(Shape::convex(three), "shape.vertices"), "needs at least 4 points, got 3");

    std::vector<Vector3> bad = tetrahedron;
    bad[3].x() = kNan;
    refusal(Shape::convex(bad), "shape.vertices[3][0]");
    bad = tetrahedron;
    bad[2].z() = -kInf;
    refusal(Shape::convex(bad), "shape.vertices[2][2]");

    // Five points of the plane x + y + z = 1: no volume.
    std::vector<Vector3> flat = {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1), Vector3(0.5, 0.5, 0),
                                 Vector3(0.2, 0.3, 0.5)};
    refusal(Shape::convex(flat), "shape.vertices");
    // Four collinear points and four equal points.
    refusal(Shape::convex({Vector3(0, 0, 0), Vector3(1, 1, 1), Vector3(2, 2, 2), Vector3(3, 3, 3)}), "shape.vertices");
    refusal(Shape::convex(std::vector<Vector3>(4, Vector3(1, 2, 3))), "shape.vertices");
}

TEST(ShapeValidation, PlaneNormalAndOffset) {
    EXPECT_EQ(refusal(Shape::plane(Vector3::Zero(), 0), "shape.normal"), "must have non-zero length");
    refusal(Shape::plane(Vector3(kNan, 1, 0), 0), "shape.normal[0]");
    refusal(Shape::plane(Vector3(0, 1, kInf), 0), "shape.normal[2]");
    EXPECT_EQ(refusal(Shape::plane(Vector3::UnitY(), kInf), "shape.offset"), "must be finite, got inf");
    refusal(Shape::plane(Vector3::UnitY(), kNan), "shape.offset");
}

TEST(ShapeValidation, MeshVerticesAndTriangles) {
    const std::vector<Vector3> square = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 0, 1), Vector3(0, 0, 1)};
    EXPECT_NO_THROW(detail::compileShape(Shape::mesh(square, {{0, 2, 1}, {0, 3, 2}})));

    EXPECT_EQ(refusal(Shape::mesh(square, {}), "shape.triangles"), "must not be empty");
    EXPECT_EQ(refusal(Shape::mesh(square, {{0, 2, 1}, {0, 3, 2}, {0, 7, 2}}), "shape.triangles[2][1]"),
              "must be a vertex index in [0, 4), got 7");
    refusal(Shape::mesh(square, {{-1, 2, 1}}), "shape.triangles[0][0]");
    refusal(Shape::mesh(square, {{0, 2, 1}, {3, 3, 2}}), "shape.triangles[1][1]");
    refusal(Shape::mesh(square, {{0, 2, 1}, {0, 3, 0}}), "shape.triangles[1][2]");
    refusal(Shape::mesh({}, {{0, 1, 2}}), "shape.triangles[0][0]");

    // (0,0,0), (1,0,0), (2,0,0) are collinear: zero area.
    std::vector<Vector3> line = square;
    line.emplace_back(2, 0, 0);
    refusal(Shape::mesh(line, {{0, 2, 1}, {0, 1, 4}}), "shape.triangles[1]");

    std::vector<Vector3> bad = square;
    bad[3][0] = kNan;
    refusal(Shape::mesh(bad, {{0, 2, 1}}), "shape.vertices[3][0]");

    for (MeshSides sides : {MeshSides::Both, MeshSides::Front, MeshSides::Back})
        EXPECT_NO_THROW(detail::compileShape(Shape::mesh(square, {{0, 2, 1}}, sides)));
    EXPECT_EQ(refusal(Shape::mesh(square, {{0, 2, 1}}, static_cast<MeshSides>(7)), "shape.sides"),
              "must be MeshSides::Both, Front or Back, got 7");
}

TEST(ShapeValidation, OnlyTheFieldsOfTheTypeAreRead) {
    Shape sphere = Shape::sphere(1);
    sphere.halfExtents = Vector3(-1, -1, -1);
    sphere.length = -3;
    sphere.normal = Vector3::Zero();
    EXPECT_NO_THROW(detail::compileShape(sphere));
}

}  // namespace
}  // namespace cyclone::test
