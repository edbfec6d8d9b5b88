// The masses and inertias a dynamic body may have: those the solver's arithmetic holds
// (the derivation is on kMinMass in cyclone/world/settings.h).
#pragma once

#include "cyclone/core.h"

namespace cyclone::detail {

/// Refuses (InvalidArgument from `function`, field "mass" or "inertia") a mass outside
/// [kMinMass, kMaxMass] or an inertia tensor whose principal moments over the squared
/// bounding radius fall outside that range. `inertia` is the tensor the body would get.
void requireSolvableMass(const char *function, real mass, const Matrix3 &inertia, real boundingRadius);

}  // namespace cyclone::detail
