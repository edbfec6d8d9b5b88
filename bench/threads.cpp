// cyclone-threads: two threads against one, measured side by side. Builds each benchmark
// scene twice, one World on one thread and one on T, and steps them in turn (one step of
// each, which goes first swapping every step), timing every step. Readings of one build
// taken minutes apart on a shared machine spread by a third; two worlds stepped in turn
// see the same machine, so the ratio of each step's two times keeps what the threads
// gain and little of the machine's drift.
//
//   cyclone-threads [--scene NAME[,NAME...]] [--steps N] [--threads T] [--defaults]
//
// Prints per scene the median step on one thread and on T, the ratio of those medians,
// the median of the steps' own ratios, and whether the two worlds ended bit for bit the
// same (WorldSettings::threads must not change a result). Both worlds share the caches, so
// each step is a little slower than in a run of its own.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cyclone/world/world.h"
#include "scenes.h"
#include "statistics.h"
#include "tool_main.h"

namespace {

using namespace cyclone;

constexpr const char *kTool = "cyclone-threads";

// The wall time of one step of `world`, ms.
double timedStep(World &world) {
    const auto start = std::chrono::steady_clock::now();
    world.step(1.0 / 60);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Whether every body of the two worlds has the same position and orientation, bit for bit.
bool sameBodies(const World &one, const World &other, const std::vector<BodyId> &a, const std::vector<BodyId> &b) {
    for (std::size_t k = 0; k < a.size(); ++k) {
        const RigidBody &x = one.body(a[k]);
        const RigidBody &y = other.body(b[k]);
        const Vector3 px = x.getPosition(), py = y.getPosition();
        const Quaternion qx = x.getOrientation(), qy = y.getOrientation();
        if (std::memcmp(px.data(), py.data(), sizeof px) != 0) return false;
        if (std::memcmp(qx.coeffs().data(), qy.coeffs().data(), sizeof(real) * 4) != 0) return false;
    }
    return true;
}

void compare(const bench::Scene &scene, int steps, int threads) {
    WorldSettings single = scene.world;
    single.threads = 1;
    WorldSettings shared = scene.world;
    shared.threads = threads;
    World one(single), many(shared);
    std::vector<BodyId> idsOne, idsMany;
    for (const BodySettings &body : scene.bodies) {
        idsOne.push_back(one.addBody(body));
        idsMany.push_back(many.addBody(body));
    }
    std::vector<double> timesOne, timesMany, ratios;
    for (int i = 0; i < steps; ++i) {
        double t1 = 0, tn = 0;
        if (i % 2 == 0) {
            t1 = timedStep(one);
            tn = timedStep(many);
        } else {
            tn = timedStep(many);
            t1 = timedStep(one);
        }
        timesOne.push_back(t1);
        timesMany.push_back(tn);
        ratios.push_back(t1 / tn);
    }
    const double m1 = bench::median(timesOne), mn = bench::median(timesMany);
    std::printf("| %s | %.3f | %.3f | %.2f | %.2f | %s |\n", scene.name.c_str(), m1, mn, m1 / mn,
                bench::median(ratios), sameBodies(one, many, idsOne, idsMany) ? "yes" : "NO");
}

int run(int argc, char **argv) {
    std::vector<std::string> scenes;
    int steps = 600;
    int threads = 2;
    bool worldDefaults = false;
    for (int i = 1; i < argc; ++i) {
        std::string arg, value;
        if (std::string(argv[i]) == "--defaults") {
            worldDefaults = true;
            continue;
        }
        if (!bench::readOption(kTool, argc, argv, i, arg, value)) return 2;
        if (!bench::readSceneOption(arg, value, scenes, steps, threads)) {
            std::fprintf(stderr, "%s: unknown option %s\n", kTool, arg.c_str());
            return 2;
        }
    }
    if (steps < 1 || threads < 2 || threads > 64) {
        std::fprintf(stderr, "%s: --steps must be >= 1 and --threads 2-64\n", kTool);
        return 2;
    }
    if (scenes.empty()) scenes = bench::sceneNames();
    std::vector<bench::Scene> built;  // every name checked before the table starts
    for (const std::string &name : scenes) built.push_back(bench::makeScene(name));
    std::printf("| scene | median ms, 1 thread | median ms, %d threads | ratio of medians | median of step ratios | "
                "same bits |\n|---|--:|--:|--:|--:|---|\n",
                threads);
    for (bench::Scene &scene : built) {
        if (worldDefaults) bench::useWorldDefaults(scene.world);
        compare(scene, steps, threads);
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv) { return cyclone::bench::guardedMain(kTool, run, argc, argv); }
