// The contact test between two placed FCL geometries, as fcl::collide makes it, without
// allocating for a pair of solid shapes.
#pragma once

#include <fcl/fcl.h>

namespace cyclone::detail {

/// Tests `a` at `poseA` against `b` at `poseB` and adds their contacts to `result`, as
/// fcl::collide(a, poseA, b, poseB, request, result) does with the libccd solver (the
/// same routines, the same contacts, the same cap of request.num_max_contacts deepest
/// ones); returns the number of contacts in `result`. Pairs of shapes (box, sphere,
/// capsule, cylinder, convex, half-space) allocate nothing once `result` has held that
/// many contacts; a pair with a mesh goes through fcl::collide. Box against box still
/// allocates inside FCL: fcl::detail::boxBoxIntersect fills vectors of its own.
std::size_t collideShapes(const fcl::CollisionGeometryd *a, const fcl::Transform3d &poseA,
                          const fcl::CollisionGeometryd *b, const fcl::Transform3d &poseB,
                          const fcl::CollisionRequestd &request, fcl::CollisionResultd &result);

}  // namespace cyclone::detail
