// The "character" mode: a character of the World (cyclone/world/character.h) walked with
// W, A, S, D along the camera's heading and jumping with Space; C turns it on at the
// camera's target and off. No window or GL here.
#pragma once

#include <optional>

#include "cyclone/world/world.h"

namespace cyclone::viewer {

/// The keys that move the character, held this frame.
struct WalkKeys {
    bool forward = false, back = false, left = false, right = false, jump = false;
};

class CharacterMode {
public:
    /// Walking speed, m/s.
    static constexpr real kSpeed = 4;
    /// Jump speed, m/s.
    static constexpr real kJump = 5;

    bool on() const { return id_.has_value(); }
    /// Adds a character with its feet at `feet`; throws InvalidArgument as World::addCharacter.
    void start(World &world, const Vector3 &feet) { id_ = world.addCharacter(settingsAt(feet)); }
    /// Removes the character (if the World still has it) and turns the mode off.
    void stop(World &world);
    /// Forgets the character of a World that was rebuilt (restart, another scene).
    void forget() { id_.reset(); }
    /// Sets the character's velocity from the keys, `heading` (the camera's forward, any
    /// length) giving W's direction across up.
    void drive(World &world, const WalkKeys &keys, const Vector3 &heading) const;
    /// Where the camera should look: the character's chest, m.
    Vector3 focus(const World &world) const;

private:
    static CharacterSettings settingsAt(const Vector3 &feet) {
        CharacterSettings s;
        s.position = feet;
        return s;
    }
    std::optional<CharacterId> id_;
};

}  // namespace cyclone::viewer
