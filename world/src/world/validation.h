// Refusing bad input with a message that names the function, the field and the value.
#pragma once

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "cyclone/core.h"
#include "cyclone/world/error.h"

namespace cyclone::detail {

/// The shortest text that reads back as the same double (1e+300, not 1.0000000000000001e+300).
inline std::string show(real value) {
    std::ostringstream out;
    for (int precision = 1; precision <= 17; ++precision) {
        out.str("");
        out.precision(precision);
        out << value;
        if (!std::isfinite(value) || std::strtod(out.str().c_str(), nullptr) == value) break;
    }
    return out.str();
}

inline std::string show(const Vector3 &v) { return "[" + show(v.x()) + ", " + show(v.y()) + ", " + show(v.z()) + "]"; }

/// A quaternion as [w, x, y, z], the order of scene files.
inline std::string show(const Quaternion &q) {
    return "[" + show(q.w()) + ", " + show(q.x()) + ", " + show(q.y()) + ", " + show(q.z()) + "]";
}

/// Coordinates beyond this are refused (and a body that flies beyond it is isolated):
/// FCL's AABB tree fails on such numbers, m.
inline constexpr real kMaxCoordinate = 1e30;

[[noreturn]] inline void refuse(const std::string &function, const std::string &field, const std::string &problem) {
    throw InvalidArgument(function, field, problem);
}

inline void requireFinite(const char *function, const char *field, const Vector3 &v) {
    if (!v.allFinite()) refuse(function, field, "must be finite, got " + show(v));
}

inline void requireFinite(const char *function, const char *field, const Quaternion &q) {
    if (!q.coeffs().allFinite()) refuse(function, field, "must be finite, got " + show(q));
}

inline void requirePlace(const char *function, const char *field, const Vector3 &v) {
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxCoordinate)
        refuse(function, field, "must be finite and within 1e30 m of the origin, got " + show(v));
}

inline void requirePositive(const char *function, const char *field, real value) {
    if (!std::isfinite(value) || !(value > 0)) refuse(function, field, "must be finite and > 0, got " + show(value));
}

inline void requireNonNegative(const char *function, const char *field, real value) {
    if (!std::isfinite(value) || !(value >= 0)) refuse(function, field, "must be finite and >= 0, got " + show(value));
}

inline void requireUnit(const char *function, const char *field, real value) {
    if (!(value >= 0 && value <= 1)) refuse(function, field, "must be in [0, 1], got " + show(value));
}

}  // namespace cyclone::detail
