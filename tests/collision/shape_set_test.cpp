// ShapeSet: a description equal bit for bit to one already compiled finds that shape; any
// field that differs, by as little as one ulp, makes another.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/shape_set.h"

namespace cyclone::test {
namespace {

using detail::ShapeSet;

std::vector<Vector3> rockPoints() {
    return {Vector3(0.3, 0, 0),    Vector3(-0.28, 0.05, 0.02), Vector3(0, 0.27, 0.03), Vector3(0.02, -0.3, -0.01),
            Vector3(0.01, 0.02, 0.29), Vector3(-0.03, 0, -0.31), Vector3(0.18, 0.18, 0.16)};
}

std::uint32_t added(ShapeSet &set, const Shape &description) {
    return set.add(detail::compileShape(description));
}

TEST(ShapeSet, EqualDescriptionsFindTheShapeCompiledFirst) {
    ShapeSet set;
    EXPECT_FALSE(set.find(Shape::convex(rockPoints())).has_value());
    const std::uint32_t box = added(set, Shape::box(Vector3(0.5, 0.2, 0.1)));
    const std::uint32_t rock = added(set, Shape::convex(rockPoints()));
    ASSERT_EQ(set.find(Shape::box(Vector3(0.5, 0.2, 0.1))), box);
    ASSERT_EQ(set.find(Shape::convex(rockPoints())), rock);
    // The shape found is the one compiled: its hull, not a copy.
    EXPECT_EQ(&set[rock]->hullEdges(), &set[*set.find(Shape::convex(rockPoints()))]->hullEdges());
    EXPECT_EQ(set.size(), 2u);
}

TEST(ShapeSet, OneUlpOrOneFieldApartIsAnotherShape) {
    ShapeSet set;
    added(set, Shape::box(Vector3(0.5, 0.2, 0.1)));
    std::vector<Vector3> points = rockPoints();
    added(set, Shape::convex(points));
    added(set, Shape::cylinder(0.3, 1.0));
    added(set, Shape::capsule(0.3, 1.0, Axis::Y));

    EXPECT_FALSE(set.find(Shape::box(Vector3(0.5, std::nextafter(0.2, 1.0), 0.1))).has_value());
    points[4].z() = std::nextafter(points[4].z(), 1.0);
    EXPECT_FALSE(set.find(Shape::convex(points)).has_value());
    // The same points in another order: another description, so another shape.
    std::vector<Vector3> turned = rockPoints();
    std::swap(turned[0], turned[1]);
    EXPECT_FALSE(set.find(Shape::convex(turned)).has_value());
    // Radius and length alike, type not.
    EXPECT_FALSE(set.find(Shape::capsule(0.3, 1.0)).has_value());
    // A compound's children: the same capsule turned about another axis.
    EXPECT_FALSE(set.find(Shape::capsule(0.3, 1.0, Axis::X)).has_value());
    EXPECT_TRUE(set.find(Shape::capsule(0.3, 1.0, Axis::Y)).has_value());
    // A field the type does not read still counts: equal bit for bit means every field.
    Shape box = Shape::box(Vector3(0.5, 0.2, 0.1));
    box.radius = 7;
    EXPECT_FALSE(set.find(box).has_value());
}

TEST(ShapeSet, MeshesAndHeightfieldsAreFoundByTheirData) {
    ShapeSet set;
    const std::vector<Vector3> corners = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 0, 1), Vector3(1, 0, 1)};
    const std::uint32_t mesh = added(set, Shape::mesh(corners, {{0, 2, 1}, {1, 2, 3}}));
    EXPECT_EQ(set.find(Shape::mesh(corners, {{0, 2, 1}, {1, 2, 3}})), mesh);
    EXPECT_FALSE(set.find(Shape::mesh(corners, {{0, 2, 1}})).has_value());
    EXPECT_FALSE(set.find(Shape::mesh(corners, {{0, 2, 1}, {1, 2, 3}}, MeshSides::Front)).has_value());
    const std::uint32_t field = added(set, Shape::heightfield(2, 3, {1, 1}, {0, 0.5, 1, 0, 0.5, 1}));
    EXPECT_EQ(set.find(Shape::heightfield(2, 3, {1, 1}, {0, 0.5, 1, 0, 0.5, 1})), field);
    EXPECT_FALSE(set.find(Shape::heightfield(2, 3, {1, 1}, {0, 0.5, 1, 0, 0.5, 2})).has_value());
}

}  // namespace
}  // namespace cyclone::test
