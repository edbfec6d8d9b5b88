// A small fixture for World tests: create bodies in one line, simulate, predict.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "cyclone/world.h"

namespace cyclone::test {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDt = 1.0 / 60.0;
/// Standard gravity, m/s^2 (the World's default gravity is (0, -kG, 0)).
inline constexpr double kG = 9.81;
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// The default settings with sleep off: what a test of per-step work wants.
inline WorldSettings noSleep() {
    WorldSettings settings;
    settings.sleep = false;
    return settings;
}

/// Whether two bodies' positions, orientations, velocities and awake flags are the same
/// to the bit: what the thread-count tests compare.
inline bool sameBits(const RigidBody &x, const RigidBody &y) {
    const auto same = [](const auto &u, const auto &v) { return std::memcmp(u.data(), v.data(), sizeof(real) * u.size()) == 0; };
    return same(x.getPosition(), y.getPosition()) && same(x.getOrientation().coeffs(), y.getOrientation().coeffs()) &&
           same(x.getVelocity(), y.getVelocity()) && same(x.getRotation(), y.getRotation()) &&
           x.getAwake() == y.getAwake();
}

/// Adds a static body of `shape` at `position` on collision layer `layer`.
inline BodyId addStatic(World &world, const Shape &shape, const Vector3 &position, int layer = 0) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = shape;
    s.position = position;
    s.layer = layer;
    return world.addBody(s);
}

struct WorldFixture {
    World world;

    explicit WorldFixture(const WorldSettings &settings = WorldSettings()) : world(settings) {}

    BodyId ground(real friction = 0.6) {
        BodySettings s;
        s.name = "ground";
        s.motion = Motion::Static;
        s.shape = Shape::plane(Vector3::UnitY(), 0);
        s.material.friction = friction;
        return world.addBody(s);
    }

    BodyId box(const Vector3 &position, const Vector3 &half = Vector3(0.5, 0.5, 0.5), real mass = 1,
               real friction = 0.6) {
        BodySettings s;
        s.shape = Shape::box(half);
        s.position = position;
        s.mass = mass;
        s.material.friction = friction;
        return world.addBody(s);
    }

    BodyId sphere(const Vector3 &position, real radius = 0.5, real mass = 1) {
        BodySettings s;
        s.shape = Shape::sphere(radius);
        s.position = position;
        s.mass = mass;
        return world.addBody(s);
    }

    BodyId staticBox(const Vector3 &position, const Vector3 &half, const Quaternion &q = Quaternion::Identity(),
                     real friction = 0.6) {
        BodySettings s;
        s.motion = Motion::Static;
        s.shape = Shape::box(half);
        s.position = position;
        s.orientation = q;
        s.material.friction = friction;
        return world.addBody(s);
    }

    /// Joins a and b by a joint of `type` at `anchor` (world space), its other settings the
    /// defaults.
    JointId joint(JointType type, BodyId a, BodyId b, const Vector3 &anchor) {
        JointSettings s;
        s.type = type;
        s.a = a;
        s.b = b;
        s.anchor = anchor;
        return world.addJoint(s);
    }

    /// Steps for `seconds` at `dt`.
    void simulate(double seconds, double dt = kDt) {
        const int steps = static_cast<int>(std::lround(seconds / dt));
        for (int i = 0; i < steps; ++i) world.step(dt);
    }

    bool awake(BodyId id) const { return world.body(id).getAwake(); }
    Vector3 position(BodyId id) const { return world.body(id).getPosition(); }
};

}  // namespace cyclone::test
