// A validated, compiled collision shape: FCL geometry, mass properties and the
// supporting features that manifold building clips against.
#pragma once

#include <fcl/fcl.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "collision/polytope.h"
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

class CollisionShape;

/// A child of a compiled compound: its shape and its pose in the body's frame (whose
/// origin is the compound's centre of mass).
struct CompoundPart {
    std::shared_ptr<const CollisionShape> shape;
    Matrix4 pose = Matrix4::Identity();
};

class CollisionShape {
public:
    /// The description it was compiled from (convex: the input points).
    const Shape &shape() const { return shape_; }
    /// FCL geometry in the shape's frame (Halfspace, Box, Sphere, Capsule, Cylinder,
    /// Convex or BVHModel<OBBRSS>). A compound's is a box whose local AABB bounds its
    /// children, for the broadphase only: its children are what collide.
    const std::shared_ptr<fcl::CollisionGeometryd> &geometry() const { return geometry_; }
    /// Inertia tensor of a 1 kg body of this shape about the frame origin, kg m^2.
    const Matrix3 &unitInertia() const { return unitInertia_; }
    /// Whether this is a compound (then children() are what collide).
    bool isCompound() const { return !parts_.empty(); }
    /// A compound's children, posed in the body's frame (origin at the centre of mass).
    const std::vector<CompoundPart> &children() const { return parts_; }
    /// A compound's centre of mass in the frame its children were placed in (the frame
    /// the user places the body by), m; zero for other shapes, whose frame is the body's.
    const Vector3 &frameToCentre() const { return frameToCentre_; }
    /// Volume of a solid shape, m^3 (0 for planes and meshes).
    real volume() const { return volume_; }
    /// Centroid of a solid shape in its frame, m (a convex hull's need not be the origin).
    const Vector3 &centroid() const { return centroid_; }
    /// Farthest point of a solid shape from its frame origin, m (0 for planes).
    real boundingRadius() const { return boundingRadius_; }
    /// Radius of a ball about the frame origin that lies inside a solid shape, m, so that
    /// its support along any unit direction reaches at least that far; -1 where none is
    /// known (planes, meshes, height fields, compounds, a hull that misses its origin).
    real innerRadius() const { return innerRadius_; }
    /// Hull vertices (convex) or mesh vertices, shape frame.
    const std::vector<Vector3> &vertices() const { return vertices_; }
    /// Hull faces as vertex-index loops, counter-clockwise seen from outside (convex),
    /// or mesh triangles.
    const std::vector<std::vector<int>> &faces() const { return faces_; }
    /// Outward unit normal of each face, shape frame.
    const std::vector<Vector3> &faceNormals() const { return faceNormals_; }
    /// Mesh or height field: triangle t's active edges and vertices (mesh_features.h),
    /// the corners of its surface; contacts on the others take the triangle's normal.
    /// Stored for a mesh, computed from the heights around it for a height field.
    std::uint8_t activeFeatures(int t) const;
    /// Whether this is a mesh or a height field: a surface of triangles, numbered by
    /// FCL's primitive index (mesh) or by cell (heightfield.h).
    bool hasTriangles() const {
        return shape_.type == ShapeType::Mesh || shape_.type == ShapeType::Heightfield;
    }
    /// Mesh or height field: the number of triangles.
    int triangleCount() const;
    /// Mesh or height field: triangle t's corners (shape frame) and their vertex numbers.
    void triangle(int t, Vector3 (&corners)[3], int (&ids)[3]) const;
    /// Mesh or height field: triangle t's unit normal (counter-clockwise side), shape frame.
    Vector3 triangleNormal(int t) const;
    /// Which sides of the triangles collide: a mesh's own; a height field's front (its
    /// solid lies below).
    MeshSides triangleSides() const {
        return shape_.type == ShapeType::Heightfield ? MeshSides::Front : shape_.sides;
    }
    /// Convex hull: its face offsets and edges for the separating-axis test (polytope.h);
    /// empty for other shapes.
    const HullEdges &hullEdges() const;
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
    /// Compound: the feature of the child whose support point is furthest.
    void supportingFeature(const Matrix4 &pose, const Vector3 &direction, int triangle,
                           SupportFeature &out) const;

    /// The point of this shape, placed at `pose`, furthest along the world direction
    /// `direction` (unit): exact for every solid shape; a mesh uses its triangle
    /// `triangle`; a plane, unbounded, gives the point of its surface nearest the pose
    /// origin; a compound gives the furthest of its children's.
    Vector3 supportPoint(const Matrix4 &pose, const Vector3 &direction, int triangle) const;

private:
    /// A compound's child whose support point along `direction` is furthest.
    std::size_t furthestPart(const Matrix4 &pose, const Vector3 &direction) const;
    friend std::shared_ptr<const CollisionShape> compileShape(const Shape &shape);
    friend void compileCompound(const Shape &shape, CollisionShape &compiled);
    Shape shape_;
    std::shared_ptr<fcl::CollisionGeometryd> geometry_;
    Matrix3 unitInertia_ = Matrix3::Identity();
    std::vector<Vector3> vertices_;
    std::vector<std::vector<int>> faces_;
    std::vector<Vector3> faceNormals_;
    std::shared_ptr<const HullEdges> hullEdges_;
    std::vector<std::uint8_t> activeFeatures_;
    Vector3 planeNormal_ = Vector3::UnitY();
    real planeOffset_ = 0;
    std::vector<CompoundPart> parts_;
    Vector3 frameToCentre_ = Vector3::Zero();
    real volume_ = 0;
    Vector3 centroid_ = Vector3::Zero();
    real boundingRadius_ = 0;
    real innerRadius_ = -1;
};

/// The world pose of child `k` of a compound placed at `pose`.
inline Matrix4 partPose(const CollisionShape &compound, std::size_t k, const Matrix4 &pose) {
    return pose * compound.children()[k].pose;
}

/// Validates and compiles a shape. Throws InvalidArgument with function "" and a field
/// path relative to the shape (e.g. "shape.radius", "shape.vertices[3][1]"); callers
/// re-throw with their own function name.
std::shared_ptr<const CollisionShape> compileShape(const Shape &shape);

}  // namespace cyclone::detail
