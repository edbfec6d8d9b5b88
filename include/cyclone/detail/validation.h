/// \file
/// Refusing bad input, shared by the dynamics core and the World (not part of the API):
/// every refusal throws cyclone::InvalidArgument naming the function, the field and the
/// value, before anything changes.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "cyclone/core.h"
#include "cyclone/error.h"

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

/// A matrix row by row: [a, b, c; d, e, f; g, h, i].
inline std::string show(const Matrix3 &m) {
    std::string text = "[";
    for (int row = 0; row < 3; ++row)
        text += show(m(row, 0)) + ", " + show(m(row, 1)) + ", " + show(m(row, 2)) + (row < 2 ? "; " : "]");
    return text;
}

[[noreturn]] inline void refuse(const std::string &function, const std::string &field, const std::string &problem) {
    throw InvalidArgument(function, field, problem);
}

inline void requireFinite(const char *function, const char *field, real value) {
    if (!std::isfinite(value)) refuse(function, field, "must be finite, got " + show(value));
}

inline void requireFinite(const char *function, const char *field, const Vector3 &v) {
    if (!v.allFinite()) refuse(function, field, "must be finite, got " + show(v));
}

inline void requireFinite(const char *function, const char *field, const Quaternion &q) {
    if (!q.coeffs().allFinite()) refuse(function, field, "must be finite, got " + show(q));
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

/// An inertia tensor or its inverse: finite, symmetric (to 1e-9 of its largest entry) and
/// positive definite.
inline void requireSymmetricPositiveDefinite(const char *function, const char *field, const Matrix3 &m) {
    if (!m.allFinite()) refuse(function, field, "must be finite, got " + show(m));
    const real scale = m.cwiseAbs().maxCoeff();
    if ((m - m.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
        refuse(function, field, "must be symmetric, got " + show(m));
    const Eigen::LDLT<Matrix3> ldlt(m);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().minCoeff() > 0))
        refuse(function, field, "must be positive definite, got " + show(m));
}

}  // namespace cyclone::detail
