// A validated, compiled collision shape: FCL geometry, mass properties and the
// supporting features that manifold building clips against.
#pragma once

#include <fcl/fcl.h>

#include <memory>
#include <vector>

#include "cyclone/world/shape.h"

namespace cyclone::detail {

/// A feature of a shape that supports it in a direction: 1 point (vertex or curved
/// surface), 2 points (an edge) or a convex polygon (a face), in world space,
/// counter-clockwise seen from outside the shape (a mesh triangle: from the side the
/// direction points to).
struct SupportFeature {
    static constexpr int kMaxPoints = 32;
    int count = 0;
    Vector3 points[kMaxPoints];
};

class CollisionShape {
public:
    /// The description it was compiled from (convex: the input points).
    const Shape &shape() const { return shape_; }
    /// FCL geometry in the shape's frame (Halfspace, Box, Sphere, Capsule, Cylinder,
    /// Convex or BVHModel<OBBRSS>).
    const std::shared_ptr<fcl::CollisionGeometryd> &geometry() const { return geometry_; }
    /// Inertia tensor of a 1 kg body of this shape about the frame origin, kg m^2.
    const Matrix3 &unitInertia() const { return unitInertia_; }
    /// Hull vertices (convex) or mesh vertices, shape frame.
    const std::vector<Vector3> &vertices() const { return vertices_; }
    /// Hull faces as vertex-index loops, counter-clockwise seen from outside (convex),
    /// or mesh triangles.
    const std::vector<std::vector<int>> &faces() const { return faces_; }
    /// Outward unit normal of each face, shape frame.
    const std::vector<Vector3> &faceNormals() const { return faceNormals_; }
    /// Plane: outward unit normal, shape frame (the solid is normal.x <= planeOffset()).
    const Vector3 &planeNormal() const { return planeNormal_; }
    /// Plane: distance of the surface from the frame origin along planeNormal(), m
    /// (the shape's offset divided by the length of its normal).
    real planeOffset() const { return planeOffset_; }

    /// The feature of this shape, placed at `pose`, that is furthest along the world
    /// direction `direction` (unit). `triangle` selects the triangle of a mesh (FCL's
    /// primitive index); other shapes ignore it. Box, convex: the face most aligned with
    /// the direction. Sphere: a point. Capsule: its side (2 points) when the axis is
    /// within 5 degrees of perpendicular, else a point. Cylinder: its cap (a 16-gon, plus
    /// the deepest rim point when tilted over 1 degree) within 15 degrees of the axis, its
    /// side within 5 degrees of perpendicular, else a rim point. Plane: a 2 km square
    /// centred on the pose origin's projection. Mesh: the triangle (none if out of range).
    void supportingFeature(const Matrix4 &pose, const Vector3 &direction, int triangle,
                           SupportFeature &out) const;

    /// The point of this shape, placed at `pose`, furthest along the world direction
    /// `direction` (unit): exact for every solid shape; a mesh uses its triangle
    /// `triangle`; a plane, unbounded, gives the point of its surface nearest the pose
    /// origin.
    Vector3 supportPoint(const Matrix4 &pose, const Vector3 &direction, int triangle) const;

private:
    friend std::shared_ptr<const CollisionShape> compileShape(const Shape &shape);
    Shape shape_;
    std::shared_ptr<fcl::CollisionGeometryd> geometry_;
    Matrix3 unitInertia_ = Matrix3::Identity();
    std::vector<Vector3> vertices_;
    std::vector<std::vector<int>> faces_;
    std::vector<Vector3> faceNormals_;
    Vector3 planeNormal_ = Vector3::UnitY();
    real planeOffset_ = 0;
};

/// Validates and compiles a shape. Throws InvalidArgument with function "" and a field
/// path relative to the shape (e.g. "shape.radius", "shape.vertices[3][1]"); callers
/// re-throw with their own function name.
std::shared_ptr<const CollisionShape> compileShape(const Shape &shape);

}  // namespace cyclone::detail
