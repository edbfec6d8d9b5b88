// A game's physics layer on an installed cyclone: a ball dropped on the ground.
#include <cstdio>

#include <cyclone/world.h>

using namespace cyclone;

int main() {
    World world;
    BodySettings ground;
    ground.isStatic = true;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(ground);

    BodySettings ball;
    ball.shape = Shape::sphere(0.5);
    ball.position = Vector3(0, 3, 0);
    const BodyId id = world.addBody(ball);
    for (int i = 0; i < 180; ++i) world.step(1.0 / 60.0);
    const double y = world.body(id).getPosition().y();
    std::printf("ball at %.4f m\n", y);
    return y > 0.49 && y < 0.51 ? 0 : 1;
}
