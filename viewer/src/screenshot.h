// The picture drawn, saved as a PNG.
#pragma once

#include <string>

namespace cyclone::viewer {

/// Reads the width x height picture just drawn (the back buffer, before it is shown) and
/// writes it to `path` as an RGB PNG, whole or not at all (a temporary file renamed).
/// Throws std::runtime_error naming the file when it cannot.
void writeScreenshot(const std::string &path, int width, int height);

}  // namespace cyclone::viewer
