// The World's characters: their checks, records and slots, and the helpers their motion
// shares. The World's character members (world/world_characters.cpp) call these.
#include <cmath>
#include <string>

#include "character/character_record.h"
#include "world/free_slots.h"
#include "world/validation.h"

namespace cyclone::detail {
namespace {

constexpr real kQuarterTurn = 1.5707963267948966;  // pi / 2, rad

}  // namespace

Characters::Characters() = default;
Characters::~Characters() = default;

bool Characters::empty() const { return records.size() == free.size(); }

CharacterRecord &Characters::record(CharacterId id, const char *function) {
    if (id.index >= records.size() || !records[id.index].alive || records[id.index].generation != id.generation)
        refuse(function, "id", "names no character of this world (stale or default handle)");
    return records[id.index];
}

const CharacterRecord &Characters::record(CharacterId id, const char *function) const {
    return const_cast<Characters *>(this)->record(id, function);
}

CharacterId Characters::add(CharacterRecord c) {
    const std::uint32_t index = takeSlot(records, free);
    c.generation = records[index].generation;
    c.alive = true;
    records[index] = c;
    return {index, c.generation};
}

BodyId Characters::remove(CharacterId id, const char *function) {
    const BodyId capsule = record(id, function).body;
    freeSlot(records, free, id.index);  // first, so that World::removeBody takes its capsule
    return capsule;
}

CharacterState Characters::state(CharacterId id, const char *function) const {
    const CharacterRecord &c = record(id, function);
    CharacterState state;
    state.position = c.feet;
    state.velocity = c.velocity;
    state.onGround = c.onGround;
    state.groundBody = c.groundBody;
    state.groundNormal = c.groundNormal;
    state.body = c.body;
    return state;
}

bool Characters::owns(BodyId body) const {
    for (const CharacterRecord &c : records)
        if (c.alive && c.body == body) return true;
    return false;
}

Vector3 characterUp(const Vector3 &gravity) {
    const real length = gravity.norm();
    return length > 0 ? Vector3(-gravity / length) : Vector3(Vector3::UnitY());
}

Quaternion uprightFor(const Vector3 &up) { return Quaternion::FromTwoVectors(Vector3::UnitZ(), up); }

QueryFilter characterFilter(const BodyStore &bodies, const CharacterRecord &c) {
    QueryFilter filter;
    filter.layers = c.settings.collidesWith;
    filter.ignore = c.body;
    const int layer = c.settings.layer;
    filter.accept = [&bodies, layer](BodyId id) { return (bodies[id.index].collidesWith >> layer & 1u) != 0; };
    return filter;
}

void checkCharacter(const char *function, const CharacterSettings &s) {
    requirePlace(function, "position", s.position);
    requirePositive(function, "radius", s.radius);
    if (!std::isfinite(s.height) || !(s.height > 2 * s.radius))
        refuse(function, "height", "must be finite and > 2 radius = " + show(2 * s.radius) + ", got " + show(s.height));
    if (!(s.maxSlope > 0 && s.maxSlope < kQuarterTurn))
        refuse(function, "maxSlope", "must be in (0, pi/2) rad, got " + show(s.maxSlope));
    if (!(s.stepHeight >= 0 && s.stepHeight <= s.height - s.radius))
        refuse(function, "stepHeight",
               "must be in [0, height - radius = " + show(s.height - s.radius) + "], got " + show(s.stepHeight));
    if (!(s.mass >= kMinMass && s.mass <= kMaxMass))
        refuse(function, "mass", "must be in [1e-100, 1e100] kg, got " + show(s.mass));
    if (s.layer < 0 || s.layer > 31) refuse(function, "layer", "must be in [0, 31], got " + std::to_string(s.layer));
}

CharacterRecord newCharacter(const CharacterSettings &settings, const Vector3 &gravity) {
    CharacterRecord c;
    c.settings = settings;
    c.capsule = characterCapsule(settings);
    c.feet = settings.position;
    c.groundNormal = characterUp(gravity);
    return c;
}

BodySettings capsuleBody(const char *function, const CharacterRecord &c, const Vector3 &gravity) {
    const Vector3 up = characterUp(gravity);
    BodySettings body;
    body.shape = c.capsule;
    body.motion = Motion::Kinematic;
    body.position = capsuleCentre(c, up, c.settings.position);
    body.orientation = uprightFor(up);
    body.layer = c.settings.layer;
    body.collidesWith = c.settings.collidesWith;
    if (!(body.position.cwiseAbs().maxCoeff() <= kMaxCoordinate))
        refuse(function, "position",
               "puts the capsule's centre beyond 1e12 m of the origin, got " + show(c.settings.position));
    return body;
}

}  // namespace cyclone::detail
