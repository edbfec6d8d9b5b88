// Collision shapes: a plain description that the World validates and compiles.
#pragma once

#include <array>
#include <vector>

#include "cyclone/core.h"

namespace cyclone {

/// The kinds of collision shape. Plane and Mesh are for static bodies only.
enum class ShapeType { Box, Sphere, Capsule, Cylinder, Convex, Plane, Mesh };

/// A collision shape in the body's own frame; the body's position is the frame's origin.
/// Build one with the named constructors; only the fields of its type are read.
struct Shape {
    ShapeType type = ShapeType::Box;
    Vector3 halfExtents = Vector3(0.5, 0.5, 0.5);  ///< Box half sizes, m, each > 0.
    real radius = 0.5;                             ///< Sphere, capsule, cylinder radius, m, > 0.
    real length = 1.0;  ///< Capsule: length of the cylindrical part (>= 0); cylinder: total length (> 0); m, along local z.
    std::vector<Vector3> vertices;               ///< Convex: points whose hull is the shape; mesh: vertices; m.
    std::vector<std::array<int, 3>> triangles;   ///< Mesh: vertex indices of each triangle.
    Vector3 normal = Vector3::UnitY();           ///< Plane: outward normal (any length > 0).
    real offset = 0;                             ///< Plane: solid half-space normal.x <= offset (normal normalised), m.

    static Shape box(const Vector3 &halfExtents);
    static Shape sphere(real radius);
    static Shape capsule(real radius, real length);
    static Shape cylinder(real radius, real length);
    static Shape convex(std::vector<Vector3> points);
    static Shape plane(const Vector3 &normal, real offset);
    static Shape mesh(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles);
};

/// Name of a shape type as in scene files: "box", "sphere", ...
const char *shapeTypeName(ShapeType type);

}  // namespace cyclone
