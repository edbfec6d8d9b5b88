// Reading a scene file's JSON values: each reader checks the value's type and range and
// refuses a bad one with a SceneError naming its place (e.g. bodies[2].mass).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "json_document.h"
#include "scene.h"

namespace cyclone::scene {

[[noreturn]] void fail(const std::string &path, const std::string &message);

/// The shortest text that reads back as the same double ("nan", "inf" as such).
std::string formatNumber(double value);
/// What a wrong value is, for "must be X, got Y".
std::string describe(const nlohmann::json &value);

/// The member `key` of `object`, or null.
const nlohmann::json *member(const nlohmann::json &object, const char *key);
/// The member `key` of `object` at `path`; refuses a missing one, at the key of `object`
/// that looks like its misspelling when there is one.
const nlohmann::json &required(const nlohmann::json &object, const std::string &path, const char *key);
void expectObject(const nlohmann::json &value, const std::string &path);
void expectArray(const nlohmann::json &value, const std::string &path, std::size_t maxSize);

/// Ranges of numbers; the *Length ones are also within ±kMaxCoordinate.
enum class Range { Any, Positive, NonNegative, Unit, Length, PositiveLength, NonNegativeLength };

real readNumber(const nlohmann::json &value, const std::string &path, Range range = Range::Any);
std::int64_t readInteger(const nlohmann::json &value, const std::string &path, std::int64_t min, std::int64_t max);
bool readBool(const nlohmann::json &value, const std::string &path);
const std::string &readString(const nlohmann::json &value, const std::string &path);
Vector3 readVector3(const nlohmann::json &value, const std::string &path, Range range = Range::Any);
/// [r, i, j, k], normalised; all zeros is the identity.
Quaternion readOrientation(const nlohmann::json &value, const std::string &path);
/// 3 rows of 3 numbers, symmetric positive definite.
Matrix3 readInertia(const nlohmann::json &value, const std::string &path);
/// At least `minimum` points, each within ±kMaxCoordinate.
std::vector<Vector3> readPoints(const nlohmann::json &value, const std::string &path, std::size_t minimum);

/// Every optional field: read it with `read` when present, else keep the default.
template <typename T, typename Read>
void readOptional(const nlohmann::json &object, const std::string &path, const char *key, T &target, Read read) {
    if (const nlohmann::json *value = member(object, key)) target = read(*value, memberPath(path, key));
}

}  // namespace cyclone::scene
