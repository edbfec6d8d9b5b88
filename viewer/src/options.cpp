#include "options.h"

#include <cstdlib>
#include <cstring>

namespace cyclone::viewer {

namespace {

constexpr int kMaxFrames = 1000000;
constexpr int kMaxSize = 16384;

bool parseInt(const char *text, int lo, int hi, int &out) {
    char *end = nullptr;
    const long value = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || value < lo || value > hi) return false;
    out = static_cast<int>(value);
    return true;
}

}  // namespace

const char *usage() {
    return "usage: cyclone-viewer SCENE.json [--frames N [--screenshot OUT.png] [--benchmark]]\n"
           "                      [--size WxH] [--no-ui] [--contacts]\n"
           "\n"
           "  --frames N         run N frames (1/60 s of simulation each), then exit\n"
           "  --screenshot FILE  write the last frame as a PNG (needs --frames)\n"
           "  --benchmark        print the mean frame time of the run (needs --frames)\n"
           "  --size WxH         window size in pixels, at least 640x480 (default 1280x720)\n"
           "  --no-ui            hide the overlay\n"
           "  --contacts         start with contact points and normals drawn\n"
           "\n"
           "Mouse: left drag on a body pulls it with a spring, elsewhere orbits; right or\n"
           "middle drag pans; wheel zooms. Keys: Space pause, N one step, R restart,\n"
           "S slow motion, F frame the scene, B shoot a ball, F5 keep the state, F9 rewind\n"
           "to it, Esc quit.\n";
}

std::optional<Options> parseOptions(int argc, char **argv, std::string &error) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const bool hasValue = i + 1 < argc;
        if (std::strcmp(arg, "-h") == 0 || std::strcmp(arg, "--help") == 0) {
            error.clear();
            return std::nullopt;
        } else if (std::strcmp(arg, "--frames") == 0) {
            int frames = 0;
            if (!hasValue || !parseInt(argv[++i], 1, kMaxFrames, frames)) {
                error = "--frames needs a number of frames in [1, 1000000]";
                return std::nullopt;
            }
            options.frames = frames;
        } else if (std::strcmp(arg, "--screenshot") == 0) {
            if (!hasValue) {
                error = "--screenshot needs a file name";
                return std::nullopt;
            }
            options.screenshot = argv[++i];
        } else if (std::strcmp(arg, "--size") == 0) {
            const char *x = hasValue ? std::strchr(argv[i + 1], 'x') : nullptr;
            const std::string text = hasValue ? argv[++i] : "";
            if (x == nullptr || !parseInt(text.substr(0, text.find('x')).c_str(), 640, kMaxSize, options.width) ||
                !parseInt(x + 1, 480, kMaxSize, options.height)) {
                error = "--size needs WIDTHxHEIGHT, at least 640x480";
                return std::nullopt;
            }
        } else if (std::strcmp(arg, "--benchmark") == 0) {
            options.benchmark = true;
        } else if (std::strcmp(arg, "--no-ui") == 0) {
            options.hideUi = true;
        } else if (std::strcmp(arg, "--contacts") == 0) {
            options.contacts = true;
        } else if (arg[0] == '-' && arg[1] != '\0') {
            error = std::string("unknown option ") + arg;
            return std::nullopt;
        } else if (options.scene.empty()) {
            options.scene = arg;
        } else {
            error = std::string("one scene file only (got ") + options.scene + " and " + arg + ")";
            return std::nullopt;
        }
    }
    if (options.scene.empty()) {
        error = "no scene file given";
        return std::nullopt;
    }
    if (!options.frames && (!options.screenshot.empty() || options.benchmark)) {
        error = "--screenshot and --benchmark need --frames N";
        return std::nullopt;
    }
    return options;
}

}  // namespace cyclone::viewer
