/// \file
/// Collision shapes: a plain description that the World validates (World::addBody,
/// World::overlap) and compiles. Sizes are in m, in the body's own frame.
#pragma once

#include <array>
#include <vector>

#include "cyclone/core.h"

namespace cyclone {

/// The kinds of collision shape. Plane, Mesh and Heightfield are for static bodies only.
enum class ShapeType {
    Box,       ///< Shape::box: a box, by half extents.
    Sphere,    ///< Shape::sphere.
    Capsule,   ///< Shape::capsule: along local z.
    Cylinder,  ///< Shape::cylinder: along local z.
    Convex,    ///< Shape::convex: the hull of points.
    Plane,     ///< Shape::plane: a half-space; static bodies only.
    Mesh,      ///< Shape::mesh: triangles; static bodies only.
    Compound,  ///< Shape::compound: convex children, each placed in the body's frame.
    Heightfield,  ///< Shape::heightfield: a grid of heights, solid below; static bodies only.
};

/// Which sides of a mesh's triangles collide, and so where its solid lies.
enum class MeshSides {
    Both,   ///< Two-sided (the default): a thin surface; a shape is pushed out to the side its centre is on.
    Front,  ///< One-sided: the solid lies behind the side the counter-clockwise winding faces; shapes are pushed out to the front.
    Back,   ///< One-sided: the solid lies in front of the counter-clockwise side; shapes are pushed out to the back.
};

struct CompoundChild;

/// A local axis: the one a capsule or cylinder lies along.
enum class Axis {
    X,  ///< Local x.
    Y,  ///< Local y: upright when the body is not turned and gravity is along -y.
    Z,  ///< Local z: FCL's convention and the scene format's, the default.
};

/// Most corners a convex shape keeps (Shape::convex says how a larger hull is
/// simplified); as Jolt's cap, since each contact test walks them.
inline constexpr int kMaxHullVertices = 256;

/// A collision shape in the body's own frame; the body's position is the frame's origin.
/// Build one with the named constructors; only the fields of its type are read.
struct Shape {
    /// Which kind of shape; selects the fields below that are read.
    ShapeType type = ShapeType::Box;
    Vector3 halfExtents = Vector3(0.5, 0.5, 0.5);  ///< Box half sizes, m, each > 0.
    real radius = 0.5;                             ///< Sphere, capsule, cylinder radius, m, > 0.
    real length = 1.0;  ///< Capsule: length of the cylindrical part (>= 0); cylinder: total length (> 0); m, along local z.
    std::vector<Vector3> vertices;               ///< Convex: points whose hull is the shape; mesh: vertices; m.
    std::vector<std::array<int, 3>> triangles;   ///< Mesh: vertex indices of each triangle.
    MeshSides sides = MeshSides::Both;           ///< Mesh: which sides of its triangles collide.
    Vector3 normal = Vector3::UnitY();           ///< Plane: outward normal (any length > 0).
    real offset = 0;  ///< Plane: the solid is normal.x <= offset with the normal as given (distance offset/|normal| along it), m.
    /// Compound: the children, at least one, each a box, sphere, capsule, cylinder or convex hull.
    std::vector<CompoundChild> children;
    int rows = 0;     ///< Heightfield: samples along local z, >= 2.
    int columns = 0;  ///< Heightfield: samples along local x, >= 2.
    std::array<real, 2> spacing = {1, 1};  ///< Heightfield: sample spacing along x and z, m, each > 0.
    std::vector<real> heights;  ///< Heightfield: rows x columns heights (m, finite), row by row.

