// cyclone-scale: whether a pyramid of small or large boxes holds as well as one of unit
// boxes. Builds the benchmark's pyramid (boxes 1.05 edges apart horizontally, touching
// vertically, on a ground plane, sleep off) from boxes of each given edge length, steps it
// at 60 Hz and prints the top box's drift after the run, in millimetres and in percent of
// the edge, with the deepest contact of the last step. A tolerance that is an absolute
// length shows as a drift that grows, in edges, as the boxes shrink.
//
//   cyclone-scale [--edges 0.05,1,10] [--levels 10] [--seconds 10] [--hz 60]
//                 [--passes benchmark|defaults] [--threads T]
//
// --passes benchmark (the default) is the benchmark's 1 sub-step x 10 velocity passes;
// defaults is WorldSettings' 4 x 3. Every box has a mass of edge^3 kg (the unit box's
// density, 1 kg/m^3, whatever the size), so the scenes differ by their lengths only.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "cyclone/world.h"
#include "tool_main.h"

namespace cyclone::bench {
namespace {

constexpr const char *kTool = "cyclone-scale";

struct Options {
    std::vector<double> edges = {0.05, 1, 10};
    int levels = 10;
    double seconds = 10;
    double hz = 60;
    bool defaults = false;
    int threads = 1;
    int runs = 1;
};

struct Outcome {
    double drift = 0;    ///< The top box's displacement, m.
    double deepest = 0;  ///< Deepest contact of the last step, m.
};

Outcome runPyramid(const Options &options, double edge, int run) {
    WorldSettings settings;
    settings.sleep = false;
    settings.threads = options.threads;
    if (!options.defaults) {
        settings.substeps = 1;
        settings.velocityIterations = 10;
    }
    World world(settings);
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(ground);
    BodyId top{};
    for (int layer = 0; layer < options.levels; ++layer) {
        const int count = options.levels - layer;
        for (int i = 0; i < count; ++i) {
            BodySettings box;
            box.shape = Shape::box(Vector3::Constant(edge / 2));
            box.mass = edge * edge * edge;
            box.position = Vector3((i - (count - 1) / 2.0) * 1.05 * edge, (0.5 + layer) * edge, 0);
            if (run > 0) {
                const long k = layer * 100 + i;
                box.position.x() += static_cast<real>(((k * 7919 + run * 104729) % 13) - 6) * 1e-9 * edge;
            }
            top = world.addBody(box);
        }
    }
    const Vector3 start = world.body(top).getPosition();
    const int steps = static_cast<int>(std::lround(options.seconds * options.hz));
    for (int i = 0; i < steps; ++i) world.step(1 / options.hz);
    const Vector3 d = world.body(top).getPosition() - start;
    return {d.norm(), world.stats().maxPenetration};
}

std::vector<double> readList(const std::string &value) {
    std::vector<double> list;
    std::stringstream stream(value);
    std::string item;
    while (std::getline(stream, item, ','))
        if (!item.empty()) list.push_back(std::atof(item.c_str()));
    return list;
}

int run(int argc, char **argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        std::string arg, value;
        if (!readOption(kTool, argc, argv, i, arg, value)) return 2;
        if (arg == "--edges") {
            options.edges = readList(value);
        } else if (arg == "--levels") {
            options.levels = std::atoi(value.c_str());
        } else if (arg == "--seconds") {
            options.seconds = std::atof(value.c_str());
        } else if (arg == "--hz") {
            options.hz = std::atof(value.c_str());
        } else if (arg == "--passes" && (value == "benchmark" || value == "defaults")) {
            options.defaults = value == "defaults";
        } else if (arg == "--runs") {
            options.runs = std::atoi(value.c_str());
        } else if (arg == "--threads") {
            options.threads = std::atoi(value.c_str());
        } else {
            std::fprintf(stderr, "%s: unknown option %s %s\n", kTool, arg.c_str(), value.c_str());
            return 2;
        }
    }
    for (const double edge : options.edges) {
        if (!(edge > 0)) {
            std::fprintf(stderr, "%s: --edges: every edge must be > 0 m\n", kTool);
            return 2;
        }
    }
    if (options.edges.empty() || options.levels < 1 || !(options.seconds > 0) || !(options.hz > 0)) {
        std::fprintf(stderr, "%s: need --edges, --levels >= 1, --seconds > 0, --hz > 0\n", kTool);
        return 2;
    }
    std::printf("%d-level pyramids, %g s at %g Hz, %s passes, sleep off\n", options.levels, options.seconds, options.hz,
                options.defaults ? "default (4 x 3)" : "benchmark (1 x 10)");
    std::printf("%10s %14s %14s %16s\n", "edge (m)", "top drift (mm)", "% of an edge", "deepest (% edge)");
    for (const double edge : options.edges) {
        double worst = 0, sum = 0, deepest = 0;
        std::vector<double> runs;
        for (int r = 0; r < options.runs; ++r) {
            const Outcome o = runPyramid(options, edge, r);
            runs.push_back(100 * o.drift / edge);
            worst = std::max(worst, o.drift);
            sum += o.drift;
            deepest = std::max(deepest, o.deepest);
        }
        std::printf("%10g %14.4f %14.3f %16.4f", edge, worst * 1e3, 100 * worst / edge, 100 * deepest / edge);
        if (options.runs > 1) {
            std::printf("   mean %.3f %%, runs:", 100 * sum / options.runs / edge);
            for (double r : runs) std::printf(" %.2f", r);
        }
        std::printf("\n");
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace
}  // namespace cyclone::bench

int main(int argc, char **argv) { return cyclone::bench::guardedMain(cyclone::bench::kTool, cyclone::bench::run, argc, argv); }
