// A game's physics layer on an installed cyclone: a fixed-step loop fed by uneven frame
// times, interpolated transforms for the renderer, contact events as impact sounds, a
// ray cast to pick what is under the cursor, an overlap query for an explosion, and
// debug drawing into a line buffer. Frames are simulated (no window) so that the run is
// quick and checks what it did: the exit status is 0 when everything behaved.
#include <cmath>
#include <cstdio>
#include <vector>

#include <cyclone/world.h>

using namespace cyclone;

namespace {

// The renderer's side of debug drawing: here, a line buffer that is only counted.
struct LineBuffer : DebugDraw {
    int lines = 0;
    void line(const Vector3 &, const Vector3 &, const DebugColor &) override { ++lines; }
};

const char *label(const World &world, BodyId id) {
    return world.name(id).empty() ? "crate" : world.name(id).c_str();
}

BodyId addCrate(World &world, const Vector3 &position) {
    BodySettings crate;
    crate.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    crate.position = position;
    crate.mass = 10;
    return world.addBody(crate);
}

}  // namespace

int main() {
    World world;
    BodySettings ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    const BodyId groundId = world.addBody(ground);

    std::vector<BodyId> crates;
    for (int i = 0; i < 3; ++i) crates.push_back(addCrate(world, Vector3(0, 0.5 + i, 0)));
    BodySettings ball;
    ball.name = "ball";
    ball.shape = Shape::sphere(0.25);
    ball.mass = 2;
    ball.position = Vector3(-6, 1.5, 0);
    ball.material.restitution = 0.3;
    const BodyId ballId = world.addBody(ball);

    FixedStepper stepper(world);  // 60 Hz steps, at most 5 per frame
    LineBuffer debugLines;
    int impacts = 0;
    int framesDrawn = 0;
    double simulated = 0;
    bool exploded = false;
    std::vector<BodyId> blast;

    // Uneven frame times, about 75 fps, with a 0.4 s stall at frame 200.
    for (int frame = 0; frame < 420; ++frame) {
        const double frameSeconds = frame == 200 ? 0.4 : (frame % 3 == 0 ? 0.016 : 0.0125);
        stepper.advance(
            frameSeconds,
            [&](real) {
                // Input acts for one step at a time: the player pushes the ball for 0.3 s.
                if (simulated < 0.3) world.addForce(ballId, Vector3(80, 0, 0));
            },
            [&](real dt) {
                // Each step's events: impact sounds, loud as the approach speed.
                simulated += dt;
                for (const ContactBegin &c : world.events().contactBegins) {
                    if (c.approachSpeed < 1) continue;
                    ++impacts;
                    std::printf("t=%5.2f s  impact %-6s / %-6s at %.1f m/s\n", simulated, label(world, c.a),
                                label(world, c.b), c.approachSpeed);
                }
            });

        // An explosion at t = 4 s: every dynamic body within 2 m of the ball is pushed away.
        if (!exploded && simulated >= 4) {
            exploded = true;
            const Vector3 centre = world.body(ballId).getPosition();
            QueryFilter dynamicOnly;
            dynamicOnly.staticBodies = false;
            world.overlap(Shape::sphere(2), centre, Quaternion::Identity(), blast, dynamicOnly);
            for (BodyId id : blast) {
                const Vector3 away = world.body(id).getPosition() - centre;
                if (away.norm() > 1e-6) world.applyImpulse(id, 20 * away.normalized());  // wakes the body
            }
            std::printf("t=%5.2f s  explosion pushes %zu bodies\n", simulated, blast.size());
        }

        // Rendering: every body at its interpolated pose, and the debug lines.
        for (BodyId id : world.bodies()) {
            float model[16];
            stepper.glTransform(id, model);  // column-major, for glUniformMatrix4fv
        }
        debugLines.lines = 0;
        world.debugDraw(debugLines);
        ++framesDrawn;
    }

    // Picking: what is under a cursor looking straight down onto the origin from 10 m?
    const std::optional<RayHit> pick = world.rayCast(Vector3(0.1, 10, 0.1), -Vector3::UnitY());
    std::printf("%d frames, %llu steps (%.2f s simulated, %.2f s dropped), %d impacts, %d debug lines\n",
                framesDrawn, static_cast<unsigned long long>(stepper.totalSteps()), simulated,
                stepper.droppedSeconds(), impacts, debugLines.lines);
    if (pick)
        std::printf("picked %s at %.3f m, normal (%.2f %.2f %.2f)\n",
                    pick->body == groundId ? "the ground" : "a body", pick->distance, pick->normal.x(),
                    pick->normal.y(), pick->normal.z());

    // What must have happened: the 0.4 s stall was capped at 5 steps; the ball hit the
    // stack; the explosion found the ball at least; the pick hit something below 10 m.
    bool ok = true;
    ok = ok && stepper.droppedSeconds() > 0.3;
    ok = ok && impacts >= 1;
    ok = ok && !blast.empty();
    ok = ok && pick.has_value() && pick->distance <= 10 && pick->normal.y() > 0.5;
    ok = ok && debugLines.lines > 0;
    std::printf("%s\n", ok ? "game layer OK" : "game layer FAILED");
    return ok ? 0 : 1;
}
