#include "options.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace cyclone::viewer {

namespace {

constexpr int kMaxFrames = 1000000;
constexpr int kMaxSize = 16384;

// "EX,EY,EZ,TX,TY,TZ": six finite numbers.
bool parseCamera(const char *text, Eigen::Vector3f &eye, Eigen::Vector3f &target) {
    float values[6];
    const char *at = text;
    for (int i = 0; i < 6; ++i) {
        char *end = nullptr;
        values[i] = std::strtof(at, &end);
        if (end == at || !std::isfinite(values[i]) || *end != (i < 5 ? ',' : '\0')) return false;
        at = end + 1;
    }
    eye = Eigen::Vector3f(values[0], values[1], values[2]);
    target = Eigen::Vector3f(values[3], values[4], values[5]);
    return eye != target;
}

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
           "                      [--size WxH] [--no-ui] [--contacts] [--strict]\n"
           "                      [--follow NAME | --camera EX,EY,EZ,TX,TY,TZ]\n"
           "\n"
           "  --frames N         run N frames (1/60 s of simulation each), then exit\n"
           "  --screenshot FILE  write the last frame as a PNG (needs --frames)\n"
           "  --benchmark        print the mean frame time of the run (needs --frames)\n"
           "  --size WxH         window size in pixels, at least 640x480 (default 1280x720)\n"
           "  --no-ui            hide the overlay\n"
           "  --contacts         start with contact points and normals drawn\n"
           "  --follow NAME      keep the body NAME in view (default: every moving body)\n"
           "  --camera E,T       a fixed camera: eye at E = EX,EY,EZ looking at T = TX,TY,TZ (m)\n"
           "  --strict           refuse a scene with a field the format has not (as cyclone-world)\n"
           "\n"
           "Mouse: left drag on a body pulls it with a spring, elsewhere orbits; right or\n"
           "middle drag pans; wheel zooms. Keys: Space pause, N one step, R restart,\n"
           "S slow motion, F frame and follow the moving bodies again (moving the camera\n"
           "stops following), B shoot a ball, F5 keep the state, F9 rewind to it, Esc quit.\n";
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
        } else if (std::strcmp(arg, "--strict") == 0) {
            options.strict = true;
        } else if (std::strcmp(arg, "--follow") == 0) {
            if (!hasValue || argv[i + 1][0] == '\0') {
                error = "--follow needs a body's name";
                return std::nullopt;
            }
            options.follow = argv[++i];
        } else if (std::strcmp(arg, "--camera") == 0) {
            Eigen::Vector3f eye, target;
            if (!hasValue || !parseCamera(argv[++i], eye, target)) {
                error = "--camera needs EX,EY,EZ,TX,TY,TZ: six numbers, the eye and the point looked at (m), apart";
                return std::nullopt;
            }
            options.cameraEye = eye;
            options.cameraTarget = target;
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
    if (options.cameraEye && !options.follow.empty()) {
        error = "--camera and --follow exclude each other (a fixed camera follows nothing)";
        return std::nullopt;
    }
    if (!options.frames && (!options.screenshot.empty() || options.benchmark)) {
        error = "--screenshot and --benchmark need --frames N";
        return std::nullopt;
    }
    return options;
}

}  // namespace cyclone::viewer