    /// A box centred on the origin with half sizes `halfExtents` along x, y, z (m, each
    /// finite and > 0).
    static Shape box(const Vector3 &halfExtents);
    /// A sphere centred on the origin (radius in m, finite, > 0).
    static Shape sphere(real radius);
    /// A capsule along `axis` centred on the origin: a cylinder of radius `radius` and
    /// length `length` capped by two half spheres (m; radius finite > 0, length finite
    /// >= 0; the whole capsule is length + 2 radius long). Along z by default (FCL's
    /// convention and the scene format's); Axis::Y stands a character upright. Along x
    /// or y it is a compound of one z capsule turned a quarter turn, so its type is
    /// Compound (mass, inertia and collisions are the turned capsule's).
    static Shape capsule(real radius, real length, Axis axis = Axis::Z);
    /// A cylinder along `axis` centred on the origin (m; radius and total length finite,
    /// > 0); along x or y a compound of one turned z cylinder, as capsule().
    static Shape cylinder(real radius, real length, Axis axis = Axis::Z);
    /// The convex hull of `points` (m, finite; at least 4 not all in one plane). The body's
    /// origin is the frame of the points, not necessarily the hull's centre of mass.
    /// A hull of more than kMaxHullVertices corners is replaced by the hull of
    /// kMaxHullVertices of them chosen by farthest-point sampling (the corner farthest from
    /// the corners' centroid, then each time the corner farthest from those chosen): it
    /// lies inside the true hull, and every corner of the true hull lies within r of a
    /// chosen one, where r is at most twice the least r any choice of that many corners
    /// could reach (the chosen ones are pairwise r apart). For corners on a sphere of
    /// radius R, r <= 4 R / sqrt(kMaxHullVertices) = R / 4 (caps of chord radius r / 2
    /// about the chosen corners do not overlap, and each has area pi (r / 2)^2).
    /// Mass properties and collisions use the simplified hull.
    static Shape convex(std::vector<Vector3> points);
    /// A half-space for static bodies: the solid side is normal.x <= offset with the normal
    /// as given (any finite length > 0), so its surface lies offset/|normal| m from the
    /// body's origin along the unit normal.
    static Shape plane(const Vector3 &normal, real offset);
    /// A triangle mesh for static bodies (m, finite): each triangle three distinct vertex
    /// indices of non-zero area, at least one triangle. `sides` says which sides of the
    /// triangles collide: both by default (a thin surface, whatever the winding), or one,
    /// with the solid behind it (MeshSides).
    static Shape mesh(std::vector<Vector3> vertices, std::vector<std::array<int, 3>> triangles,
                      MeshSides sides = MeshSides::Both);
    /// A body made of convex children (box, sphere, capsule, cylinder or convex; at least
    /// one), each placed in the compound's frame. The children's mass is spread at one
    /// density: the centre of mass and inertia follow from their volumes and places
    /// (parallel-axis theorem). A body with a compound shape is placed by this frame
    /// (BodySettings::position and orientation, World::framePosition), while its
    /// RigidBody's position is its centre of mass. Children may overlap; they never
    /// collide with each other.
    static Shape compound(std::vector<CompoundChild> children);
    /// A height field for static bodies: `rows` x `columns` samples (each >= 2), sample
    /// (i, j) at (j spacing[0], heights[i columns + j], i spacing[1]) in the body's frame
    /// (spacings m, finite, > 0; heights m, finite, row by row). Each cell is two triangles
    /// split along its (i, j)-(i+1, j+1) diagonal; the solid lies below the surface, and
    /// shapes are pushed out upwards (the side the surface faces).
    static Shape heightfield(int rows, int columns, const std::array<real, 2> &spacing, std::vector<real> heights);
};

/// A child of a compound shape: a convex shape placed in the compound's frame.
struct CompoundChild {
    /// The child's shape: box, sphere, capsule, cylinder or convex.
    Shape shape;
    /// Where the child's origin lies in the compound's frame, m, finite.
    Vector3 position = Vector3::Zero();
    /// The child's orientation in the compound's frame, finite; normalised, (0,0,0,0)
    /// means identity.
    Quaternion orientation = Quaternion::Identity();
};

/// Name of a shape type as in scene files: "box", "sphere", ...
const char *shapeTypeName(ShapeType type);

}  // namespace cyclone
