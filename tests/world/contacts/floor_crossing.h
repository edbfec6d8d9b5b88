// Bodies sent across a floor (a plane, a mesh, a height field): the track of their height
// and vertical speed, for the tests that a surface of triangles has no bumps.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {

/// The heights and vertical speeds of a body after each step, and how far it went.
struct FloorTrack {
    std::vector<real> height;
    std::vector<real> verticalSpeed;
    real travelled = 0;
};

/// Rolls or slides `shape` (turned by `orientation`) across the static `floor` (placed
/// at `floorAt`) from rest height `rest` at `velocity` (rolling without slipping when
/// `roll`: w = (up x v) / r) for `seconds` at 60 Hz, without sleep, from (-8.3, rest,
/// -2.1); both bodies of friction `friction`.
inline FloorTrack crossFloor(const Shape &floor, const Shape &shape, const Quaternion &orientation, real rest,
                             const Vector3 &velocity, bool roll, real friction, double seconds,
                             const Vector3 &floorAt = Vector3::Zero()) {
    WorldFixture f(noSleep());
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = floor;
    ground.position = floorAt;
    ground.material.friction = friction;
    f.world.addBody(ground);
    BodySettings s;
    s.shape = shape;
    s.orientation = orientation;
    s.position = Vector3(-8.3, rest, -2.1);
    s.velocity = velocity;
    s.rotation = roll ? Vector3(Vector3::UnitY().cross(velocity) / rest) : Vector3::Zero();
    s.mass = 1;
    s.material.friction = friction;
    const BodyId id = f.world.addBody(s);
    FloorTrack track;
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < steps; ++i) {
        f.world.step(kDt);
        track.height.push_back(f.position(id).y());
        track.verticalSpeed.push_back(f.world.body(id).getVelocity().y());
    }
    track.travelled = (f.position(id) - s.position).norm();
    return track;
}

/// The largest |height - rest| of a track.
inline real heightError(const FloorTrack &t, real rest) {
    real e = 0;
    for (real y : t.height) e = std::max(e, std::abs(y - rest));
    return e;
}

/// The largest |vy| from step `from` on: a body put down exactly touching a floor starts
/// with the gravity of its first sub-steps (up to g dt = 0.16 m/s) before its contact
/// holds it, on a plane as on a mesh.
inline real verticalSpeed(const FloorTrack &t, std::size_t from = 0) {
    real e = 0;
    for (std::size_t i = from; i < t.verticalSpeed.size(); ++i) e = std::max(e, std::abs(t.verticalSpeed[i]));
    return e;
}

}  // namespace cyclone::test
