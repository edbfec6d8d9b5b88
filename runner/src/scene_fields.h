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

}  // namespace cyclone::scene
