// A character's record (character/characters.h holds the list): its settings, capsule and
// motion state, and the helpers its motion shares.
#pragma once

#include <optional>

#include "character/characters.h"

namespace cyclone::detail {

/// One character: its settings, capsule and motion state.
struct CharacterRecord {
    CharacterSettings settings;
    Shape capsule;                     ///< The capsule's shape, along local z.
    BodyId body;                       ///< Its kinematic body.
    std::uint32_t generation = 0;
    bool alive = false;
    Vector3 feet = Vector3::Zero();     ///< Lowest point of the capsule, m.
    Vector3 desired = Vector3::Zero();  ///< Velocity asked by World::setCharacterVelocity, m/s.
    Vector3 flight = Vector3::Zero();   ///< Velocity of its own while airborne (a jump, a fall, a slide down a steep slope), m/s.
    Vector3 push = Vector3::Zero();     ///< Velocity across up given by bodies that ran into it, m/s.
    Vector3 velocity = Vector3::Zero(); ///< How fast the feet moved over the last step, m/s.
    bool onGround = false;
    std::optional<BodyId> groundBody;
    Vector3 groundNormal = Vector3::UnitY();
    Vector3 groundPoint = Vector3::Zero();  ///< Where it touches the ground, m.
    Matrix4 groundStart = Matrix4::Identity();  ///< The ground body's pose when the step began.
};

/// A character's capsule: along local z, its cylinder the height less the two caps.
inline Shape characterCapsule(const CharacterSettings &s) { return Shape::capsule(s.radius, s.height - 2 * s.radius); }
/// Up for the characters: against gravity, +y when there is none.
Vector3 characterUp(const Vector3 &gravity);
/// The turn that stands a capsule (along local z) along `up`.
Quaternion uprightFor(const Vector3 &up);
/// The centre of a character's capsule whose feet are at `feet`.
inline Vector3 capsuleCentre(const CharacterRecord &c, const Vector3 &up, const Vector3 &feet) {
    return feet + up * (c.settings.height / 2);
}
/// What a character's casts consider: the layers of its mask whose bodies' masks hold its
/// layer, its own capsule and sensors left out.
QueryFilter characterFilter(const BodyStore &bodies, const CharacterRecord &c);

/// Refuses, with `function`'s name, settings out of their ranges (cyclone/world/character.h).
void checkCharacter(const char *function, const CharacterSettings &settings);
/// A character standing at its settings' position, its capsule not yet added.
CharacterRecord newCharacter(const CharacterSettings &settings, const Vector3 &gravity);
/// The kinematic body of a character's capsule, standing along up; refused, with
/// `function`'s name, when its centre is beyond 1e12 m of the origin.
BodySettings capsuleBody(const char *function, const CharacterRecord &c, const Vector3 &gravity);

}  // namespace cyclone::detail
