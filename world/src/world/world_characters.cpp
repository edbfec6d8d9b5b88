// The World's character members: each passes what it reads to character/characters.cpp.
#include "character/character_record.h"
#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {

CharacterId World::addCharacter(const CharacterSettings &settings) {
    static const char *function = "World::addCharacter";
    detail::checkCharacter(function, settings);
    Impl &w = *impl_;
    detail::CharacterRecord c = detail::newCharacter(settings, w.settings.gravity);
    c.body = addBody(detail::capsuleBody(function, c, w.settings.gravity));
    return w.characters.add(c);
}

void World::removeCharacter(CharacterId id) {
    Impl &w = *impl_;
    removeBody(w.characters.remove(id, "World::removeCharacter"));
}

void World::setCharacterVelocity(CharacterId id, const Vector3 &desired) {
    static const char *function = "World::setCharacterVelocity";
    detail::CharacterRecord &c = impl_->characters.record(id, function);
    detail::requireFinite(function, "desired", desired);
    c.desired = desired;
}

CharacterState World::character(CharacterId id) const { return impl_->characters.state(id, "World::character"); }

}  // namespace cyclone
