// Sensors (BodySettings::sensor): begin and end events at the steps free fall predicts,
// sleeping bodies seen, nothing pushed or woken, layers deciding what a sensor sees, and
// the refusals.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


BodySettings sensorBox(const Vector3 &position, const Vector3 &half) {
    BodySettings s;
    s.name = "zone";
    s.motion = Motion::Static;
    s.sensor = true;
    s.shape = Shape::box(half);
    s.position = position;
    return s;
}

BodySettings ball(const Vector3 &position, real radius = 0.25) {
    BodySettings s;
    s.shape = Shape::sphere(radius);
    s.position = position;
    return s;
}

// Every sensor event of a run, one string per event: "step:begin:sensor:body".
struct EventRecorder {
    std::vector<std::string> lines;
    int begins = 0;
    int ends = 0;
    void record(const World &world, int step) {
        for (const SensorEvent &e : world.events().sensorEnds) {
            lines.push_back(std::to_string(step) + ":end:" + std::to_string(e.sensor.index) + ":" +
                            std::to_string(e.body.index));
            ++ends;
        }
        for (const SensorEvent &e : world.events().sensorBegins) {
            lines.push_back(std::to_string(step) + ":begin:" + std::to_string(e.sensor.index) + ":" +
                            std::to_string(e.body.index));
            ++begins;
        }
    }
};

// A ball of radius 0.25 dropped from rest at y = 5 through a static trigger box spanning
// y in [1.5, 2.5]. It overlaps the box while its centre is in (1.25, 2.75): from a drop of
// 2.25 m to one of 3.75 m. Free fall takes t = sqrt(2 d / g): 0.6773 s (40.64 steps of
// 1/60 s) and 0.8744 s (52.46 steps). The integrator's drop after k steps of 4 sub-steps,
// g dt^2 k (4k + 1) / 8, exceeds free fall's by g dt^2 k / 8 (1.4 cm here), which moves
// neither boundary: 2.194 m after 40 steps and 2.304 m after 41; 3.702 m after 52 and
// 3.845 m after 53. The ball first overlaps after step 41, and sensors test the poses at
// a step's start, so the begin comes with step 42 and the end with step 54.
TEST(Sensors, ABallFallingThroughATriggerBeginsAndEndsAtTheFreeFallSteps) {
    WorldFixture f(noSleep());
    const BodyId zone = f.world.addBody(sensorBox(Vector3(0, 2, 0), Vector3(1, 0.5, 1)));
    const BodyId falling = f.world.addBody(ball(Vector3(0, 5, 0)));
    const int enter = static_cast<int>(std::ceil(std::sqrt(2 * 2.25 / kG) / kDt)) + 1;
    const int leave = static_cast<int>(std::ceil(std::sqrt(2 * 3.75 / kG) / kDt)) + 1;
    ASSERT_EQ(enter, 42);
    ASSERT_EQ(leave, 54);
    int begins = 0, ends = 0;
    for (int step = 1; step <= 70; ++step) {
        f.world.step(kDt);
        const WorldEvents &events = f.world.events();
        for (const SensorEvent &e : events.sensorBegins) {
            ++begins;
            EXPECT_EQ(step, enter);
            EXPECT_EQ(e.sensor, zone);
            EXPECT_EQ(e.body, falling);
        }
        for (const SensorEvent &e : events.sensorEnds) {
            ++ends;
            EXPECT_EQ(step, leave);
            EXPECT_EQ(e.sensor, zone);
            EXPECT_EQ(e.body, falling);
        }
        // The sensor pushes nothing: no contact, and the ball falls freely (v += g h per
        // sub-step, exact to rounding; the drop as above).
        EXPECT_EQ(f.world.stats().contacts, 0);
        EXPECT_EQ(f.world.stats().manifolds, 0);
        EXPECT_TRUE(events.contactBegins.empty());
        EXPECT_NEAR(f.world.body(falling).getVelocity().y(), -kG * step * kDt, 1e-9);
        EXPECT_NEAR(f.position(falling).y(), 5 - kG * kDt * kDt * step * (4.0 * step + 1) / 8, 1e-9);
        EXPECT_EQ(f.world.body(falling).getVelocity().x(), 0);
    }
    EXPECT_EQ(begins, 1);
    EXPECT_EQ(ends, 1);
}

