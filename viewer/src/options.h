// The viewer's command line.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>

namespace cyclone::viewer {

/// What the command line asks for.
struct Options {
    /// The scene file to open.
    std::string scene;
    /// Headless run: this many frames (each one 1/60 s of simulated time, whatever the
    /// clock), then exit; none: interactive until the window closes.
    std::optional<int> frames;
    /// Where to write a PNG of the last frame (with `frames`).
    std::string screenshot;
    /// Window size in pixels, at least 640 x 480.
    int width = 1280;
    int height = 720;
    /// Print the mean frame time of the run (with `frames`).
    bool benchmark = false;
    /// Hide the overlay (windows, plots).
    bool hideUi = false;
    /// Start with the contact points and normals drawn.
    bool contacts = false;
    /// Follow this body (by its name in the scene) instead of all the moving ones.
    std::string follow;
    /// A fixed camera: the eye and the point looked at, m (no follow mode).
    std::optional<Eigen::Vector3f> cameraEye;
    Eigen::Vector3f cameraTarget = Eigen::Vector3f::Zero();
    /// Refuse a scene with a field the format has not, as cyclone-world --strict does.
    bool strict = false;
};

/// The usage text.
const char *usage();

/// Parses argv; returns none and writes a message to `error` when it cannot ("" for
/// --help, which the caller answers with usage()).
std::optional<Options> parseOptions(int argc, char **argv, std::string &error);

}  // namespace cyclone::viewer
