// Convex hull of a point cloud (Qhull), with coplanar facets merged into polygon faces.
#pragma once

#include <vector>

#include "cyclone/core.h"

namespace cyclone::detail {

/// A closed convex polyhedron.
struct ConvexHull {
    /// Hull vertices (the input points that are corners of the hull), m.
    std::vector<Vector3> vertices;
    /// Faces as loops of indices into `vertices`, counter-clockwise seen from outside.
    std::vector<std::vector<int>> faces;
    /// Outward unit normal of each face.
    std::vector<Vector3> normals;
};

/// Computes the hull of `points` into `hull`. Returns false (hull empty) when the points
/// span no volume: fewer than 4, or all (nearly) coplanar, relative to their extent.
bool computeConvexHull(const std::vector<Vector3> &points, ConvexHull &hull);

/// Farthest-point sampling: `count` of `points` (all when there are no more), the first
/// the one farthest from their centroid, each next the one farthest from those already
/// chosen (ties: the lowest index). `cover` gets the largest distance from any point to
/// its nearest chosen one; the chosen points are pairwise at least `cover` apart, so no
/// choice of `count` points covers them within less than cover / 2. O(points x count).
std::vector<Vector3> spreadSubset(const std::vector<Vector3> &points, int count, real &cover);

/// Volume (m^3), centroid (m) and inertia tensor of a unit-mass, uniform-density
/// polyhedron about the frame origin (kg m^2), by decomposition into tetrahedra with
/// apex at the origin. Faces must be counter-clockwise seen from outside.
void polyhedronMassProperties(const std::vector<Vector3> &vertices, const std::vector<std::vector<int>> &faces,
                              real &volume, Matrix3 &unitInertia, Vector3 &centroid);

}  // namespace cyclone::detail
