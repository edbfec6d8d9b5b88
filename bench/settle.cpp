// cyclone-settle: how deep contacts get and how soon a pile sleeps. Steps benchmark
// scenes (mixed1000 over several seeds) or scene files and prints, per run, the deepest
// contact of any step (with the step and the shapes of the two bodies there), the
// deepest from the second step on (the first step's contacts are those of the bodies as
// placed: a scene that places bodies overlapping shows it there), the
// deepest contact of the last step in which some body was awake (at rest, when the run
// falls asleep; with the shapes there when some body is still awake at the end), and the
// time after which every dynamic body sleeps.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cyclone/world.h"
#include "scenes.h"
#include "tool_main.h"
#ifdef CYCLONE_SETTLE_HAVE_SCENE_FILES
#include "scene_loader.h"
#include "scene_world.h"
#endif

namespace cyclone::bench {
namespace {

constexpr const char *kTool = "cyclone-settle";

// The deepest contact point drawn: where it is, so that the bodies there can be named.
class DeepestContact final : public DebugDraw {
public:
    void line(const Vector3 &, const Vector3 &, const DebugColor &) override {}
    void contact(const Vector3 &point, const Vector3 &, real depth, real, const DebugColor &,
                 const DebugColor &) override {
        if (depth > deepest) deepest = depth, where = point;
    }
    real deepest = -1;
    Vector3 where = Vector3::Zero();
};

struct Outcome {
    real deepestEver = 0;
    int deepestStep = -1;
    std::string deepestShapes;
    real deepestAfterFirst = 0;  ///< Over steps 2 on.
    int deepestAfterFirstStep = -1;
    real deepestAtRest = 0;
    std::string restShapes;  ///< At the last step, when some body is still awake then.
    int allAsleepStep = -1;
};

// The shape types of the bodies that a small ball at `point` touches.
std::string shapesAt(const World &world, const Vector3 &point) {
    std::vector<BodyId> bodies;
    world.overlap(Shape::sphere(0.005), point, Quaternion::Identity(), bodies);
    std::string names;
    for (const BodyId id : bodies) names += std::string(names.empty() ? "" : "-") + shapeTypeName(world.shape(id).type);
    return names;
}

// The shape types of the bodies at the deepest contact of the last step.
std::string deepestShapes(const World &world) {
    DeepestContact deepest;
    DebugDrawOptions options;
    options.shapes = false;
    options.contacts = true;
    world.debugDraw(deepest, options);
    return deepest.deepest >= 0 ? shapesAt(world, deepest.where) : "";
}

Outcome settle(World &world, int steps, real dt) {
    Outcome outcome;
    real lastAwakeDeepest = 0;
    for (int step = 1; step <= steps; ++step) {
        world.step(dt);
        const StepStats &stats = world.stats();
        if (stats.maxPenetration > outcome.deepestEver) {
            outcome.deepestEver = stats.maxPenetration;
            outcome.deepestStep = step;
            outcome.deepestShapes = deepestShapes(world);
        }
        if (step > 1 && stats.maxPenetration > outcome.deepestAfterFirst) {
            outcome.deepestAfterFirst = stats.maxPenetration;
            outcome.deepestAfterFirstStep = step;
        }
        if (stats.awakeBodies > 0) {
            lastAwakeDeepest = stats.maxPenetration;
            outcome.allAsleepStep = -1;
        } else if (outcome.allAsleepStep < 0) {
            outcome.allAsleepStep = step;
        }
    }
    outcome.deepestAtRest = lastAwakeDeepest;
    if (world.stats().awakeBodies > 0) outcome.restShapes = deepestShapes(world);
    return outcome;
}

void print(const std::string &run, const Outcome &o, real dt) {
    std::printf("| %s | %.2f | %d | %s | %.2f (%d) | %.2f | %s | %s |\n", run.c_str(), o.deepestEver * 1000,
                o.deepestStep, o.deepestShapes.c_str(), o.deepestAfterFirst * 1000, o.deepestAfterFirstStep,
                o.deepestAtRest * 1000, o.restShapes.c_str(),
                o.allAsleepStep < 0 ? "never" : (std::to_string(o.allAsleepStep * dt) + " s").c_str());
}

int run(int argc, char **argv) {
    std::vector<std::string> scenes;
    std::vector<std::string> files;
    int firstSeed = 1, lastSeed = 10, steps = 600;
    bool landing = true;  // DebugSettings::landingCorrection, for comparing
    bool worldDefaults = false;  // the benchmark scenes at WorldSettings' sub-steps and passes
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--defaults") {
            worldDefaults = true;
            continue;
        }
        std::string name, value;
        if (!readOption(kTool, argc, argv, i, name, value)) return 2;
        if (name == "--scene") {
            for (const std::string &s : splitSceneList(value)) scenes.push_back(s);
        } else if (name == "--file") {
            files.push_back(value);
        } else if (name == "--seeds") {
            const std::size_t dash = value.find('-');
            firstSeed = std::stoi(value.substr(0, dash));
            lastSeed = dash == std::string::npos ? firstSeed : std::stoi(value.substr(dash + 1));
        } else if (name == "--steps") {
            steps = std::stoi(value);
        } else if (name == "--landing" && (value == "on" || value == "off")) {
            landing = value == "on";
        } else {
            std::fprintf(stderr,
                         "usage: %s [--scene NAME[,NAME]] [--seeds FIRST-LAST] [--file SCENE.json] [--steps N] "
                         "[--landing on|off] [--defaults]\n",
                         kTool);
            return 2;
        }
    }
    if (scenes.empty() && files.empty()) scenes.push_back("mixed1000");
    constexpr real dt = 1.0 / 60;
    std::printf("| run | deepest ever mm | at step | shapes there | from step 2 mm (step) | deepest at rest mm | "
                "shapes there, if awake at the end | all asleep after |\n"
                "|---|--:|--:|---|--:|--:|---|--:|\n");
    for (const std::string &name : scenes) {
        for (int seed = firstSeed; seed <= lastSeed; ++seed) {
            const Scene scene = makeScene(name, static_cast<std::uint64_t>(seed));
            WorldSettings settings = scene.world;
            settings.debug.landingCorrection = landing;
            if (worldDefaults) useWorldDefaults(settings);
            World world(settings);
            for (const BodySettings &body : scene.bodies) world.addBody(body);
            print(name + " seed " + std::to_string(seed), settle(world, steps, dt), dt);
        }
    }
    for (const std::string &file : files) {
#ifdef CYCLONE_SETTLE_HAVE_SCENE_FILES
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        const scene::Scene scene = scene::loadScene(text.str(), file);
        scene::SceneWorld built = scene::buildWorld(scene);
        WorldSettings settings = built.world.settings();
        settings.debug.landingCorrection = landing;
        built.world.setSettings(settings);
        print(file, settle(built.world, steps, scene.dt), scene.dt);
#else
        std::fprintf(stderr, "%s: --file %s needs the runner (CYCLONE_BUILD_RUNNER=ON)\n", kTool, file.c_str());
        return 2;
#endif
    }
    return 0;
}

}  // namespace
}  // namespace cyclone::bench

int main(int argc, char **argv) { return cyclone::bench::guardedMain("cyclone-settle", cyclone::bench::run, argc, argv); }
