// Body user data (BodySettings::userData) comes back with every contact and sensor event
// and query hit; each solved pair's normal impulse of the step is in the events.
#include "world_fixture.h"

namespace cyclone::test {
namespace {

BodySettings withData(Shape shape, const Vector3 &position, std::uint64_t userData, bool isStatic = false) {
    BodySettings s;
    s.shape = std::move(shape);
    s.position = position;
    s.userData = userData;
    s.motion = isStatic ? Motion::Static : Motion::Dynamic;
    return s;
}

// A 2 kg box resting on the ground: every sub-step the contacts cancel what gravity adds,
// m g h, so over the step they give m g dt = 2 * 9.81 / 60 = 0.327 N s; one entry, the
// pair (ground, box), with both bodies' user data.
TEST(ContactImpulses, ARestingBoxTakesItsWeightTimesTheStep) {
    WorldFixture f(noSleep());
    const BodyId ground = f.world.addBody(withData(Shape::plane(Vector3::UnitY(), 0), Vector3::Zero(), 7, true));
    BodySettings s = withData(Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(0, 0.5, 0), 42);
    s.mass = 2;
    const BodyId box = f.world.addBody(s);
    f.simulate(1);
    const std::vector<ContactImpulse> &impulses = f.world.events().contactImpulses;
    ASSERT_EQ(impulses.size(), 1u);
    EXPECT_EQ(impulses[0].a, ground);
    EXPECT_EQ(impulses[0].b, box);
    EXPECT_EQ(impulses[0].userDataA, 7u);
    EXPECT_EQ(impulses[0].userDataB, 42u);
    EXPECT_NEAR(impulses[0].normalImpulse, 2 * kG * kDt, 0.01 * 2 * kG * kDt);
}

// Without contacts there are no entries; pairs come sorted by the bodies' indices, one
// per pair.
TEST(ContactImpulses, OneEntryPerSolvedPairInIndexOrder) {
    WorldFixture f(noSleep());
    f.simulate(0.1);
    EXPECT_TRUE(f.world.events().contactImpulses.empty());
    f.ground();
    for (int level = 0; level < 3; ++level) f.box(Vector3(0, 0.5 + level, 0));
    f.simulate(0.5);
    const std::vector<ContactImpulse> &impulses = f.world.events().contactImpulses;
    ASSERT_EQ(impulses.size(), 3u);
    for (std::size_t k = 1; k < impulses.size(); ++k) {
        const bool ordered = impulses[k - 1].a.index < impulses[k].a.index ||
                             (impulses[k - 1].a.index == impulses[k].a.index && impulses[k - 1].b.index < impulses[k].b.index);
        EXPECT_TRUE(ordered) << k;
    }
    // The bottom pair carries the three boxes, the top one only the top box: 3 m g dt and m g dt.
    EXPECT_NEAR(impulses[0].normalImpulse, 3 * kG * kDt, 0.03 * kG * kDt);
    EXPECT_NEAR(impulses[2].normalImpulse, kG * kDt, 0.01 * kG * kDt);
}

// Contact begin and end, sensor begin and end, ray and shape cast hits all carry the
// bodies' user data; setUserData replaces it.
TEST(UserData, ComesBackWithEventsAndHits) {
    WorldSettings settings = noSleep();
    WorldFixture f(settings);
    const BodyId ground = f.world.addBody(withData(Shape::plane(Vector3::UnitY(), 0), Vector3::Zero(), 7, true));
    BodySettings zone = withData(Shape::box(Vector3(2, 2, 2)), Vector3(0, 2, 0), 9, true);
    zone.sensor = true;
    f.world.addBody(zone);
    const BodyId box = f.world.addBody(withData(Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(0, 0.5, 0), 42));
    EXPECT_EQ(f.world.userData(box), 42u);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().contactBegins.size(), 1u);
    EXPECT_EQ(f.world.events().contactBegins[0].userDataA, 7u);
    EXPECT_EQ(f.world.events().contactBegins[0].userDataB, 42u);
    // The zone sees the box and the ground (a sensor sees static bodies too).
    ASSERT_EQ(f.world.events().sensorBegins.size(), 2u);
    for (const SensorEvent &e : f.world.events().sensorBegins) {
        EXPECT_EQ(e.sensorUserData, 9u);
        EXPECT_EQ(e.bodyUserData, e.body == box ? 42u : 7u);
    }

    const std::optional<RayHit> ray = f.world.rayCast(Vector3(0, 10, 0), Vector3(0, -1, 0));
    ASSERT_TRUE(ray);
    EXPECT_EQ(ray->body, box);
    EXPECT_EQ(ray->userData, 42u);
    const std::optional<ShapeCastHit> cast =
        f.world.shapeCast(Shape::sphere(0.2), Vector3(0, 10, 0), Quaternion::Identity(), Vector3(0, -20, 0));
    ASSERT_TRUE(cast);
    EXPECT_EQ(cast->userData, 42u);

    f.world.setUserData(ground, 8);
    EXPECT_EQ(f.world.userData(ground), 8u);
    f.world.removeBody(box);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().contactEnds.size(), 1u);
    EXPECT_EQ(f.world.events().contactEnds[0].userDataA, 7u) << "as it was when the contact began";
    EXPECT_EQ(f.world.events().contactEnds[0].userDataB, 42u);
    ASSERT_EQ(f.world.events().sensorEnds.size(), 1u);
    EXPECT_EQ(f.world.events().sensorEnds[0].bodyUserData, 42u);
}

}  // namespace
}  // namespace cyclone::test
