/// \file
/// Characters: upright capsules that the World walks over its bodies inside World::step
/// (World::addCharacter). Each is a kinematic capsule body of the World (CharacterState::body),
/// so rays, shape casts, overlaps and sensors see it, and dynamic bodies rest on it; the
/// World moves it by casting the capsule (collide and slide), not by the contact solver.
///
/// Each step, after the bodies have moved: the character is carried by what it stood on
/// (the ground body's move over the step, turning included), walks at the velocity set by
/// World::setCharacterVelocity along the ground's plane, climbs steps up to stepHeight onto
/// walkable ground, slides along walls and down slopes steeper than maxSlope, falls under
/// the world's gravity while airborne, and keeps to the ground (snapped down by up to
/// stepHeight) while it walks down steps and slopes. It pushes the dynamic bodies it walks
/// into with at most its weight (mass times |gravity|), and a dynamic body that runs into
/// it exchanges momentum with it as with a body of `mass` (WorldState::step: before the solve).
#pragma once

#include <cstdint>
#include <optional>

#include "cyclone/core.h"
#include "cyclone/world/settings.h"

namespace cyclone {

/// How a character is made. Up is against the world's gravity (+y when gravity is zero).
struct CharacterSettings {
    /// The feet: the lowest point of the capsule, world space, m (finite, within 1e12 m).
    Vector3 position = Vector3::Zero();
    /// Capsule radius, m, > 0.
    real radius = 0.3;
    /// Feet to head, m, > 2 radius.
    real height = 1.8;
    /// Steepest walkable ground, rad, in (0, pi/2): steeper ground is a wall it slides down.
    real maxSlope = 0.7854;
    /// Highest step it climbs, m, in [0, height - radius]; also how far it is kept down
    /// to the ground when it walks down steps and slopes.
    real stepHeight = 0.35;
    /// Mass, kg, in [kMinMass, kMaxMass]: it pushes dynamic bodies with at most its weight,
    /// and bodies that run into it share their momentum with this mass.
    real mass = 70;
    /// Collision layer of the character and its capsule, in [0, 31].
    int layer = 0;
    /// The layers it collides with (bit k for layer k): it walks on and is stopped by
    /// the bodies of these layers whose own mask holds its layer.
    std::uint32_t collidesWith = kAllLayers;
};

/// A character's state after the last step (World::character).
struct CharacterState {
    /// The feet, world space, m.
    Vector3 position = Vector3::Zero();
    /// How fast the feet moved over the last step, carrying included, m/s.
    Vector3 velocity = Vector3::Zero();
    /// Whether it stands on walkable ground.
    bool onGround = false;
    /// The body it stands on, when onGround.
    std::optional<BodyId> groundBody;
    /// Unit normal of the ground it stands on (up when airborne).
    Vector3 groundNormal = Vector3::UnitY();
    /// Its capsule in the World: a kinematic body that rays and sensors see. Moved by the
    /// World; removed with the character (World::removeBody refuses it).
    BodyId body;
};

/// Handle of a character in a World. Stale handles (of removed characters) are refused. A
/// default-constructed CharacterId names no character.
struct CharacterId {
    /// Slot of the character in its World; reused after the character is removed.
    std::uint32_t index = UINT32_MAX;
    /// Incremented each time the slot is reused, so that an old handle stays stale.
    std::uint32_t generation = 0;
    /// True when both name the same character.
    bool operator==(const CharacterId &other) const { return index == other.index && generation == other.generation; }
    /// True when they name different characters.
    bool operator!=(const CharacterId &other) const { return !(*this == other); }
};

}  // namespace cyclone
