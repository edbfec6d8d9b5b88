// cyclone-drift: how much a scene's 10 s drift depends on chance. Runs each scene once as
// the benchmark builds it and then with each body's x moved by a few nanometres (a
// different small pattern per run), and prints the tracked body's drift after 10 s for
// every run, their mean and the worst. A tall stack's drift is chaotic: rounding
// differences alone move it, so one run says little about the next.
//
//   cyclone-drift [--scene NAME[,NAME...]] [--runs N] [--threads T]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cyclone/world/world.h"
#include "scenes.h"
#include "tool_main.h"

namespace {

using namespace cyclone;

// The tracked body's drift after 10 s at 60 Hz, m, with the bodies' x moved by
// nanometres in a pattern set by `run` (run 0: the scene as built).
double driftAfter10s(const bench::Scene &scene, int run) {
    World world(scene.world);
    std::vector<BodyId> ids;
    for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
        BodySettings body = scene.bodies[k];
        if (run > 0) body.position.x() += static_cast<real>(static_cast<long>((k * 7919 + run * 104729) % 13) - 6) * 1e-9;
        ids.push_back(world.addBody(body));
    }
    const BodyId tracked = ids[static_cast<std::size_t>(scene.tracked)];
    const Vector3 start = world.body(tracked).getPosition();
    for (int i = 0; i < 600; ++i) world.step(1.0 / 60);
    return (world.body(tracked).getPosition() - start).norm();
}

int run(int argc, char **argv) {
    std::vector<std::string> names = {"pyramid20", "pyramid40"};
    int runs = 5;
    int threads = 1;
    for (int i = 1; i < argc; ++i) {
        std::string arg, value;
        if (!bench::readOption("cyclone-drift", argc, argv, i, arg, value)) return 2;
        if (arg == "--scene") {
            names = bench::splitSceneList(value);
        } else if (arg == "--runs") {
            runs = std::atoi(value.c_str());
        } else if (arg == "--threads") {
            threads = std::atoi(value.c_str());
        } else {
            std::fprintf(stderr, "cyclone-drift: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    if (runs < 1) {
        std::fprintf(stderr, "cyclone-drift: --runs must be >= 1\n");
        return 2;
    }
    for (const std::string &name : names) {
        bench::Scene scene = bench::makeScene(name);
        if (scene.tracked < 0) {
            std::fprintf(stderr, "cyclone-drift: scene %s tracks no body\n", name.c_str());
            return 2;
        }
        scene.world.threads = threads;
        std::printf("%s, drift after 10 s (cm):", name.c_str());
        double sum = 0;
        double worst = 0;
        for (int r = 0; r < runs; ++r) {
            const double drift = driftAfter10s(scene, r) * 100;
            sum += drift;
            worst = std::max(worst, drift);
            std::printf(" %.2f", drift);
            std::fflush(stdout);
        }
        std::printf(" | mean %.2f, worst %.2f\n", sum / runs, worst);
    }
    return 0;
}

}  // namespace

int main(int argc, char **argv) { return cyclone::bench::guardedMain("cyclone-drift", run, argc, argv); }