// A body asleep inside a static sensor added later: begin in the first step, and nothing
// woken. From then on neither body is in the step's walk: the pair is not tested at all,
// and the overlap stays.
TEST(Sensors, ASleepingBodyInsideASensorAddedLaterBeginsInTheFirstStep) {
    WorldFixture f;
    BodySettings sleeper = ball(Vector3(0, 0, 0));
    sleeper.awake = false;
    const BodyId body = f.world.addBody(sleeper);
    f.simulate(0.5);
    ASSERT_FALSE(f.awake(body));
    const BodyId zone = f.world.addBody(sensorBox(Vector3(0, 0.5, 0), Vector3(1, 1, 1)));
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    EXPECT_EQ(f.world.events().sensorBegins[0].sensor, zone);
    EXPECT_EQ(f.world.events().sensorBegins[0].body, body);
    EXPECT_FALSE(f.awake(body));
    EXPECT_TRUE(f.world.events().wokeUp.empty());
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        EXPECT_TRUE(f.world.events().sensorBegins.empty());
        EXPECT_TRUE(f.world.events().sensorEnds.empty());
        EXPECT_EQ(f.world.stats().sensorPairs, 0) << "nothing awake: nothing tested";
    }
    // Removing the sensor ends the overlap (reported by the next step, with its stale id).
    f.world.removeBody(zone);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorEnds.size(), 1u);
    EXPECT_EQ(f.world.events().sensorEnds[0].sensor, zone);
    EXPECT_EQ(f.world.events().sensorEnds[0].body, body);
    EXPECT_FALSE(f.world.contains(zone));
}

// At load the order does not matter: a sensor added before or after the sleeping body, a
// static body and an awake one inside it all begin in the first step, sorted by index.
TEST(Sensors, BodiesInsideASensorAtLoadBeginInTheFirstStep) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    BodySettings sleeper = ball(Vector3(-0.5, 0, 0));
    sleeper.awake = false;
    const BodyId first = f.world.addBody(sleeper);
    const BodyId zone = f.world.addBody(sensorBox(Vector3::Zero(), Vector3(1, 1, 1)));
    const BodyId wall = f.staticBox(Vector3(0.9, 0, 0), Vector3(0.2, 0.2, 0.2));
    sleeper.position = Vector3(0, 0.5, 0);
    const BodyId second = f.world.addBody(sleeper);
    const BodyId awake = f.world.addBody(ball(Vector3(0, -0.5, 0)));
    f.world.addBody(ball(Vector3(5, 0, 0)));  // outside
    f.world.step(kDt);
    const std::vector<SensorEvent> &begins = f.world.events().sensorBegins;
    ASSERT_EQ(begins.size(), 4u);
    const BodyId expected[] = {first, wall, second, awake};
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(begins[k].sensor, zone);
        EXPECT_EQ(begins[k].body, expected[k]) << k;
    }
}

// A dynamic sensor falls like any body and through others: through a box resting asleep
// on the ground, which it neither pushes nor wakes, and into the ground.
TEST(Sensors, ADynamicSensorFallsThroughWithoutWakingOrPushing) {
    WorldFixture f;
    const BodyId ground = f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(3);
    ASSERT_FALSE(f.awake(box));
    const Vector3 rest = f.position(box);
    BodySettings probe = ball(Vector3(0, 3, 0), 0.2);
    probe.sensor = true;
    const BodyId sensor = f.world.addBody(probe);
    int boxBegins = 0, groundBegins = 0;
    for (int step = 1; step <= 60; ++step) {
        f.world.step(kDt);
        for (const SensorEvent &e : f.world.events().sensorBegins) {
            EXPECT_EQ(e.sensor, sensor);
            boxBegins += e.body == box;
            groundBegins += e.body == ground;
        }
        EXPECT_FALSE(f.awake(box)) << step;
        EXPECT_NEAR(f.world.body(sensor).getVelocity().y(), -kG * step * kDt, 1e-9);
    }
    EXPECT_EQ(boxBegins, 1);
    EXPECT_EQ(groundBegins, 1);
    EXPECT_EQ(f.position(box), rest);
    EXPECT_LT(f.position(sensor).y(), 0) << "it fell into the ground: 1 s of free fall from 3 m";
}

