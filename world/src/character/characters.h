// The World's characters (cyclone/world/character.h): their records, and the two points
// of a step at which they act.
//
// A character's capsule is a still kinematic body: the contact solver treats it as
// immovable (what falls on it rests on it), and the character moves it itself after the
// step, by casting it through the World's queries (character_motion.cpp). Bodies that run
// into it are handled before the solve, as an inelastic collision with the character's
// mass (character_pushes.cpp), so that it is pushed instead of standing like a wall.
#pragma once

#include <vector>

#include "cyclone/world/world.h"
#include "queries/queries.h"
#include "world/body_store.h"
#include "world/body_transitions.h"

namespace cyclone::detail {

struct CharacterRecord;

/// The characters of a World, indexed by CharacterId::index; removed slots are reused.
class Characters {
public:
    std::vector<CharacterRecord> records;  ///< Complete in character_record.h.
    std::vector<std::uint32_t> free;

    Characters();
    ~Characters();
    /// Whether there is no live character (the step then does nothing for them).
    bool empty() const;
    /// The character `id` names; refused with `function`'s name when it names none.
    CharacterRecord &record(CharacterId id, const char *function);
    const CharacterRecord &record(CharacterId id, const char *function) const;
    /// Stores a new live character in a free slot (the last freed first) and names it.
    CharacterId add(CharacterRecord c);
    /// Ends the character `id` names (refused with `function`'s name when it names none)
    /// and gives its capsule, which the World then removes.
    BodyId remove(CharacterId id, const char *function);
    /// What World::character reports of the character `id` names.
    CharacterState state(CharacterId id, const char *function) const;
    /// Whether `body` is the capsule of a live character.
    bool owns(BodyId body) const;

    /// Before the solve: keeps the pose of each character's ground body, and shares the
    /// momentum of the dynamic bodies about to run into a character, found by casting
    /// through `queries` (on `bodies`) (character_pushes.cpp).
    void beginStep(const Vector3 &gravity, BodyStore &bodies, const QueryScene &queries, real dt);
    /// After the bodies moved: moves each character, in index order, and its capsule,
    /// casting through `queries` (on `bodies`); wakes the bodies it pushes or stands on
    /// and refits its capsule's box through `transitions` (character_motion.cpp).
    void update(const Vector3 &gravity, BodyStore &bodies, const QueryScene &queries, BodyTransitions transitions,
                real dt);

private:
    std::vector<BodyId> near_;  ///< Scratch of beginStep: the bodies near a character.
};

}  // namespace cyclone::detail
