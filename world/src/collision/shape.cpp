#include "cyclone/world/shape.h"

#include <utility>

namespace cyclone {

Shape Shape::box(const Vector3 &halfExtents) {
    Shape shape;
    shape.type = ShapeType::Box;
    shape.halfExtents = halfExtents;
    return shape;
}

Shape Shape::sphere(real radius) {
    Shape shape;
    shape.type = ShapeType::Sphere;
    shape.radius = radius;
    return shape;
}

namespace {

// `shape` (along z) turned so that it lies along `axis`: a compound of one child.
Shape alongAxis(Shape shape, Axis axis) {
    if (axis == Axis::Z) return shape;
    CompoundChild child;
    // A quarter turn about y takes z to x; a quarter turn about -x takes z to y.
    const Vector3 turnAxis = axis == Axis::X ? Vector3::UnitY() : Vector3(-Vector3::UnitX());
    child.orientation = Quaternion(Eigen::AngleAxis<real>(real(1.5707963267948966), turnAxis));
    child.shape = std::move(shape);
    return Shape::compound({std::move(child)});
}

}  // namespace

Shape Shape::capsule(real radius, real length, Axis axis) {
    Shape shape;
    shape.type = ShapeType::Capsule;
    shape.radius = radius;
    shape.length = length;
    return alongAxis(std::move(shape), axis);
}

Shape Shape::cylinder(real radius, real length, Axis axis) {
    Shape shape;
    shape.type = ShapeType::Cylinder;
    shape.radius = radius;
    shape.length = length;
    return alongAxis(std::move(shape), axis);
}

Shape Shape::convex(std::vector<Vector3> points) {
    Shape shape;
    shape.type = ShapeType::Convex;
    shape.vertices = std::move(points);
    return shape;
}

Shape Shape::plane(const Vector3 &normal, real offset) {
    Shape shape;
    shape.type = ShapeType::Plane;
    shape.normal = normal;
    shape.offset = offset;
    return shape;
}

Shape Shape::mesh(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles, MeshSides sides) {
    Shape shape;
    shape.type = ShapeType::Mesh;
    shape.sides = sides;
    shape.vertices = std::move(vertices);
    shape.triangles = std::move(triangles);
    return shape;
}

Shape Shape::compound(std::vector<CompoundChild> children) {
    Shape shape;
    shape.type = ShapeType::Compound;
    shape.children = std::move(children);
    return shape;
}

Shape Shape::heightfield(int rows, int columns, const std::array<real, 2> &spacing, std::vector<real> heights) {
    Shape shape;
    shape.type = ShapeType::Heightfield;
    shape.rows = rows;
    shape.columns = columns;
    shape.spacing = spacing;
    shape.heights = std::move(heights);
    return shape;
}

const char *shapeTypeName(ShapeType type) {
    switch (type) {
        case ShapeType::Box: return "box";
        case ShapeType::Sphere: return "sphere";
        case ShapeType::Capsule: return "capsule";
        case ShapeType::Cylinder: return "cylinder";
        case ShapeType::Convex: return "convex";
        case ShapeType::Plane: return "plane";
        case ShapeType::Mesh: return "mesh";
        case ShapeType::Compound: return "compound";
        case ShapeType::Heightfield: return "heightfield";
    }
    return "unknown";
}

}  // namespace cyclone