// Sensors filter both ways, as contacts do: a sensor on layer 3 that sees layer 1 reports
// the layer-1 ball (whose mask, every layer, holds 3), not the layer-1 ghost whose own mask
// is empty, nor the layer-0 ball. A new mask ends what it no longer sees. (Radius 0.25
// balls 1 m apart: only the zone's pairs overlap in the broadphase.)
TEST(Sensors, SensorsFilterBothWays) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    settings.sleep = false;
    WorldFixture f(settings);
    BodySettings zoneSettings = sensorBox(Vector3::Zero(), Vector3(2, 1, 1));
    zoneSettings.layer = 3;
    zoneSettings.collidesWith = 1u << 1;
    const BodyId zone = f.world.addBody(zoneSettings);
    const BodyId plain = f.world.addBody(ball(Vector3(-1, 0, 0)));
    BodySettings seen = ball(Vector3(1, 0, 0));
    seen.layer = 1;
    const BodyId layered = f.world.addBody(seen);
    BodySettings ghost = ball(Vector3(0, 0, 0));
    ghost.layer = 1;
    ghost.collidesWith = 0;
    f.world.addBody(ghost);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    EXPECT_EQ(f.world.events().sensorBegins[0].body, layered);
    EXPECT_EQ(f.world.stats().sensorPairs, 1);
    EXPECT_EQ(f.world.stats().filteredPairs, 2) << "the layer-0 ball's and the ghost's pairs never reach a test";
    f.world.setCollisionFilter(zone, 3, 1u << 0);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorEnds.size(), 1u);
    EXPECT_EQ(f.world.events().sensorEnds[0].body, layered);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    EXPECT_EQ(f.world.events().sensorBegins[0].body, plain);
}

// A body that changes its own mask to leave out the sensor's layer stops being seen (the
// overlap ends at once, reported with the next step's events), and is seen again when its
// mask holds that layer again.
TEST(Sensors, ABodysOwnMaskHidesItFromASensor) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    settings.sleep = false;
    WorldFixture f(settings);
    BodySettings zoneSettings = sensorBox(Vector3::Zero(), Vector3(1, 1, 1));
    zoneSettings.layer = 2;
    const BodyId zone = f.world.addBody(zoneSettings);
    const BodyId body = f.world.addBody(ball(Vector3::Zero()));
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    f.world.setCollisionFilter(body, 0, kAllLayers & ~(1u << 2));
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorEnds.size(), 1u);
    EXPECT_EQ(f.world.events().sensorEnds[0].sensor, zone);
    EXPECT_EQ(f.world.events().sensorEnds[0].body, body);
    EXPECT_TRUE(f.world.events().sensorBegins.empty());
    f.world.step(kDt);
    EXPECT_TRUE(f.world.events().sensorBegins.empty()) << "still hidden";
    f.world.setCollisionFilter(body, 0, kAllLayers);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    EXPECT_EQ(f.world.events().sensorBegins[0].body, body);
}

// Sensors never see sensors, and a pair rule hides a body from a sensor.
TEST(Sensors, SensorsDoNotSeeSensorsNorBodiesKeptApart) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    const BodyId zone = f.world.addBody(sensorBox(Vector3::Zero(), Vector3(1, 1, 1)));
    BodySettings other = sensorBox(Vector3(0.5, 0, 0), Vector3(1, 1, 1));
    other.name = "other";
    other.motion = Motion::Dynamic;
    f.world.addBody(other);
    const BodyId body = f.world.addBody(ball(Vector3(0, 0, 0)));
    f.world.setPairCollision(zone, body, false);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u) << "only the other sensor sees the ball";
    EXPECT_NE(f.world.events().sensorBegins[0].sensor, zone);
    f.world.setPairCollision(zone, body, true);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    EXPECT_EQ(f.world.events().sensorBegins[0].sensor, zone);
}

