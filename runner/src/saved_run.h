// A run's saved state (--save-state, --load-state): the steps taken and the World's
// state (World::saveState), tied to the scene text it was run from.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cyclone/world.h"

namespace cyclone::scene {

/// A saved run that cannot be resumed here; what() is the problem, for one line.
class SavedRunError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The bytes of a run of the scene `sceneText` after `stepsDone` steps.
std::vector<std::uint8_t> savedRunBytes(const std::string &sceneText, std::int64_t stepsDone, const World &world);

/// Puts `world` (built from `sceneText`) in the saved run's state and returns the steps
/// it had taken. Throws SavedRunError, `world` unchanged, on a damaged file or one saved
/// from another scene.
std::int64_t resumeSavedRun(const std::vector<std::uint8_t> &bytes, const std::string &sceneText, World &world);

/// Reads a whole file as bytes; throws SavedRunError ("cannot read: ...").
std::vector<std::uint8_t> readSavedRun(const std::string &path);

}  // namespace cyclone::scene
