// The character API: refusals that name the function, field and value and change
// nothing; the capsule seen by rays and sensors; removal; the same result on any number
// of threads.
#include <cstring>
#include <functional>
#include <string>

#include "character/character_fixture.h"

namespace cyclone::test {
namespace {

// Expects `call` to throw InvalidArgument naming `function` and `field` and holding `value`.
void expectRefused(const std::function<void()> &call, const std::string &function, const std::string &field,
                   const std::string &value) {
    try {
        call();
        ADD_FAILURE() << function << " accepted a bad " << field;
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), function);
        EXPECT_EQ(e.field(), field);
        EXPECT_NE(std::string(e.what()).find(value), std::string::npos) << e.what();
    }
}

TEST(CharacterApi, RefusesBadSettingsAndAddsNothing) {
    CharacterLevel level;
    level.floor();
    const auto refuses = [&](const std::function<void(CharacterSettings &)> &spoil, const std::string &field,
                             const std::string &value) {
        CharacterSettings s;
        spoil(s);
        expectRefused([&] { level.world.addCharacter(s); }, "World::addCharacter", field, value);
        EXPECT_EQ(level.world.bodyCount(), 1u) << field;
    };
    refuses([](CharacterSettings &s) { s.position.x() = kNaN; }, "position", "nan");
    refuses([](CharacterSettings &s) { s.position.y() = 2e12; }, "position", "2e+12");
    refuses([](CharacterSettings &s) { s.position.y() = 1e12; }, "position", "1e+12");  // its centre 0.9 m beyond
    refuses([](CharacterSettings &s) { s.radius = 0; }, "radius", "0");
    refuses([](CharacterSettings &s) { s.radius = -1; }, "radius", "-1");
    refuses([](CharacterSettings &s) { s.height = 0.5; }, "height", "0.5");
    refuses([](CharacterSettings &s) { s.height = kInf; }, "height", "inf");
    refuses([](CharacterSettings &s) { s.maxSlope = 0; }, "maxSlope", "0");
    refuses([](CharacterSettings &s) { s.maxSlope = 2; }, "maxSlope", "2");
    refuses([](CharacterSettings &s) { s.stepHeight = -0.1; }, "stepHeight", "-0.1");
    refuses([](CharacterSettings &s) { s.stepHeight = 1.6; }, "stepHeight", "1.6");
    refuses([](CharacterSettings &s) { s.mass = 0; }, "mass", "0");
    refuses([](CharacterSettings &s) { s.mass = kNaN; }, "mass", "nan");
    refuses([](CharacterSettings &s) { s.layer = 32; }, "layer", "32");
    refuses([](CharacterSettings &s) { s.layer = -1; }, "layer", "-1");
}

TEST(CharacterApi, RefusesStaleHandlesAndBadVelocities) {
    CharacterLevel level;
    level.floor();
    const CharacterId walker = level.character({0, 0, 0});
    expectRefused([&] { level.world.setCharacterVelocity(walker, {kNaN, 0, 0}); }, "World::setCharacterVelocity",
                  "desired", "nan");
    EXPECT_TRUE(level.world.character(walker).velocity.isZero(0));
    const BodyId capsule = level.world.character(walker).body;
    expectRefused([&] { level.world.removeBody(capsule); }, "World::removeBody", "id", "capsule");
    EXPECT_TRUE(level.world.contains(capsule));
    level.world.removeCharacter(walker);
    EXPECT_FALSE(level.world.contains(capsule));
    EXPECT_EQ(level.world.bodyCount(), 1u);
    expectRefused([&] { level.world.character(walker); }, "World::character", "id", "no character");
    expectRefused([&] { level.world.removeCharacter(walker); }, "World::removeCharacter", "id", "no character");
    expectRefused([&] { level.world.setCharacterVelocity(walker, {1, 0, 0}); }, "World::setCharacterVelocity", "id",
                  "no character");
    expectRefused([&] { level.world.character(CharacterId()); }, "World::character", "id", "no character");
    // The slot is reused with a new generation: the old handle stays stale.
    const CharacterId next = level.character({0, 0, 0});
    EXPECT_EQ(next.index, walker.index);
    EXPECT_NE(next, walker);
    expectRefused([&] { level.world.character(walker); }, "World::character", "id", "no character");
}

