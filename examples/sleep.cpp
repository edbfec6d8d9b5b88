// Sleep: three stacks settle and fall asleep; a ball thrown at one of them wakes that
// stack only; removing a box's support wakes the boxes above it.
#include <cstdio>
#include <vector>

#include "cyclone/world.h"

using namespace cyclone;

namespace {

int awake(const World &world, const std::vector<BodyId> &ids) {
    int n = 0;
    for (BodyId id : ids) n += world.body(id).getAwake() ? 1 : 0;
    return n;
}

}  // namespace

int main() {
    World world;
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(ground);

    std::vector<std::vector<BodyId>> stacks(3);
    for (int s = 0; s < 3; ++s) {
        for (int i = 0; i < 4; ++i) {
            BodySettings box;
            box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            box.position = Vector3(s * 6.0, 0.5 + i, 0);
            stacks[s].push_back(world.addBody(box));
        }
    }
    int step = 0;
    auto run = [&](double seconds) {
        for (int i = 0; i < int(seconds * 60); ++i, ++step) world.step(1.0 / 60.0);
    };
    auto report = [&](const char *what) {
        std::printf("t = %5.2f s  %-34s awake per stack: %d %d %d of 4\n", step / 60.0, what, awake(world, stacks[0]),
                    awake(world, stacks[1]), awake(world, stacks[2]));
    };
    report("start");
    int asleepAt = -1;
    while (step < 600 && asleepAt < 0) {
        run(1.0 / 60.0);
        if (world.stats().awakeBodies == 0) asleepAt = step;
    }
    std::printf("t = %5.2f s  everything asleep (%s)\n", step / 60.0, asleepAt >= 0 ? "yes" : "no");

    BodySettings ball;
    ball.shape = Shape::sphere(0.25);
    ball.mass = 5;
    ball.position = Vector3(-4, 3.25, 0);
    const BodyId thrown = world.addBody(ball);
    world.setVelocity(thrown, Vector3(12, 0, 0));
    run(0.5);
    report("ball thrown at stack 0");
    run(6);
    report("6 s later");
    world.removeBody(stacks[2][1]);
    stacks[2].erase(stacks[2].begin() + 1);
    run(1.0 / 60.0);
    report("second box of stack 2 removed");
    return 0;
}
