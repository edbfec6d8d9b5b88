// A small level walked by a scripted player, a character of the World
// (cyclone/world/character.h): up five stairs to a landing, onto a platform that carries
// it across a gap, down a ramp, a crate pushed along, a step aside, a jump onto a block
// too high to climb, and a goal zone (a sensor) on it that reports its arrival. Prints
// where it is twice a second.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <cyclone/world.h>

using namespace cyclone;

namespace {

BodyId block(World &world, const Vector3 &low, const Vector3 &high, Motion motion = Motion::Static, real mass = 1) {
    BodySettings s;
    s.motion = motion;
    s.shape = Shape::box((high - low) / 2);
    s.position = (low + high) / 2;
    s.mass = mass;
    return world.addBody(s);
}

struct Level {
    BodyId platform, crate, goal;
};

// x grows along the course; the floor is y = 0.
Level build(World &world) {
    BodySettings floor;
    floor.motion = Motion::Static;
    floor.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(floor);
    for (int k = 1; k <= 4; ++k) block(world, {2 + 0.5 * k - 0.5, 0, -1.5}, {2 + 0.5 * k, 0.3 * k, 1.5});
    block(world, {4, 0, -1.5}, {6, 1.5, 1.5});  // the landing, 1.5 m high
    Level level;
    // A platform level with the landing shuttles across a 4 m gap (x from 6 to 10).
    level.platform = block(world, {6, 1.2, -1.5}, {8, 1.5, 1.5}, Motion::Kinematic);
    block(world, {10, 0, -1.5}, {12, 1.5, 1.5});  // the far landing
    // A 20 degree ramp down from x = 12 to the floor.
    BodySettings ramp;
    ramp.motion = Motion::Static;
    const real angle = 0.349;
    ramp.shape = Shape::box({2.2, 0.1, 1.5});
    ramp.orientation = Quaternion(Eigen::AngleAxis<real>(-angle, Vector3::UnitZ()));
    ramp.position = Vector3(12 + 2.2 * std::cos(angle), 1.5 - 2.2 * std::sin(angle), 0) -
                    0.1 * Vector3(std::sin(angle), std::cos(angle), 0);
    world.addBody(ramp);
    level.crate = block(world, {17, 0, -0.3}, {17.6, 0.6, 0.3}, Motion::Dynamic, 15);
    block(world, {24, 0, 0}, {27, 1, 3});  // a block 1 m high: jumped onto
    BodySettings goal;
    goal.motion = Motion::Static;
    goal.sensor = true;
    goal.shape = Shape::box({0.5, 1, 1.5});
    goal.position = {26, 2, 1.5};
    level.goal = world.addBody(goal);
    return level;
}

// The script: from `time` on, walk at `velocity` (an upward part jumps).
struct Command {
    real time;
    Vector3 velocity;
};

}  // namespace

int main() {
    World world;
    const Level level = build(world);
    CharacterSettings settings;
    const CharacterId player = world.addCharacter(settings);
    const Command script[] = {
        {0.0, {2, 0, 0}},    // up the stairs, to the landing's edge
        {2.9, {0, 0, 0}},    // wait for the platform
        {3.0, {1, 0, 0}},    // onto it
        {4.0, {0, 0, 0}},    // ride
        {5.2, {2, 0, 0}},    // off onto the far landing, down the ramp, push the crate
        {11.0, {0, 0, 1.5}}, // step aside
        {12.0, {2, 0, 0}},
        {13.6, {2, 5, 0}},   // jump onto the block
        {13.7, {2, 0, 0}},
        {15.0, {0, 0, 0}},
    };
    const real dt = 1.0 / 60;
    std::size_t next = 0;
    for (int step = 0; step < 16 * 60; ++step) {
        const real t = step * dt;
        if (next < sizeof(script) / sizeof(script[0]) && t >= script[next].time - 1e-9)
            world.setCharacterVelocity(player, script[next++].velocity);
        // The platform shuttles between x = 6 and x = 8 (its near end), 2 s each way, from t = 3.5 s.
        const real phase = std::fmod(std::max(real(0), t - 3.5), real(4));
        world.setVelocity(level.platform, {t < 3.5 ? 0.0 : (phase < 2 ? 1.0 : -1.0), 0, 0});
        world.step(dt);
        for (const SensorEvent &e : world.events().sensorBegins)
            if (e.sensor == level.goal && e.body == world.character(player).body)
                std::printf("t = %5.2f s  the player reaches the goal\n", t + dt);
        if ((step + 1) % 30 == 0) {
            const CharacterState s = world.character(player);
            std::printf("t = %5.2f s  feet (%6.2f, %5.2f, %5.2f)  %s  crate at x = %.2f\n", t + dt, s.position.x(),
                        s.position.y(), s.position.z(), s.onGround ? "on the ground" : "airborne     ",
                        world.body(level.crate).getPosition().x());
        }
    }
    return 0;
}