TEST(CharacterApi, ItsCapsuleIsAnUprightKinematicBody) {
    // The capsule stands from the feet to 1.8 m: its centre 0.9 m above the feet, its axis
    // (local z) along +y; a ray along +x at the height of its middle meets its side at
    // x = -r, 4.7 m from an origin at x = -5.
    CharacterLevel level;
    level.floor();
    const CharacterId walker = level.character({0, 0, 0});
    const CharacterState state = level.world.character(walker);
    EXPECT_EQ(level.world.motion(state.body), Motion::Kinematic);
    EXPECT_NEAR(level.world.body(state.body).getPosition().y(), kCharacterHeight / 2, 1e-12);
    const Vector3 axis = level.world.body(state.body).getOrientation() * Vector3::UnitZ();
    EXPECT_NEAR(axis.y(), 1, 1e-12);
    const auto hit = level.world.rayCast({-5, 0.9, 0}, {1, 0, 0});
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->body, state.body);
    EXPECT_NEAR(hit->distance, 5 - kCharacterRadius, 1e-9);
}

TEST(CharacterApi, RaysHitItWhereItWalked) {
    // After walking 1 s at 3 m/s the capsule is at x = 3: a ray down from above its head
    // meets its top, 1.8 m above the feet (the hemisphere's pole on the axis).
    CharacterLevel level;
    level.floor();
    const CharacterId walker = level.character({0, 0, 0});
    level.walk(walker, {3, 0, 0}, 60);
    const Vector3 feet = level.feet(walker);
    EXPECT_NEAR(feet.x(), 3, 0.05);
    const auto hit = level.world.rayCast(feet + Vector3(0, 5, 0), {0, -1, 0});
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->body, level.world.character(walker).body);
    EXPECT_NEAR(hit->point.y(), feet.y() + kCharacterHeight, 1e-6);
}

TEST(CharacterApi, ASensorReportsItEnteringAZone) {
    // A sensor zone over x in [3, 5]; walking at 2 m/s from x = 0 the capsule's side
    // (x + r) reaches x = 3 at t = 2.7 / 2 = 1.35 s, step 81; the sensor sees it in the
    // step after it moved there (sensors are tested before the characters move).
    CharacterLevel level;
    level.floor();
    BodySettings zone;
    zone.motion = Motion::Static;
    zone.sensor = true;
    zone.shape = Shape::box({1, 1, 1});
    zone.position = {4, 1, 0};
    const BodyId sensor = level.world.addBody(zone);
    const CharacterId walker = level.character({0, 0, 0});
    level.world.setCharacterVelocity(walker, {2, 0, 0});
    int entered = -1;
    for (int i = 1; i <= 120 && entered < 0; ++i) {
        level.world.step(kDt);
        for (const SensorEvent &e : level.world.events().sensorBegins)
            if (e.sensor == sensor && e.body == level.world.character(walker).body) entered = i;
    }
    EXPECT_NEAR(entered, 82, 1);
}

TEST(CharacterApi, SameResultOnAnyNumberOfThreads) {
    // Characters walking among falling and pushed crates: the same bits on 1 and 4 threads.
    const auto run = [](int threads) {
        WorldSettings settings;
        settings.threads = threads;
        CharacterLevel level(settings);
        level.floor();
        for (int k = 0; k < 6; ++k)
            level.block({1.0 + k, 0.5 * k, -0.3}, {1.5 + k, 0.5 * k + 0.5, 0.3}, Motion::Dynamic, 5);
        const CharacterId a = level.character({0, 0, 0});
        const CharacterId b = level.character({0, 0, 2});
        level.world.setCharacterVelocity(a, {2, 0, 0});
        level.world.setCharacterVelocity(b, {2, 0, -1});
        for (int i = 0; i < 120; ++i) level.world.step(kDt);
        std::vector<Vector3> out{level.feet(a), level.feet(b)};
        for (BodyId id : level.world.bodies()) out.push_back(level.world.body(id).getPosition());
        return out;
    };
    const std::vector<Vector3> one = run(1), four = run(4);
    ASSERT_EQ(one.size(), four.size());
    for (std::size_t i = 0; i < one.size(); ++i)
        EXPECT_EQ(std::memcmp(one[i].data(), four[i].data(), sizeof(real) * 3), 0) << i;
}

}  // namespace
}  // namespace cyclone::test
