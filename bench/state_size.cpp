// cyclone-state: what World::saveState costs. Steps each scene and, at the given steps,
// saves the state: its bytes per body (all bodies, static ones included) and the median
// time of a save, of a restore and of a step around it.
//
//   cyclone-state [--scene NAME[,NAME...]] [--at STEP[,STEP...]] [--threads T] [--repeats R]
//
// Defaults: the pyramids 10 to 100, mixed1000 and sleeping1000, at steps 100 and 600,
// one thread, 15 repeats. A restore puts the World back where it was saved, so the
// repeats time the same work.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cyclone/world/world.h"
#include "scenes.h"
#include "statistics.h"
#include "tool_main.h"

namespace {

using namespace cyclone;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<int> splitInts(const std::string &list) {
    std::vector<int> values;
    for (const std::string &item : bench::splitSceneList(list)) values.push_back(std::atoi(item.c_str()));
    return values;
}

int run(int argc, char **argv) {
    std::vector<std::string> scenes = {"pyramid10", "pyramid20", "pyramid40", "pyramid100", "mixed1000", "sleeping1000"};
    std::vector<int> at = {100, 600};
    int threads = 1;
    int repeats = 15;
    for (int i = 1; i < argc; ++i) {
        std::string arg, value;
        if (!bench::readOption("cyclone-state", argc, argv, i, arg, value)) return 2;
        if (arg == "--scene") {
            scenes = bench::splitSceneList(value);
        } else if (arg == "--at") {
            at = splitInts(value);
        } else if (arg == "--threads") {
            threads = std::atoi(value.c_str());
        } else if (arg == "--repeats") {
            repeats = std::atoi(value.c_str());
        } else {
            std::fprintf(stderr, "cyclone-state: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    if (repeats < 1) {
        std::fprintf(stderr, "cyclone-state: --repeats must be >= 1\n");
        return 2;
    }
    std::printf("| scene | step | bodies | awake | state, bytes | bytes per body | save, ms | restore, ms | step, ms |\n");
    std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    for (const std::string &name : scenes) {
        bench::Scene scene = bench::makeScene(name);
        scene.world.threads = threads;
        World world(scene.world);
        for (const BodySettings &body : scene.bodies) world.addBody(body);
        int stepped = 0;
        for (int target : at) {
            for (; stepped < target; ++stepped) world.step(1.0 / 60);
            std::vector<double> saves, restores, steps;
            std::vector<std::uint8_t> state;
            for (int r = 0; r < repeats; ++r) {
                auto start = Clock::now();
                state = world.saveState();
                saves.push_back(msSince(start));
                start = Clock::now();
                world.step(1.0 / 60);
                steps.push_back(msSince(start));
                start = Clock::now();
                world.restoreState(state);
                restores.push_back(msSince(start));
            }
            const std::size_t bodies = world.bodyCount();
            std::printf("| %s | %d | %zu | %d | %zu | %.0f | %.3f | %.3f | %.3f |\n", name.c_str(), target, bodies,
                        world.stats().awakeBodies, state.size(), static_cast<double>(state.size()) / bodies,
                        bench::median(saves), bench::median(restores), bench::median(steps));
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv) { return cyclone::bench::guardedMain("cyclone-state", run, argc, argv); }
