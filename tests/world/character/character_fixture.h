// A level for character tests: boxes placed by their corners, a character, steps.
#pragma once

#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {

/// The default character (cyclone::CharacterSettings): radius 0.3 m, 1.8 m tall, 45 degree
/// slopes, 0.35 m steps, 70 kg. Its capsule keeps 1 mm from what it touches.
inline constexpr real kCharacterRadius = 0.3;
inline constexpr real kCharacterHeight = 1.8;
inline constexpr real kStepHeight = 0.35;
inline constexpr real kCharacterMass = 70;
/// The gap the capsule keeps, m (character_motion.cpp).
inline constexpr real kSkin = 0.001;

struct CharacterLevel {
    World world;

    explicit CharacterLevel(const WorldSettings &settings = noSleep()) : world(settings) {}

    /// A static plane y = 0 with this friction.
    BodyId floor(real friction = 0.6) {
        BodySettings s;
        s.motion = Motion::Static;
        s.shape = Shape::plane(Vector3::UnitY(), 0);
        s.material.friction = friction;
        return world.addBody(s);
    }

    /// A box between corners `low` and `high`, static unless `motion` says otherwise.
    BodyId block(const Vector3 &low, const Vector3 &high, Motion motion = Motion::Static, real mass = 1,
                 real friction = 0.6) {
        BodySettings s;
        s.motion = motion;
        s.shape = Shape::box((high - low) / 2);
        s.position = (low + high) / 2;
        s.mass = mass;
        s.material.friction = friction;
        return world.addBody(s);
    }

    /// A static ramp rising along +x at `angle` from the foot line x = footX on y = 0, with
    /// its top surface `length` m long (the box reaches 0.5 m below the surface).
    BodyId ramp(real footX, real angle, real length) {
        BodySettings s;
        s.motion = Motion::Static;
        s.shape = Shape::box({length / 2, 0.25, 2});
        s.orientation = Quaternion(Eigen::AngleAxis<real>(angle, Vector3::UnitZ()));
        const Vector3 along(std::cos(angle), std::sin(angle), 0), normal(-std::sin(angle), std::cos(angle), 0);
        s.position = Vector3(footX, 0, 0) + along * (length / 2) - normal * 0.25;
        return world.addBody(s);
    }

    CharacterId character(const Vector3 &feet) {
        CharacterSettings s;
        s.position = feet;
        return world.addCharacter(s);
    }

    Vector3 feet(CharacterId id) const { return world.character(id).position; }

    /// Steps `steps` times at kDt walking at `velocity`.
    void walk(CharacterId id, const Vector3 &velocity, int steps) {
        world.setCharacterVelocity(id, velocity);
        for (int i = 0; i < steps; ++i) world.step(kDt);
    }
};

}  // namespace cyclone::test
