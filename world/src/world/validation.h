// The World's own checks on top of the shared ones (cyclone/detail/validation.h).
#pragma once

#include <cmath>

#include "cyclone/detail/validation.h"
#include "cyclone/world/settings.h"

namespace cyclone::detail {

/// Coordinates beyond this are refused (and a body that flies beyond it is isolated), m:
/// cyclone::kMaxCoordinate says why.
inline constexpr real kMaxCoordinate = cyclone::kMaxCoordinate;

inline void requirePlace(const char *function, const char *field, const Vector3 &v) {
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxCoordinate)
        refuse(function, field, "must be finite and within 1e12 m of the origin, got " + show(v));
}

/// Refuses a body or query shape of bounding radius `radius` (m, from `centre`) that
/// reaches beyond kMaxCoordinate in some coordinate: where its far side lies is where its
/// contacts are computed, and beyond the range they are lost.
inline void requireReach(const char *function, const char *field, const Vector3 &centre, real radius) {
    const real reach = centre.cwiseAbs().maxCoeff() + radius;
    if (!(radius <= kMaxCoordinate && reach <= kMaxCoordinate))
        refuse(function, field,
               "puts part of the shape " + show(reach) + " m from the origin (its centre at " + show(centre) +
                   ", its farthest point " + show(radius) + " m from it); every point must be within 1e12 m");
}

/// A gravity scale: finite, and with `gravity` times it finite.
inline void requireGravityScale(const char *function, const char *field, real scale, const Vector3 &gravity) {
    if (!std::isfinite(scale) || !(gravity * scale).allFinite())
        refuse(function, field, "must be finite (and times the gravity too), got " + show(scale));
}

}  // namespace cyclone::detail
