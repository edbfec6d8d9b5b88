// The fields of the scene-format contract (its second version included), place by place,
// and the warnings for fields a scene has that the contract has not: usually typos, which
// would otherwise leave the default in place without a word.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "scene.h"

namespace cyclone::scene {

/// Most warnings the runner prints for one scene; the rest are counted in one more line.
inline constexpr std::size_t kMaxWarningsShown = 50;

/// One warning per field of `document` that the contract does not have at its place (top
/// level, settings, bodies, springs, joints, events; within each object in key order),
/// with the nearest known name when one is close ("did you mean ..."). `document` is a
/// scene that loadSceneDocument accepted.
std::vector<SceneWarning> unknownFields(const nlohmann::json &document);

/// Edit distance between `a` and `b`: insertions, deletions, substitutions and swaps of
/// two neighbouring characters ("frictoin" is 1 from "friction").
std::size_t editDistance(const std::string &a, const std::string &b);

/// The name of `known` nearest to `typed` (case aside), when it is near enough to be what
/// was meant: within one edit for names up to 4 characters, two up to 8, three beyond;
/// else "".
std::string nearestName(const std::string &typed, const std::vector<std::string> &known);

/// "; did you mean \"box\"?" when a name of `known` is near `typed`, else "".
std::string didYouMean(const std::string &typed, const std::vector<std::string> &known);

/// The member of `object` that is likely a misspelling of the missing field `key`
/// ("halfextents" for "half_extents", "bodys" for "bodies"): a key near `key` that is no
/// field of the format anywhere; else "".
std::string misspellingOf(const nlohmann::json &object, const std::string &key);

}  // namespace cyclone::scene
