// The masses and inertias a dynamic body may have: those the solver's arithmetic holds
// (the derivation is on kMinMass in cyclone/world/settings.h).
#pragma once

#include "cyclone/core.h"

namespace cyclone::detail {

/// Refuses (InvalidArgument from `function`, field "mass" or "inertia") a mass outside
/// [kMinMass, kMaxMass] or an inertia tensor whose principal moments over the squared
/// bounding radius fall outside that range. `inertia` is the tensor the body would get.
void requireSolvableMass(const char *function, real mass, const Matrix3 &inertia, real boundingRadius);

/// Smallest fraction of the inertia a solid shape of uniform density would have that an
/// explicit inertia may have along any axis (docs/hostile_input.md measures the range).
inline constexpr real kMinInertiaFraction = 0.01;

/// Refuses (InvalidArgument from `function`, field "inertia") an explicit inertia tensor
/// with a moment about some axis below kMinInertiaFraction times that of `shapeInertia`
/// (the shape's tensor at uniform density for the body's mass) about the same axis.
void requireInertiaNearShape(const char *function, const Matrix3 &inertia, const Matrix3 &shapeInertia);

/// Smallest principal moment of inertia a shape-derived tensor keeps, as a fraction of its
/// largest: below it the contact solve of a thin rod or needle gains energy without bound
/// (docs/hostile_input.md, "Thin bodies").
inline constexpr real kMinMomentRatio = 1e-3;

/// `inertia` (symmetric, positive definite) with every principal moment raised to at least
/// kMinMomentRatio times the largest, about the same principal axes; `inertia` itself,
/// bit for bit, when no moment is below.
Matrix3 withMomentFloor(const Matrix3 &inertia);

}  // namespace cyclone::detail
