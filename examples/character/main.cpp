// A capsule character walks across a floor, up a 0.2 m step, up a slope, and into a wall,
// moved by World::shapeCast (character_controller.h). Prints where it is each second.
#include <cstdio>

#include "character_controller.h"

using namespace cyclone;

namespace {

BodyId addStatic(World &world, const Shape &shape, const Vector3 &position, const Quaternion &orientation) {
    BodySettings s;
    s.isStatic = true;
    s.shape = shape;
    s.position = position;
    s.orientation = orientation;
    return world.addBody(s);
}

}  // namespace

int main() {
    World world;
    const Quaternion level = Quaternion::Identity();
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero(), level);
    addStatic(world, Shape::box({1, 0.1, 2}), {3, 0.1, 0}, level);  // a step 0.2 m high, x in [2, 4]
    // A 20 degree ramp from x = 4 rising to the right, then a wall at x = 9.
    addStatic(world, Shape::box({1.5, 0.1, 2}), {5.4, 0.6, 0}, Quaternion(Eigen::AngleAxis<real>(0.349, Vector3::UnitZ())));
    addStatic(world, Shape::box({0.5, 3, 2}), {9.5, 3, 0}, level);

    character::CharacterController walker(world, Vector3(0, 0.8 + 0.005, 0));
    const real dt = 1.0 / 60;
    for (int step = 1; step <= 600; ++step) {
        walker.move(Vector3(1.5, 0, 0), dt);
        if (step % 60 == 0)
            std::printf("t = %4.1f s  centre (%.3f, %.3f, %.3f)  %s\n", step * dt, walker.centre().x(),
                        walker.centre().y(), walker.centre().z(), walker.grounded() ? "on the ground" : "falling");
    }
    return 0;
}
