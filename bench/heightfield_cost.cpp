// cyclone-heightfield: what a large height field costs. Builds an N x N field (rolling
// hills, 0.25 m cells), adds it to a World, drops a box on it and steps once: the bytes
// the World keeps per sample, the time to add it, the first step's time (its first
// contact query) and the median of later steps.
//
//   cyclone-heightfield [N]          (default 1024)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "alloc_counter.h"
#include "cyclone/world/world.h"

namespace {

using namespace cyclone;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char **argv) {
    const int n = argc > 1 ? std::atoi(argv[1]) : 1024;
    if (n < 2) {
        std::fprintf(stderr, "cyclone-heightfield: N must be >= 2\n");
        return 2;
    }
    const real spacing = 0.25;
    std::vector<real> heights(static_cast<std::size_t>(n) * n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            heights[static_cast<std::size_t>(i) * n + j] = std::sin(0.05 * j) * std::cos(0.07 * i);

    World world;
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::heightfield(n, n, {spacing, spacing}, std::move(heights));
    const long long before = bench::allocCounters().liveBytes;
    auto start = Clock::now();
    world.addBody(ground);
    const double addMs = msSince(start);
    const long long kept = bench::allocCounters().liveBytes - before;

    // A box just above the middle of the field, falling onto it.
    const real middle = 0.5 * (n - 1) * spacing;
    BodySettings box;
    box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    box.position = Vector3(middle, 1.6, middle);
    box.mass = 1;
    world.addBody(box);
    start = Clock::now();
    world.step(1.0 / 60);
    const double firstMs = msSince(start);
    std::vector<double> steps;
    for (int k = 0; k < 120; ++k) {
        start = Clock::now();
        world.step(1.0 / 60);
        steps.push_back(msSince(start));
    }
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());

    const double samples = static_cast<double>(n) * n;
    std::printf("| samples | bytes kept per sample | addBody ms | first step ms | median step ms |\n");
    std::printf("|---|---|---|---|---|\n");
    std::printf("| %d x %d | %.2f | %.1f | %.3f | %.3f |\n", n, n, static_cast<double>(kept) / samples, addMs, firstMs,
                steps[steps.size() / 2]);
    return 0;
}
