#include "json_reading.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "scene_fields.h"
#include "scene_loader.h"

namespace cyclone::scene {

using nlohmann::json;

[[noreturn]] void fail(const std::string &path, const std::string &message) { throw SceneError(path, message); }

std::string formatNumber(double value) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char buffer[32];
    // The shortest text that reads back as the same double.
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
        if (std::strtod(buffer, nullptr) == value) break;
    }
    return buffer;
}

std::string describe(const json &value) {
    switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return value.dump();
    case json::value_t::number_float: return formatNumber(value.get<double>());
    case json::value_t::string: {
        const auto &text = value.get_ref<const std::string &>();
        constexpr std::size_t kShown = 40;
        return "string " + (text.size() > kShown ? jsonQuoted(text.substr(0, kShown)) + "..." : jsonQuoted(text));
    }
    case json::value_t::array: return "an array of " + std::to_string(value.size());
    case json::value_t::object: return "an object";
    default: return "a value of type " + std::string(value.type_name());
    }
}

const json *member(const json &object, const char *key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

const json &required(const json &object, const std::string &path, const char *key) {
    const json *value = member(object, key);
    if (value) return *value;
    // A misspelt required field is named where it stands, with the word that was meant.
    if (const std::string typed = misspellingOf(object, key); !typed.empty()) {
        fail(memberPath(path, typed), "unknown field; did you mean " + jsonQuoted(key) + "? (" + jsonQuoted(key) +
                                          " is required)");
    }
    fail(memberPath(path, key), "required field missing");
}

void expectObject(const json &value, const std::string &path) {
    if (!value.is_object()) fail(path, "must be an object, got " + describe(value));
}

void expectArray(const json &value, const std::string &path, std::size_t maxSize) {
    if (!value.is_array()) fail(path, "must be an array, got " + describe(value));
    if (value.size() > maxSize) {
        fail(path, "has " + std::to_string(value.size()) + " elements, at most " + std::to_string(maxSize) +
                       " are allowed");
    }
}

real readNumber(const json &value, const std::string &path, Range range) {
    if (!value.is_number()) fail(path, "must be a number, got " + describe(value));
    const real x = value.get<real>();
    switch (range) {
    case Range::Any:
        if (!std::isfinite(x)) fail(path, "must be finite, got " + describe(value));
        break;
    case Range::Positive:
        if (!(std::isfinite(x) && x > 0)) fail(path, "must be finite and > 0, got " + describe(value));
        break;
    case Range::NonNegative:
        if (!(std::isfinite(x) && x >= 0)) fail(path, "must be finite and >= 0, got " + describe(value));
        break;
    case Range::Unit:
        if (!(x >= 0 && x <= 1)) fail(path, "must be in [0, 1], got " + describe(value));
        break;
    case Range::Length:
        if (!(std::abs(x) <= kMaxCoordinate)) fail(path, "must be finite and within ±1e12 m, got " + describe(value));
        break;
    case Range::PositiveLength:
        if (!(x > 0 && x <= kMaxCoordinate)) fail(path, "must be finite and > 0 (at most 1e12 m), got " + describe(value));
        break;
    case Range::NonNegativeLength:
        if (!(x >= 0 && x <= kMaxCoordinate)) fail(path, "must be finite and >= 0 (at most 1e12 m), got " + describe(value));
        break;
    }
    return x;
}

std::int64_t readInteger(const json &value, const std::string &path, std::int64_t min, std::int64_t max) {
    if (!value.is_number()) fail(path, "must be an integer, got " + describe(value));
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    if (value.is_number_unsigned()) {
        const auto x = value.get<std::uint64_t>();
        if (x > static_cast<std::uint64_t>(max) || static_cast<std::int64_t>(x) < min) fail(path, "must be an integer in " + range + ", got " + describe(value));
        return static_cast<std::int64_t>(x);
    }
    if (value.is_number_integer()) {
        const auto x = value.get<std::int64_t>();
        if (x < min || x > max) fail(path, "must be an integer in " + range + ", got " + describe(value));
        return x;
    }
    const double x = value.get<double>();
    if (!std::isfinite(x) || x != std::floor(x)) fail(path, "must be an integer, got " + describe(value));
    if (x < static_cast<double>(min) || x > static_cast<double>(max)) {
        fail(path, "must be an integer in " + range + ", got " + describe(value));
    }
    return static_cast<std::int64_t>(x);
}

bool readBool(const json &value, const std::string &path) {
    if (!value.is_boolean()) fail(path, "must be true or false, got " + describe(value));
    return value.get<bool>();
}

const std::string &readString(const json &value, const std::string &path) {
    if (!value.is_string()) fail(path, "must be a string, got " + describe(value));
    return value.get_ref<const std::string &>();
}

Vector3 readVector3(const json &value, const std::string &path, Range range) {
    if (!value.is_array() || value.size() != 3) fail(path, "must be an array of 3 numbers, got " + describe(value));
    Vector3 v;
    for (int i = 0; i < 3; ++i) v[i] = readNumber(value[i], elementPath(path, i), range);
    return v;
}

Quaternion readOrientation(const json &value, const std::string &path) {
    if (!value.is_array() || value.size() != 4) {
        fail(path, "must be an array of 4 numbers [r, i, j, k], got " + describe(value));
    }
    real q[4];
    real largest = 0;
    for (int i = 0; i < 4; ++i) {
        q[i] = readNumber(value[i], elementPath(path, i));
        largest = std::max(largest, std::abs(q[i]));
    }
    if (largest == 0) return Quaternion::Identity();
    // Scaled first so that the norm of huge components does not overflow.
    Quaternion result(q[0] / largest, q[1] / largest, q[2] / largest, q[3] / largest);
    result.normalize();
    return result;
}

Matrix3 readInertia(const json &value, const std::string &path) {
    if (!value.is_array() || value.size() != 3) {
        fail(path, "must be 3 rows of 3 numbers, got " + describe(value));
    }
    Matrix3 inertia;
    for (int r = 0; r < 3; ++r) {
        const std::string rowPath = elementPath(path, r);
        const json &row = value[r];
        if (!row.is_array() || row.size() != 3) fail(rowPath, "must be a row of 3 numbers, got " + describe(row));
        for (int c = 0; c < 3; ++c) inertia(r, c) = readNumber(row[c], elementPath(rowPath, c));
    }
    const real scale = inertia.cwiseAbs().maxCoeff();
    if (!std::isfinite(scale) || scale == 0) fail(path, "must be symmetric positive definite, got all zeros");
    const Matrix3 unit = inertia / scale;
    if ((unit - unit.transpose()).cwiseAbs().maxCoeff() > 1e-9) fail(path, "must be symmetric");
    const Eigen::SelfAdjointEigenSolver<Matrix3> solver(unit, Eigen::EigenvaluesOnly);
    if (solver.info() != Eigen::Success || !(solver.eigenvalues().minCoeff() > 1e-12)) {
        fail(path, "must be positive definite");
    }
    return inertia;
}

std::vector<Vector3> readPoints(const json &value, const std::string &path, std::size_t minimum) {
    expectArray(value, path, kMaxShapePoints);
    if (value.size() < minimum) {
        fail(path, "needs at least " + std::to_string(minimum) + " points, got " + std::to_string(value.size()));
    }
    std::vector<Vector3> points;
    points.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) points.push_back(readVector3(value[i], elementPath(path, i), Range::Length));
    return points;
}

}  // namespace cyclone::scene
