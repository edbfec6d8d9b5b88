// cyclone-stages: where a step's time goes. Steps each benchmark scene in cyclone's World
// and prints the median milliseconds of every stage (StepStats::ms) and of the solve
// stage's parts (StageTimes::solveParts), over the steps after the first second.
//
//   cyclone-stages [--scene NAME[,NAME...]] [--steps N] [--threads T] [--defaults]
//                  [--substeps S] [--iterations N] [--positions N] [--landing on|off]
//                  [--carrier on|off] [--holding on|off] [--unchanged on|off] [--slowest K]
// --defaults steps the scenes at WorldSettings' default sub-steps and passes instead of the
// benchmark's 1 x 10; --substeps, --iterations and --positions then set each one.
// --landing off steps them without the landing correction (DebugSettings::landingCorrection),
// --carrier off without the carrier pass (DebugSettings::carrierPass), --holding off
// solving every awake body (DebugSettings::holding), --unchanged off testing every pair
// (DebugSettings::unchangedPairs).
// --slowest K prints, instead of the medians, each stage's mean over the K slowest steps
// after the first second (by total): the steps that make a benchmark's p95 (the 30
// slowest of its 600 steps).
// `shared` is StageTimes::shared (on one thread, the work two threads would share) and
// `serial` the rest of the step. The last column counts the steps (of all, the first
// second included) that took fewer sub-steps than the settings' (resting steps,
// StepStats::substeps).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>
#include <vector>

#include "cyclone/world/world.h"
#include "scenes.h"
#include "tool_main.h"
#include "statistics.h"

namespace {

using namespace cyclone;

struct Column {
    const char *name;
    double (*read)(const StageTimes &);
};

const Column kColumns[] = {
    {"total", [](const StageTimes &t) { return t.total; }},
    {"forces", [](const StageTimes &t) { return t.forces; }},
    {"broadphase", [](const StageTimes &t) { return t.broadphase; }},
    {"narrowphase", [](const StageTimes &t) { return t.narrowphase; }},
    {"events", [](const StageTimes &t) { return t.events; }},
    {"manifolds", [](const StageTimes &t) { return t.manifolds; }},
    {"islands", [](const StageTimes &t) { return t.islands; }},
    {"solve", [](const StageTimes &t) { return t.solve; }},
    {"solve: setup", [](const StageTimes &t) { return t.solveParts.setup; }},
    {"solve: velocity", [](const StageTimes &t) { return t.solveParts.velocity; }},
    {"solve: carrier", [](const StageTimes &t) { return t.solveParts.carrier; }},
    {"solve: position", [](const StageTimes &t) { return t.solveParts.position; }},
    {"integrate", [](const StageTimes &t) { return t.integrate; }},
    {"ccd", [](const StageTimes &t) { return t.ccd; }},
    {"landing", [](const StageTimes &t) { return t.landing; }},
    {"sleep", [](const StageTimes &t) { return t.sleep; }},
    {"shared", [](const StageTimes &t) { return t.shared; }},
    {"serial", [](const StageTimes &t) { return t.total - t.shared; }},
};

int run(int argc, char **argv) {
    std::vector<std::string> scenes;
    int steps = 600;
    int threads = 1;
    bool worldDefaults = false;
    int substeps = 0, iterations = 0, positions = -1;  // 0 / -1: the scene's own
    bool landing = true;  // DebugSettings::landingCorrection, for comparing
    bool carrier = true;  // DebugSettings::carrierPass, for comparing
    bool holding = true;  // DebugSettings::holding, for comparing
    bool unchanged = true;  // DebugSettings::unchangedPairs, for comparing
    int slowest = 0;      // 0: medians; K: means over the K slowest steps
    for (int i = 1; i < argc; ++i) {
        std::string arg, value;
        if (std::string(argv[i]) == "--defaults") {
            worldDefaults = true;
            continue;
        }
        if (!bench::readOption("cyclone-stages", argc, argv, i, arg, value)) return 2;
        if (bench::readSceneOption(arg, value, scenes, steps, threads)) continue;
        if (arg == "--substeps") {
            substeps = std::atoi(value.c_str());
        } else if (arg == "--iterations") {
            iterations = std::atoi(value.c_str());
        } else if (arg == "--positions") {
            positions = std::atoi(value.c_str());
        } else if (arg == "--landing" && (value == "on" || value == "off")) {
            landing = value == "on";
        } else if (arg == "--carrier" && (value == "on" || value == "off")) {
            carrier = value == "on";
        } else if (arg == "--holding" && (value == "on" || value == "off")) {
            holding = value == "on";
        } else if (arg == "--unchanged" && (value == "on" || value == "off")) {
            unchanged = value == "on";
        } else if (arg == "--slowest") {
            slowest = std::atoi(value.c_str());
            if (slowest < 1) {
                std::fprintf(stderr, "cyclone-stages: --slowest must be >= 1, got \"%s\"\n", value.c_str());
                return 2;
            }
        } else {
            std::fprintf(stderr, "cyclone-stages: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    if (steps <= 60) {
        std::fprintf(stderr, "cyclone-stages: --steps must be > 60 (the first second is not counted)\n");
        return 2;
    }
    if (slowest > steps - 60) {
        std::fprintf(stderr, "cyclone-stages: --slowest %d is more than the %d steps after the first second\n",
                     slowest, steps - 60);
        return 2;
    }
    if (scenes.empty()) scenes = bench::sceneNames();
    std::vector<bench::Scene> built;  // every name checked before the table starts
    for (const std::string &name : scenes) built.push_back(bench::makeScene(name));

    if (slowest > 0) std::printf("Means over the %d slowest steps after the first second, ms:\n\n", slowest);
    std::printf("| scene |");
    for (const Column &c : kColumns) std::printf(" %s |", c.name);
    std::printf(" resting steps |\n|---|");
    for (std::size_t k = 0; k <= std::size(kColumns); ++k) std::printf("--:|");
    std::printf("\n");
    for (bench::Scene &scene : built) {
        scene.world.threads = threads;
        if (worldDefaults) bench::useWorldDefaults(scene.world);
        if (substeps > 0) scene.world.substeps = substeps;
        if (iterations > 0) scene.world.velocityIterations = iterations;
        if (positions >= 0) scene.world.positionIterations = positions;
        scene.world.debug.landingCorrection = landing;
        scene.world.debug.carrierPass = carrier;
        scene.world.debug.holding = holding;
        scene.world.debug.unchangedPairs = unchanged;
        World world(scene.world);
        for (const BodySettings &body : scene.bodies) world.addBody(body);
        std::vector<StageTimes> times;
        int resting = 0;
        for (int i = 0; i < steps; ++i) {
            world.step(1.0 / 60);
            if (world.stats().substeps < scene.world.substeps) ++resting;
            if (i >= 60) times.push_back(world.stats().ms);
        }
        if (slowest > 0) {
            // The slowest steps first, each stage then averaged over them.
            std::stable_sort(times.begin(), times.end(),
                             [](const StageTimes &x, const StageTimes &y) { return x.total > y.total; });
            times.resize(static_cast<std::size_t>(slowest));
        }
        std::printf("| %s |", scene.name.c_str());
        for (const Column &c : kColumns) {
            std::vector<double> values;
            for (const StageTimes &t : times) values.push_back(c.read(t));
            std::printf(" %.3f |", slowest > 0 ? bench::mean(values) : bench::median(values));
        }
        std::printf(" %d / %d |\n", resting, steps);
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv) { return cyclone::bench::guardedMain("cyclone-stages", run, argc, argv); }
