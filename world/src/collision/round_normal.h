// The normal of least overlap of two round shapes (spheres, capsules, cylinders) by
// Newton's method on their support functions, which are closed forms: a cylinder's rim
// is a smooth part of it where GJK's refinement creeps (contact_normal.cpp).
#pragma once

#include "collision/contact_building.h"

namespace cyclone::detail {

/// Whether roundNormal takes shapes of these types: each a sphere, a capsule or a
/// cylinder, at least one a cylinder (the others have closed-form pairs).
bool roundNormalPair(ShapeType a, ShapeType b);

/// Descends from `normal` (unit, A to B; `overlap` along it) to the nearest normal of
/// least overlap of the pair's shapes, which roundNormalPair must take, and leaves it and
/// its overlap there (unchanged when no step lowers the overlap). Returns false when the
/// descent did not settle within its steps (118 of 75,034 descents in mixed1000's first
/// 300 steps): the caller goes on from there another way.
bool roundNormal(const Pair &pair, Vector3 &normal, real &overlap);

}  // namespace cyclone::detail
