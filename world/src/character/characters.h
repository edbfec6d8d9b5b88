// The World's characters (cyclone/world/character.h): their records, and the two points
// of a step at which they act.
//
// A character's capsule is a still kinematic body: the contact solver treats it as
// immovable (what falls on it rests on it), and the character moves it itself after the
// step, by casting it through the World (character_motion.cpp). Bodies that run into it
// are handled before the solve, as an inelastic collision with the character's mass
// (character_pushes.cpp), so that it is pushed instead of standing like a wall.
#pragma once

#include <optional>
#include <vector>

#include "cyclone/world/world.h"

namespace cyclone::detail {

struct WorldState;

/// One character: its settings, capsule and motion state.
struct CharacterRecord {
    CharacterSettings settings;
    Shape capsule;                     ///< The capsule's shape, along local z.
    BodyId body;                       ///< Its kinematic body.
    std::uint32_t generation = 0;
    bool alive = false;
    Vector3 feet = Vector3::Zero();     ///< Lowest point of the capsule, m.
    Vector3 desired = Vector3::Zero();  ///< Velocity asked by World::setCharacterVelocity, m/s.
    real rise = 0;                      ///< Speed along up while airborne (a jump, a fall), m/s.
    Vector3 push = Vector3::Zero();     ///< Velocity across up given by bodies that ran into it, m/s.
    Vector3 velocity = Vector3::Zero(); ///< How fast the feet moved over the last step, m/s.
    bool onGround = false;
    std::optional<BodyId> groundBody;
    Vector3 groundNormal = Vector3::UnitY();
    Vector3 groundPoint = Vector3::Zero();  ///< Where it touches the ground, m.
    Matrix4 groundStart = Matrix4::Identity();  ///< The ground body's pose when the step began.
};

/// The characters of a World, indexed by CharacterId::index; removed slots are reused.
class Characters {
public:
    std::vector<CharacterRecord> records;
    std::vector<std::uint32_t> free;

    /// Whether there is no live character (the step then does nothing for them).
    bool empty() const { return records.size() == free.size(); }
    /// The character `id` names; refused with `function`'s name when it names none.
    CharacterRecord &record(CharacterId id, const char *function);
    const CharacterRecord &record(CharacterId id, const char *function) const;
    /// Whether `body` is the capsule of a live character.
    bool owns(BodyId body) const;

    /// Before the solve: keeps the pose of each character's ground body, and shares the
    /// momentum of the dynamic bodies about to run into a character (character_pushes.cpp).
    void beginStep(WorldState &world, const World &queries, real dt);
    /// After the bodies moved: moves each character, in index order, and its capsule
    /// (character_motion.cpp).
    void update(WorldState &world, const World &queries, real dt);

private:
    std::vector<BodyId> near_;  ///< Scratch of beginStep: the bodies near a character.
};

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
QueryFilter characterFilter(const WorldState &world, const CharacterRecord &c);

}  // namespace cyclone::detail
