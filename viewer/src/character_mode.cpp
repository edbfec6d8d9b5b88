// The "character" mode's walking: keys to a velocity along the camera's heading.
#include "character_mode.h"

namespace cyclone::viewer {

void CharacterMode::stop(World &world) {
    if (id_) {
        try {
            world.removeCharacter(*id_);
        } catch (const InvalidArgument &) {
            // The World was rebuilt under it: nothing to remove.
        }
    }
    id_.reset();
}

void CharacterMode::drive(World &world, const WalkKeys &keys, const Vector3 &heading) const {
    if (!id_) return;
    const Vector3 up = Vector3::UnitY();
    Vector3 ahead = heading - up * heading.dot(up);
    ahead = ahead.norm() > 1e-9 ? Vector3(ahead.normalized()) : Vector3(Vector3::UnitZ() * -1);
    const Vector3 side = ahead.cross(up);
    Vector3 walk = Vector3::Zero();
    if (keys.forward) walk += ahead;
    if (keys.back) walk -= ahead;
    if (keys.right) walk += side;
    if (keys.left) walk -= side;
    if (walk.norm() > 0) walk = walk.normalized() * kSpeed;
    if (keys.jump) walk += up * kJump;
    world.setCharacterVelocity(*id_, walk);
}

Vector3 CharacterMode::focus(const World &world) const {
    return world.character(*id_).position + Vector3(0, 1.2, 0);
}

}  // namespace cyclone::viewer
