// The contact test and the distance between two placed FCL geometries, as fcl::collide
// and fcl::distance find them, without allocating for a pair of solid shapes.
#pragma once

#include <fcl/fcl.h>

namespace cyclone::detail {

/// Tests `a` at `poseA` against `b` at `poseB` and adds their contacts to `result`, as
/// fcl::collide(a, poseA, b, poseB, request, result) does with the libccd solver (the
/// same routines, the same contacts, the same cap of request.num_max_contacts deepest
/// ones; a request without contacts gets FCL's yes-or-no test and one contact without a
/// point); returns the number of contacts in `result`. Pairs of shapes (box, sphere,
/// capsule, cylinder, convex, half-space) allocate nothing once `result` has held that
/// many contacts; a pair with a mesh goes through fcl::collide. Box against box still
/// allocates inside FCL: fcl::detail::boxBoxIntersect fills vectors of its own.
std::size_t collideShapes(const fcl::CollisionGeometryd *a, const fcl::Transform3d &poseA,
                          const fcl::CollisionGeometryd *b, const fcl::Transform3d &poseB,
                          const fcl::CollisionRequestd &request, fcl::CollisionResultd &result);

/// fcl::distance(a, poseA, b, poseB, request, result) with the libccd solver: the same
/// routines (GJKDistance, or the solver's own for sphere and capsule pairs), the same
/// distance and nearest points in `result`; returns the distance. Pairs of solid shapes
/// (box, sphere, capsule, cylinder, convex) allocate nothing (a hull's support as in
/// collideShapes); anything else, or a signed-distance request, goes through
/// fcl::distance.
double distanceShapes(const fcl::CollisionGeometryd *a, const fcl::Transform3d &poseA,
                      const fcl::CollisionGeometryd *b, const fcl::Transform3d &poseB,
                      const fcl::DistanceRequestd &request, fcl::DistanceResultd &result);

/// Whether `shape` (a box, sphere, capsule, cylinder or convex) at `pose` overlaps the
/// triangle `p` (corners in the frame `trianglePose` places), by the libccd solver's
/// shapeTriangleIntersect: the routine fcl::collide runs for each triangle of a mesh it
/// tests against a shape. When it does: FCL's unit normal from the shape towards the
/// triangle and its depth. False for any other geometry.
bool shapeTriangleContact(const fcl::CollisionGeometryd *shape, const fcl::Transform3d &pose,
                          const fcl::Vector3d (&p)[3], const fcl::Transform3d &trianglePose, fcl::Vector3d &normal,
                          double &depth);

}  // namespace cyclone::detail
