// The World's character calls: validation, adding and removing characters, their state.
#include <cmath>
#include <string>

#include "character/character_record.h"
#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {

namespace detail {

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

}  // namespace detail

namespace {

constexpr real kQuarterTurn = 1.5707963267948966;  // pi / 2, rad

void validateCharacter(const char *function, const CharacterSettings &s) {
    using namespace detail;
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

}  // namespace

CharacterId World::addCharacter(const CharacterSettings &settings) {
    validateCharacter("World::addCharacter", settings);
    Impl &w = *impl_;
    const Vector3 up = detail::characterUp(w.settings.gravity);
    detail::CharacterRecord c;
    c.settings = settings;
    c.capsule = detail::characterCapsule(settings);
    c.feet = settings.position;
    c.groundNormal = up;
    BodySettings body;
    body.shape = c.capsule;
    body.motion = Motion::Kinematic;
    body.position = detail::capsuleCentre(c, up, settings.position);
    body.orientation = detail::uprightFor(up);
    body.layer = settings.layer;
    body.collidesWith = settings.collidesWith;
    if (!(body.position.cwiseAbs().maxCoeff() <= detail::kMaxCoordinate))
        detail::refuse("World::addCharacter", "position",
                       "puts the capsule's centre beyond 1e12 m of the origin, got " + detail::show(settings.position));
    c.body = addBody(body);

    std::uint32_t index;
    if (!w.characters.free.empty()) {
        index = w.characters.free.back();
        w.characters.free.pop_back();
    } else {
        index = static_cast<std::uint32_t>(w.characters.records.size());
        w.characters.records.emplace_back();
    }
    c.generation = w.characters.records[index].generation;
    c.alive = true;
    w.characters.records[index] = c;
    return {index, c.generation};
}

void World::removeCharacter(CharacterId id) {
    Impl &w = *impl_;
    detail::CharacterRecord &c = w.characters.record(id, "World::removeCharacter");
    c.alive = false;  // first, so that removeBody takes its capsule
    ++c.generation;
    w.characters.free.push_back(id.index);
    removeBody(c.body);
}

void World::setCharacterVelocity(CharacterId id, const Vector3 &desired) {
    static const char *function = "World::setCharacterVelocity";
    detail::CharacterRecord &c = impl_->characters.record(id, function);
    detail::requireFinite(function, "desired", desired);
    c.desired = desired;
}

CharacterState World::character(CharacterId id) const {
    const detail::CharacterRecord &c = impl_->characters.record(id, "World::character");
    CharacterState state;
    state.position = c.feet;
    state.velocity = c.velocity;
    state.onGround = c.onGround;
    state.groundBody = c.groundBody;
    state.groundNormal = c.groundNormal;
    state.body = c.body;
    return state;
}

}  // namespace cyclone
