// Rollback: two peers step the same scene, a ball knocked into a wall of boxes by the
// player's impulses. Peer A applies each impulse in the frame it was given; peer B
// receives it 6 frames late, as over a network: it then goes back to the state it saved
// at the start of that frame (World::restoreState), applies the impulse, and steps the 6
// frames again. Both must end bit for bit the same; the example says whether they do,
// and what the states cost: bytes per frame, time saving and restoring.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

#include "cyclone/world.h"

namespace {

using namespace cyclone;
using Clock = std::chrono::steady_clock;

constexpr real kDt = 1.0 / 60;
constexpr int kFrames = 360;
constexpr int kDelay = 6;  // frames between an input and its arrival at peer B

// A wall of boxes 6 wide and 5 high on the ground, and the player's ball before it.
struct Peer {
    World world;
    std::vector<BodyId> bodies;
    BodyId player;

    Peer() {
        BodySettings ground;
        ground.motion = Motion::Static;
        ground.shape = Shape::plane(Vector3::UnitY(), 0);
        world.addBody(ground);
        for (int row = 0; row < 5; ++row) {
            for (int column = 0; column < 6; ++column) {
                BodySettings box;
                box.shape = Shape::box(Vector3(0.25, 0.25, 0.25));
                box.position = Vector3(-1.5 + 0.52 * column + 0.26 * (row % 2), 0.25 + 0.5 * row, 0);
                bodies.push_back(world.addBody(box));
            }
        }
        BodySettings ball;
        ball.shape = Shape::sphere(0.3);
        ball.mass = 4;
        ball.position = Vector3(0, 0.3, 4);
        player = world.addBody(ball);
        bodies.push_back(player);
    }
};

// The player's input of a frame: an impulse on the ball, every 30 frames (none in the
// last second, so that every input has arrived before the end).
bool inputOf(int frame, Vector3 &impulse) {
    if (frame % 30 != 10 || frame > kFrames - 60) return false;
    const real side = (frame / 30) % 3 - 1.0;
    impulse = Vector3(3 * side, 2, -25);
    return true;
}

// Whether two peers' bodies have the same bits: poses, velocities, sleep.
bool identical(const Peer &a, const Peer &b) {
    for (std::size_t k = 0; k < a.bodies.size(); ++k) {
        const RigidBody &x = a.world.body(a.bodies[k]);
        const RigidBody &y = b.world.body(b.bodies[k]);
        const Vector3 vx[] = {x.getPosition(), x.getVelocity(), x.getRotation()};
        const Vector3 vy[] = {y.getPosition(), y.getVelocity(), y.getRotation()};
        if (std::memcmp(vx, vy, sizeof vx) != 0 || x.getAwake() != y.getAwake()) return false;
        const Quaternion qx = x.getOrientation(), qy = y.getOrientation();
        if (std::memcmp(qx.coeffs().data(), qy.coeffs().data(), 4 * sizeof(real)) != 0) return false;
    }
    return true;
}

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

}  // namespace

int main() {
    Peer a, b;
    // Peer B's state at the start of each of the last kDelay + 1 frames, and the inputs it
    // has received, by frame.
    std::vector<std::vector<std::uint8_t>> saved(kDelay + 1);
    std::vector<char> known(kFrames, 0);
    std::size_t savedBytes = 0;
    int saves = 0, restores = 0, replayed = 0;
    double saveMs = 0, restoreMs = 0;

    // Peer B steps frame f: saves its state, applies the input of f if it has it, steps.
    const auto stepB = [&](int frame) {
        auto start = Clock::now();
        saved[frame % (kDelay + 1)] = b.world.saveState();
        saveMs += msSince(start);
        savedBytes += saved[frame % (kDelay + 1)].size();
        ++saves;
        Vector3 impulse;
        if (known[frame] && inputOf(frame, impulse)) b.world.applyImpulse(b.player, impulse);
        b.world.step(kDt);
    };

    for (int frame = 0; frame < kFrames; ++frame) {
        Vector3 impulse;
        if (inputOf(frame, impulse)) a.world.applyImpulse(a.player, impulse);
        a.world.step(kDt);

        stepB(frame);
        // The input of frame - kDelay arrives: B goes back to that frame and plays on.
        const int late = frame - kDelay;
        if (late >= 0 && inputOf(late, impulse)) {
            known[late] = 1;
            auto start = Clock::now();
            b.world.restoreState(saved[late % (kDelay + 1)]);
            restoreMs += msSince(start);
            ++restores;
            for (int replay = late; replay <= frame; ++replay, ++replayed) stepB(replay);
        }
    }

    const bool same = identical(a, b);
    std::printf("frames: %d, inputs %d frames late, rollbacks: %d (%d frames stepped again)\n", kFrames, kDelay,
                restores, replayed);
    std::printf("state: %.0f bytes per frame (%zu bodies, %.0f bytes per body)\n",
                static_cast<double>(savedBytes) / saves, a.bodies.size() + 1,
                static_cast<double>(savedBytes) / saves / static_cast<double>(a.bodies.size() + 1));
    std::printf("saving: %.3f ms in all (%.4f ms per save); restoring: %.3f ms in all (%.4f ms per restore)\n", saveMs,
                saveMs / saves, restoreMs, restores ? restoreMs / restores : 0.0);
    std::printf("peers identical at the end: %s\n", same ? "yes" : "NO");
    return same ? 0 : 1;
}
