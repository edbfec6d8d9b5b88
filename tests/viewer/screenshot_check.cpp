// Runs cyclone-viewer headless under xvfb-run on the 20-level pyramid and checks its
// screenshot: a picture of at least 640x480, not blank, with the pyramid's boxes where the
// scene puts them (their centres, projected with the viewer's own camera, show the awake
// colour), sky above the apex and ground in front of it.
//
//   screenshot_check VIEWER SCENE.json OUT.png
//
// Exit status: 0 passed, 1 failed, 77 skipped (no xvfb-run: no display server to be had).
#include <stb_image.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "camera.h"
#include "meshes.h"
#include "palette.h"
#include "session.h"

namespace {

constexpr int kSkip = 77;
constexpr int kFrames = 90;

int failures = 0;

void check(bool ok, const std::string &what) {
    if (!ok) {
        std::fprintf(stderr, "FAILED: %s\n", what.c_str());
        ++failures;
    }
}

bool onPath(const std::string &program) {
    const char *path = std::getenv("PATH");
    std::string dirs = path != nullptr ? path : "";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::string candidate = dirs.substr(start, end - start) + "/" + program;
        if (end > start && access(candidate.c_str(), X_OK) == 0) return true;
        start = end + 1;
    }
    return false;
}

// Runs argv; returns its exit status (-1 when it did not exit normally).
int runProgram(std::vector<std::string> args) {
    std::vector<char *> argv;
    for (std::string &arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    const pid_t child = fork();
    if (child == 0) {
        execvp(argv[0], argv.data());
        std::perror("execvp");
        _exit(127);
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) != child) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Pixel {
    int r = 0, g = 0, b = 0;
};

struct Image {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    Pixel at(int x, int y) const {
        const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
        return Pixel{rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

std::string describe(const Pixel &p) {
    return "(" + std::to_string(p.r) + ", " + std::to_string(p.g) + ", " + std::to_string(p.b) + ")";
}

bool isSky(const Pixel &p) {
    using cyclone::viewer::kSkyColor;
    const auto near = [](int value, float channel) { return std::abs(value - static_cast<int>(std::lround(channel * 255))) <= 3; };
    return near(p.r, kSkyColor.r) && near(p.g, kSkyColor.g) && near(p.b, kSkyColor.b);
}

// The awake colour lit by any light keeps its hue: red above green well above blue.
bool looksAwake(const Pixel &p) { return p.r > p.g && p.g > p.b && p.r - p.b > 60; }

// The ground, lit from above: light grey, red no less than blue (the sky is bluer).
bool looksLikeGround(const Pixel &p) { return !isSky(p) && p.r >= p.b && p.r > 120 && std::abs(p.r - p.g) < 25; }

}  // namespace

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: screenshot_check VIEWER SCENE.json OUT.png\n");
        return 2;
    }
    const std::string viewer = argv[1], scenePath = argv[2], out = argv[3];
    if (!onPath("xvfb-run")) {
        std::printf("SKIPPED: xvfb-run is not installed (Debian package xvfb), so no display server can be had "
                    "for the viewer\n");
        return kSkip;
    }
    std::remove(out.c_str());
    // Under AddressSanitizer, LeakSanitizer reports a few small allocations (240 bytes in 3
    // seen) made by the OpenGL libraries, which are loaded at run time (dlopen) and unloaded
    // before the leak check: their stacks end in "<unknown module>", where the viewer's own
    // code would be named. Leak detection is off for the viewer process only;
    // AddressSanitizer's other checks stay on, and viewer_tests leak-check the session and
    // the camera.
    const char *asan = std::getenv("ASAN_OPTIONS");
    const std::string viewerAsan = std::string(asan != nullptr ? asan : "") + (asan != nullptr && *asan ? ":" : "") + "detect_leaks=0";
    setenv("ASAN_OPTIONS", viewerAsan.c_str(), 1);
    const int status = runProgram({"xvfb-run", "-a", "-s", "-screen 0 1280x720x24", viewer, scenePath, "--frames",
                                   std::to_string(kFrames), "--screenshot", out});
    if (asan != nullptr) {
        setenv("ASAN_OPTIONS", asan, 1);
    } else {
        unsetenv("ASAN_OPTIONS");
    }
    check(status == 0, "the viewer exits with status 0 (got " + std::to_string(status) + ")");

    Image image;
    int channels = 0;
    unsigned char *data = stbi_load(out.c_str(), &image.width, &image.height, &channels, 3);
    check(data != nullptr, "the screenshot " + out + " can be read as a PNG");
    if (data == nullptr) return 1;
    image.rgb.assign(data, data + static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
    stbi_image_free(data);
    check(image.width >= 640 && image.height >= 480,
          "the picture is at least 640x480 (got " + std::to_string(image.width) + "x" + std::to_string(image.height) + ")");

    // Not blank: sky, ground, lit faces at several angles, grid lines, overlay text.
    std::set<int> colours;
    for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
        colours.insert((image.rgb[i] >> 4) << 8 | (image.rgb[i + 1] >> 4) << 4 | (image.rgb[i + 2] >> 4));
    }
    check(colours.size() >= 12, "the picture has many colours (got " + std::to_string(colours.size()) +
                                    " distinct ones at 4 bits a channel)");

    // The viewer's first view frames the scene as loaded; the resting pyramid stays put.
    cyclone::viewer::Session session(scenePath);
    const cyclone::World &world = session.world();
    cyclone::viewer::OrbitCamera camera;
    camera.frame(cyclone::viewer::sceneBounds(world),
                 static_cast<float>(image.width) / static_cast<float>(image.height));
    const auto pixelAt = [&](const Eigen::Vector3f &point, Pixel &pixel) {
        const std::optional<Eigen::Vector2f> p = camera.project(point, image.width, image.height);
        if (!p || !(p->x() >= 0 && p->y() >= 0 && p->x() < static_cast<float>(image.width) &&
                    p->y() < static_cast<float>(image.height))) {
            return false;
        }
        pixel = image.at(static_cast<int>(p->x()), static_cast<int>(p->y()));
        return true;
    };

    for (const char *name : {"r0b0", "r0b19", "r5b7", "r10b4", "r15b2", "r19b0"}) {
        const std::optional<cyclone::BodyId> id = world.findBody(name);
        check(id.has_value(), std::string("the scene has a body ") + name);
        if (!id) continue;
        Pixel pixel;
        const bool inView = pixelAt(world.body(*id).getPosition().cast<float>(), pixel);
        check(inView, std::string("box ") + name + " is in view");
        if (inView) {
            check(looksAwake(pixel), std::string("the centre of box ") + name + " shows an awake box (got " +
                                         describe(pixel) + ")");
        }
    }
    Pixel above, ground;
    const bool aboveInView = pixelAt(Eigen::Vector3f(0, 22, 0), above);
    check(aboveInView, "the point 2 m above the apex is in view");
    if (aboveInView) check(isSky(above), "above the apex is sky (got " + describe(above) + ")");
    const bool groundInView = pixelAt(Eigen::Vector3f(0.5f, 0, 2.5f), ground);
    check(groundInView, "the ground 2.5 m in front of the pyramid is in view");
    if (groundInView) check(looksLikeGround(ground), "in front of the pyramid is the ground (got " + describe(ground) + ")");

    if (failures > 0) {
        std::fprintf(stderr, "%d check(s) failed; the screenshot is %s\n", failures, out.c_str());
        return 1;
    }
    std::printf("passed: %dx%d screenshot of %s, %zu colours\n", image.width, image.height, scenePath.c_str(),
                colours.size());
    return 0;
}
