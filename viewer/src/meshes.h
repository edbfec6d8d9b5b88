// Shapes as triangles for the renderer: every collision shape in its body's frame, with
// the normals a lit picture needs, and the world-space bounds used to frame a scene.
#pragma once

#include <cstdint>
#include <vector>

#include "camera.h"
#include "cyclone/world.h"

namespace cyclone::viewer {

/// A vertex of a lit mesh: position (m, in the body's frame) and unit normal.
struct MeshVertex {
    float position[3];
    float normal[3];
};

/// Indexed triangles, counter-clockwise seen from outside.
struct TriangleMesh {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;
};

/// Segments of a full circle of round shapes (spheres, capsules, cylinders), in [8, 128].
inline constexpr int kRoundSegments = 32;

/// Half size of the square drawn for a plane, m, and the spacing of its grid lines, m.
inline constexpr float kPlaneHalfSize = 60.0f;
inline constexpr float kGridSpacing = 1.0f;

/// The triangles of `shape` in its body's frame. A plane becomes a square of half size
/// kPlaneHalfSize around the point of its surface nearest the body's origin; a convex
/// shape becomes its hull (empty if the points span no volume, which the World refuses);
/// a compound, its children, moved so that `origin` (its centre of mass in its frame,
/// World::localCentreOfMass) is the body's origin.
TriangleMesh shapeMesh(const Shape &shape, const Vector3 &origin = Vector3::Zero());

/// A plane shape's surface point nearest its body's origin and two unit tangents, in the
/// body's frame (the axes of shapeMesh()'s square and of its grid).
struct PlaneAxes {
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    Eigen::Vector3f u = Eigen::Vector3f::UnitX();
    Eigen::Vector3f v = Eigen::Vector3f::UnitZ();
};
PlaneAxes planeAxes(const Shape &shape);

/// World-space bounds of a body's shape at its current pose; empty for a plane (it is
/// unbounded).
Bounds bodyBounds(const World &world, BodyId id);

/// What "frame the scene" shows: the bounds of the dynamic bodies, or of every body but
/// the planes when none is dynamic (the ground and walls of a scene can be much larger
/// than what moves on them).
Bounds sceneBounds(const World &world);

}  // namespace cyclone::viewer
