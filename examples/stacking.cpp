// Stacking: a 12-box tower with alternating 1 cm offsets and a 20-level box pyramid.
// Prints, for each, how far the top box moved, the deepest penetration and when
// everything fell asleep.
//
//   stacking [--substeps N] [--velocity-iterations N]
//            [--position-iterations N] [--slop M] [--recovery F] [--reuse M]
//            [--shock on|off]
//
// The options change the WorldSettings, to compare solver settings on the same scenes.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "cyclone/world.h"

using namespace cyclone;

namespace {

struct Report {
    double topDrift = 0;
    double maxPenetration = 0;
    double msPerStep = 0;
    int asleepStep = -1;
};

BodyId addGround(World &world) {
    BodySettings ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    return world.addBody(ground);
}

BodyId addBox(World &world, const Vector3 &position) {
    BodySettings box;
    box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    box.position = position;
    box.material.friction = 0.6;
    return world.addBody(box);
}

Report simulate(World &world, BodyId top, int steps) {
    Report report;
    const Vector3 start = world.body(top).getPosition();
    const auto begin = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) {
        world.step(1.0 / 60.0);
        report.maxPenetration = std::max(report.maxPenetration, double(world.stats().maxPenetration));
        if (report.asleepStep < 0 && world.stats().awakeBodies == 0) report.asleepStep = i;
    }
    const auto end = std::chrono::steady_clock::now();
    report.msPerStep = std::chrono::duration<double, std::milli>(end - begin).count() / steps;
    report.topDrift = (world.body(top).getPosition() - start).norm();
    return report;
}

void print(const char *name, int boxes, const Report &r) {
    std::printf("%-22s %4d boxes  top drift %7.4f m  max penetration %7.4f m  %6.3f ms/step  ", name, boxes,
                r.topDrift, r.maxPenetration, r.msPerStep);
    if (r.asleepStep >= 0)
        std::printf("all asleep at %.2f s\n", (r.asleepStep + 1) / 60.0);
    else
        std::printf("awake at the end\n");
}

}  // namespace

void run(const WorldSettings &chosen);

bool parse(int argc, char **argv, WorldSettings &settings) {
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) return false;
        const char *value = argv[++i];
        if (flag == "--substeps") {
            settings.substeps = std::atoi(value);
        } else if (flag == "--velocity-iterations") {
            settings.velocityIterations = std::atoi(value);
        } else if (flag == "--position-iterations") {
            settings.positionIterations = std::atoi(value);
        } else if (flag == "--slop") {
            settings.penetrationSlop = std::atof(value);
        } else if (flag == "--reuse") {
            settings.debug.manifoldReuseTolerance = std::atof(value);
        } else if (flag == "--recovery") {
            settings.penetrationRecovery = std::atof(value);
        } else if (flag == "--shock") {
            if (std::strcmp(value, "on") == 0) settings.debug.carrierPass = true;
            else if (std::strcmp(value, "off") == 0) settings.debug.carrierPass = false;
            else return false;
        } else {
            return false;
        }
    }
    return true;
}

int main(int argc, char **argv) {
    WorldSettings chosen;
    if (!parse(argc, argv, chosen)) {
        std::fprintf(stderr, "usage: stacking [--substeps N] [--velocity-iterations N] "
                             "[--position-iterations N] [--slop M] [--recovery F] [--reuse M] [--shock on|off]\n");
        return 2;
    }
    std::printf("10 s at 60 Hz, %d sub-steps x (%d velocity + %d position iterations), slop %g m, "
                "carrier pass %s\n",
                chosen.substeps,
                chosen.velocityIterations, chosen.positionIterations, chosen.penetrationSlop,
                chosen.debug.carrierPass ? "on" : "off");
    try {
        run(chosen);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "stacking: %s\n", e.what());
        return 2;
    }
    return 0;
}

void run(const WorldSettings &chosen) {
    for (bool sleep : {false, true}) {
        WorldSettings settings = chosen;
        settings.sleep = sleep;
        World tower(settings);  // throws InvalidArgument on bad options
        addGround(tower);
        BodyId top;
        for (int i = 0; i < 12; ++i) top = addBox(tower, Vector3(i % 2 ? 0.01 : -0.01, 0.5 + i, 0));
        print(sleep ? "tower (sleep on)" : "tower (sleep off)", 12, simulate(tower, top, 600));

        World pyramid(settings);
        addGround(pyramid);
        const int base = 20;
        int count = 0;
        for (int level = 0; level < base; ++level) {
            for (int i = 0; i < base - level; ++i) {
                const double x = (i - (base - level - 1) / 2.0) * 1.05;
                top = addBox(pyramid, Vector3(x, 0.5 + level, 0));
                ++count;
            }
        }
        print(sleep ? "pyramid-20 (sleep on)" : "pyramid-20 (sleep off)", count, simulate(pyramid, top, 600));
    }
}
