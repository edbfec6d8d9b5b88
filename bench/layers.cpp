// cyclone-layers: where and when a pyramid starts to move. Steps a pyramid scene of the
// benchmark and prints, every --every steps, each layer's largest displacement from its
// start (the layer's boxes' worst), and at the end the step at which each layer's worst
// box first moved more than 1 mm and 1 cm, so that a collapse can be traced to the layer
// it starts from.
//
//   cyclone-layers [--scene pyramid60] [--steps N] [--substeps S] [--iterations I]
//                  [--every K] [--layers L] [--positions P] [--reuse M] [--shock 0|1]
//                  [--warm 0|1] [--recovery R] [--slop M] [--velocities 0|1]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cyclone/world/world.h"
#include "scenes.h"
#include "tool_main.h"

namespace {

using namespace cyclone;

int run(int argc, char **argv) {
    std::string name = "pyramid60";
    int steps = 600, substeps = 1, iterations = 10, every = 60, shownLayers = 12;
    WorldSettings knobs;
    bool velocities = false;
    for (int i = 1; i < argc; ++i) {
        std::string arg, value;
        if (!bench::readOption("cyclone-layers", argc, argv, i, arg, value)) return 2;
        if (arg == "--scene") {
            name = value;
        } else if (arg == "--steps") {
            steps = std::atoi(value.c_str());
        } else if (arg == "--substeps") {
            substeps = std::atoi(value.c_str());
        } else if (arg == "--iterations") {
            iterations = std::atoi(value.c_str());
        } else if (arg == "--every") {
            every = std::max(1, std::atoi(value.c_str()));
        } else if (arg == "--layers") {
            shownLayers = std::max(1, std::atoi(value.c_str()));
        } else if (arg == "--positions") {
            knobs.positionIterations = std::atoi(value.c_str());
        } else if (arg == "--reuse") {
            knobs.debug.manifoldReuseTolerance = std::atof(value.c_str());
        } else if (arg == "--shock") {
            knobs.debug.carrierPass = std::atoi(value.c_str()) != 0;
        } else if (arg == "--warm") {
            knobs.debug.warmStarting = std::atoi(value.c_str()) != 0;
        } else if (arg == "--recovery") {
            knobs.penetrationRecovery = std::atof(value.c_str());
        } else if (arg == "--slop") {
            knobs.penetrationSlop = std::atof(value.c_str());
        } else if (arg == "--velocities") {
            velocities = std::atoi(value.c_str()) != 0;
        } else {
            std::fprintf(stderr, "cyclone-layers: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    if (name.rfind("pyramid", 0) != 0) {
        std::fprintf(stderr, "cyclone-layers: --scene must be a pyramid (pyramid10 ... pyramid200), got %s\n", name.c_str());
        return 2;
    }
    bench::Scene scene = bench::makeScene(name);
    scene.world.substeps = substeps;
    scene.world.velocityIterations = iterations;
    scene.world.positionIterations = knobs.positionIterations;
    scene.world.debug.manifoldReuseTolerance = knobs.debug.manifoldReuseTolerance;
    scene.world.debug.carrierPass = knobs.debug.carrierPass;
    scene.world.debug.warmStarting = knobs.debug.warmStarting;
    scene.world.penetrationRecovery = knobs.penetrationRecovery;
    scene.world.penetrationSlop = knobs.penetrationSlop;
    World world(scene.world);
    std::vector<BodyId> ids;
    std::vector<int> layerOf;
    std::vector<Vector3> start;
    int layers = 0;
    for (const BodySettings &body : scene.bodies) {
        const BodyId id = world.addBody(body);
        if (body.motion == Motion::Static) continue;
        ids.push_back(id);
        // Pyramid boxes are unit cubes whose centres sit at 0.5 + layer.
        const int layer = static_cast<int>(std::lround(body.position.y() - 0.5));
        layerOf.push_back(layer);
        start.push_back(body.position);
        layers = std::max(layers, layer + 1);
    }
    std::vector<int> firstMm(static_cast<std::size_t>(layers), -1), firstCm(static_cast<std::size_t>(layers), -1);
    std::vector<double> worst(static_cast<std::size_t>(layers));
    // The layers printed: spread evenly from the bottom to the top.
    std::vector<int> shown;
    for (int k = 0; k < std::min(shownLayers, layers); ++k)
        shown.push_back(layers == 1 ? 0 : static_cast<int>(std::lround(k * (layers - 1.0) / (std::min(shownLayers, layers) - 1.0))));
    std::printf("%s at %d x %d, layer worst displacement (mm)\nstep", name.c_str(), substeps, iterations);
    for (int layer : shown) std::printf(" %7s%d", "L", layer);
    std::printf("\n");
    long carrierSweeps = 0;
    for (int s = 1; s <= steps; ++s) {
        world.step(1.0 / 60);
        carrierSweeps += world.stats().carrierSweeps;
        std::fill(worst.begin(), worst.end(), 0.0);
        for (std::size_t b = 0; b < ids.size(); ++b) {
            const double d = (world.body(ids[b]).getPosition() - start[b]).norm();
            double &w = worst[static_cast<std::size_t>(layerOf[b])];
            w = std::max(w, d);
        }
        for (int layer = 0; layer < layers; ++layer) {
            const auto l = static_cast<std::size_t>(layer);
            if (firstMm[l] < 0 && worst[l] > 1e-3) firstMm[l] = s;
            if (firstCm[l] < 0 && worst[l] > 1e-2) firstCm[l] = s;
        }
        if (s % every == 0 || s == 1) {
            std::printf("%4d", s);
            for (int layer : shown) std::printf(" %8.2f", worst[static_cast<std::size_t>(layer)] * 1e3);
            const RigidBody &top = world.body(ids.back());
            const Vector3 d = (top.getPosition() - start.back()) * 1e3;
            const Vector3 w = top.getRotation();
            std::printf("  top d (%.2f %.2f %.2f) mm w (%.4f %.4f %.4f)\n", d.x(), d.y(), d.z(), w.x(), w.y(), w.z());
            if (velocities) {
                // Per shown layer: the spread of the boxes' vertical velocities (mm/s) and
                // their fastest turn (rad/s).
                std::printf("  vy spread / max |w|");
                for (int layer : shown) {
                    double low = 1e9, high = -1e9, turn = 0;
                    for (std::size_t b = 0; b < ids.size(); ++b) {
                        if (layerOf[b] != layer) continue;
                        const RigidBody &body = world.body(ids[b]);
                        low = std::min(low, body.getVelocity().y());
                        high = std::max(high, body.getVelocity().y());
                        turn = std::max(turn, body.getRotation().norm());
                    }
                    std::printf(" %.2f/%.4f", (high - low) * 1e3, turn);
                }
                std::printf("\n");
            }
            std::fflush(stdout);
        }
    }
    std::printf("carrier sweeps per step (single runs, summed over sub-steps): %.0f\n",
                static_cast<double>(carrierSweeps) / steps);
    std::printf("first step over 1 mm / 1 cm per layer (-1: never):\n");
    for (int layer = 0; layer < layers; ++layer) {
        const auto l = static_cast<std::size_t>(layer);
        std::printf("L%d %d/%d%s", layer, firstMm[l], firstCm[l], layer % 10 == 9 ? "\n" : "  ");
    }
    std::printf("\n");
    return 0;
}

}  // namespace

int main(int argc, char **argv) { return cyclone::bench::guardedMain("cyclone-layers", run, argc, argv); }