// Removing a body inside a sensor ends the overlap; its id is stale in the event.
TEST(Sensors, RemovingABodyEndsItsOverlaps) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    const BodyId zone = f.world.addBody(sensorBox(Vector3::Zero(), Vector3(1, 1, 1)));
    const BodyId body = f.world.addBody(ball(Vector3::Zero()));
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorBegins.size(), 1u);
    f.world.removeBody(body);
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().sensorEnds.size(), 1u);
    EXPECT_EQ(f.world.events().sensorEnds[0].sensor, zone);
    EXPECT_EQ(f.world.events().sensorEnds[0].body, body);
    f.world.step(kDt);
    EXPECT_TRUE(f.world.events().sensorEnds.empty());
}

// Rays and overlap queries pass through sensors unless the filter asks for them.
TEST(Sensors, QueriesPassThroughSensorsUnlessAsked) {
    WorldFixture f;
    const BodyId zone = f.world.addBody(sensorBox(Vector3(0, 0, 5), Vector3(1, 1, 1)));
    EXPECT_FALSE(f.world.rayCast(Vector3::Zero(), Vector3::UnitZ(), 100));
    QueryFilter filter;
    filter.sensors = true;
    const auto hit = f.world.rayCast(Vector3::Zero(), Vector3::UnitZ(), 100, filter);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, zone);
    EXPECT_NEAR(hit->distance, 4, 1e-9);
}

// The same events in the same order whatever the thread count, run after run: balls
// raining through two sensors onto a pile.
TEST(Sensors, EventsAreTheSameWhateverTheThreads) {
    const auto run = [](int threads) {
        WorldSettings settings;
        settings.threads = threads;
        WorldFixture f(settings);
        f.ground();
        f.world.addBody(sensorBox(Vector3(0, 0.5, 0), Vector3(2, 0.5, 2)));
        BodySettings second = sensorBox(Vector3(0.5, 3, 0), Vector3(1, 0.5, 2));
        second.name = "second";
        f.world.addBody(second);
        for (int i = 0; i < 12; ++i) f.world.addBody(ball(Vector3(0.3 * (i % 4) - 0.5, 4 + 0.6 * i, 0.2 * (i % 3))));
        EventRecorder recorder;
        for (int step = 0; step < 240; ++step) {
            f.world.step(kDt);
            recorder.record(f.world, step);
        }
        return recorder;
    };
    const EventRecorder one = run(1);
    EXPECT_GE(one.begins, 24) << "every ball passes the upper sensor and lands in the lower one";
    EXPECT_EQ(run(1).lines, one.lines);
    EXPECT_EQ(run(3).lines, one.lines);
}

TEST(Sensors, BadSensorsAreRefused) {
    WorldFixture f;
    const BodyId body = f.box(Vector3::Zero());
    BodySettings mesh;
    mesh.sensor = true;
    mesh.shape = Shape::mesh({Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 0, 1)}, {{{0, 1, 2}}});
    try {
        f.world.addBody(mesh);
        FAIL() << "a mesh sensor on a dynamic body";
    } catch (const InvalidArgument &e) {
        EXPECT_NE(std::string(e.what()).find("World::addBody"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("shape.type"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("mesh"), std::string::npos);
    }
    mesh.motion = Motion::Kinematic;
    EXPECT_THROW(f.world.addBody(mesh), InvalidArgument);
    mesh.motion = Motion::Static;
    const BodyId staticMesh = f.world.addBody(mesh);
    EXPECT_TRUE(f.world.isSensor(staticMesh));
    EXPECT_FALSE(f.world.isSensor(body));
    EXPECT_EQ(f.world.bodyCount(), 2u);
    f.world.removeBody(staticMesh);
    EXPECT_THROW(f.world.isSensor(staticMesh), InvalidArgument);
}

}  // namespace
}  // namespace cyclone::test
