// Your first game (README.md shows this file from its first #include): a level, a player
// walked by scripted input, a fixed-step loop, events and a ground ray. No window: where a
// game would draw or play a sound, it prints.
#include <cstdio>
#include <string>
#include <unordered_map>

#include <cyclone/world.h>
using namespace cyclone;

BodyId add(World &world, const Shape &shape, const Vector3 &position, Motion motion, real mass = 1) {
    BodySettings s;
    s.shape = shape;
    s.position = position;
    s.motion = motion;
    s.mass = mass;  // kg; a static or kinematic body's is infinite
    return world.addBody(s);
}

int main() {
    World world;  // gravity 9.81 m/s^2 down the y axis
    add(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero(), Motion::Static);
    const BodyId platform = add(world, Shape::box({1.5, 0.2, 1.5}), {4, 1, -4}, Motion::Kinematic);
    world.setVelocity(platform, {1, 0, 0});         // kinematic: moved by the velocity the game sets
    std::unordered_map<BodyId, std::string> crates;  // BodyId hashes and orders: a key of maps
    for (int i = 0; i < 3; ++i)
        crates[add(world, Shape::box({0.4, 0.4, 0.4}), {4, 0.4 + 0.8 * i, 0}, Motion::Dynamic, 10)] =
            "crate " + std::to_string(i);
    BodySettings zone;                               // a sensor: reports who enters, pushes nothing
    zone.motion = Motion::Static;
    zone.sensor = true;
    zone.shape = Shape::box({1, 1, 2});
    zone.position = {10, 1, 0};
    const BodyId goal = world.addBody(zone);
    BodySettings hero;                               // an upright capsule: 0.3 m radius, 1.8 m tall
    hero.shape = Shape::capsule(0.3, 1.2, Axis::Y);  // Axis::Z (lying) is the default, as in FCL
    hero.position = {0, 0.9, 0};
    hero.mass = 80;
    hero.canSleep = false;
    const BodyId player = world.addBody(hero);       // bad input throws InvalidArgument, naming it

    FixedStepper stepper(world);                     // 1/60 s steps whatever the frame rate
    QueryFilter notMe;
    notMe.ignore = player;
    bool grounded = false;
    for (int frame = 0; frame < 240; ++frame) {
        const real frameSeconds = frame % 2 == 0 ? 0.02 : 0.013;  // your clock's frame time
        stepper.advance(
            frameSeconds,
            [&](real) {  // before each step: input, acting for exactly one step
                const Vector3 v = world.body(player).getVelocity();
                world.setVelocity(player, {2.5, v.y(), 0});   // walk right at 2.5 m/s
                world.setRotation(player, Vector3::Zero());  // and stay upright
                if (frame == 150 && grounded) world.applyImpulse(player, {0, 80 * 4.0, 0});  // jump
                const real x = world.body(platform).getPosition().x();
                if (x > 6 || x < 2) world.setVelocity(platform, {x > 6 ? -1.0 : 1.0, 0, 0});
            },
            [&](real) {  // after each step: that step's events
                for (const ContactBegin &c : world.events().contactBegins) {
                    const BodyId other = c.a == player ? c.b : c.a;
                    if ((c.a == player || c.b == player) && crates.count(other))
                        std::printf("frame %3d: thud, %s at %.1f m/s\n", frame, crates[other].c_str(), c.approachSpeed);
                }
                for (const SensorEvent &e : world.events().sensorBegins)
                    if (e.sensor == goal && e.body == player) std::printf("frame %3d: goal reached!\n", frame);
            });
        const Vector3 feet = world.body(player).getPosition() - Vector3(0, 0.9, 0);  // a ray down from them
        grounded = world.rayCast(feet + Vector3(0, 0.05, 0), -Vector3::UnitY(), 0.1, notMe).has_value();
        const Matrix4 pose = stepper.transform(player);  // interpolated between steps: draw this
        if (frame % 40 == 0)
            std::printf("frame %3d: player at x = %.2f m, %s\n", frame, pose.translation().x(),
                        grounded ? "on the ground" : "in the air");
    }
}
