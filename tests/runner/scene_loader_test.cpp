// The loader: every field of the scene format lands in the Scene and in the World as given,
// and every default is the contract's.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>

#include "run_loop.h"
#include "scene_loader.h"
#include "scene_world.h"

namespace {

using namespace cyclone;
using namespace cyclone::scene;

constexpr const char *kBox = R"("shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]})";

std::string oneBody(const std::string &fields) {
    return std::string(R"({"bodies": [{"name": "b", )") + fields + "}]}";
}

void expectVector(const Vector3 &actual, double x, double y, double z) {
    EXPECT_DOUBLE_EQ(actual.x(), x);
    EXPECT_DOUBLE_EQ(actual.y(), y);
    EXPECT_DOUBLE_EQ(actual.z(), z);
}

TEST(SceneLoader, DefaultsAreTheContracts) {
    const Scene scene = loadScene(oneBody(kBox), "fallback");
    const WorldSettings defaults;
    EXPECT_EQ(scene.name, "fallback");
    EXPECT_DOUBLE_EQ(scene.dt, 1.0 / 60.0);
    EXPECT_EQ(scene.steps, 600);
    expectVector(scene.world.gravity, 0, -9.81, 0);
    EXPECT_TRUE(scene.world.sleep);
    EXPECT_EQ(scene.world.velocityIterations, defaults.velocityIterations);
    EXPECT_EQ(scene.world.positionIterations, defaults.positionIterations);
    EXPECT_EQ(scene.world.substeps, defaults.substeps);
    EXPECT_DOUBLE_EQ(scene.world.sleepEpsilon, defaults.sleepEpsilon);
    EXPECT_EQ(scene.world.integrator, Integrator::NewtonEuler);
    EXPECT_TRUE(scene.springs.empty());
    EXPECT_TRUE(scene.events.empty());

    ASSERT_EQ(scene.bodies.size(), 1u);
    EXPECT_FALSE(scene.bodies[0].settings.ccd);
    EXPECT_FALSE(scene.bodies[0].settings.inertia.has_value());
    SceneWorld built = buildWorld(scene);
    const BodyId id = built.ids[0];
    const RigidBody &body = built.world.body(id);
    EXPECT_EQ(built.world.name(id), "b");
    EXPECT_NE(built.world.motion(id), Motion::Static);
    EXPECT_DOUBLE_EQ(body.getMass(), 1.0);
    expectVector(body.getPosition(), 0, 0, 0);
    EXPECT_TRUE(body.getOrientation().isApprox(Quaternion::Identity()));
    expectVector(body.getVelocity(), 0, 0, 0);
    expectVector(body.getRotation(), 0, 0, 0);
    EXPECT_DOUBLE_EQ(body.getLinearDamping(), BodySettings().linearDamping);
    EXPECT_DOUBLE_EQ(body.getAngularDamping(), BodySettings().angularDamping);
    EXPECT_DOUBLE_EQ(built.world.material(id).friction, 0.6);
    EXPECT_DOUBLE_EQ(built.world.material(id).restitution, 0.0);
    EXPECT_TRUE(body.getCanSleep());
    EXPECT_TRUE(body.getAwake());
    // A unit box of 1 kg: I = m (b^2 + c^2) / 12 = 1/6 about each axis.
    const Matrix3 inertia = body.getInertiaTensor();
    EXPECT_NEAR(inertia(0, 0), 1.0 / 6.0, 1e-12);
    EXPECT_NEAR(inertia(1, 1), 1.0 / 6.0, 1e-12);
    EXPECT_NEAR(inertia(2, 2), 1.0 / 6.0, 1e-12);
}

TEST(SceneLoader, EverySettingLandsInTheWorld) {
    const Scene scene = loadScene(R"({
        "name": "all-settings",
        "settings": {"gravity": [1, -2, 3], "dt": 0.005, "steps": 42, "velocity_iterations": 17,
                     "position_iterations": 3, "substeps": 4, "sleep": false, "sleep_epsilon": 0.25,
                     "integrator": "newton-euler"},
        "bodies": []})",
                                  "x");
    EXPECT_EQ(scene.name, "all-settings");
    EXPECT_DOUBLE_EQ(scene.dt, 0.005);
    EXPECT_EQ(scene.steps, 42);
    SceneWorld built = buildWorld(scene);
    const WorldSettings &settings = built.world.settings();
    expectVector(settings.gravity, 1, -2, 3);
    EXPECT_EQ(settings.velocityIterations, 17);
    EXPECT_EQ(settings.positionIterations, 3);
    EXPECT_EQ(settings.substeps, 4);
    EXPECT_FALSE(settings.sleep);
    EXPECT_DOUBLE_EQ(settings.sleepEpsilon, 0.25);
    EXPECT_EQ(settings.integrator, Integrator::NewtonEuler);
}

TEST(SceneLoader, EveryIntegratorNameOfTheTableLoads) {
    for (const IntegratorName &entry : kIntegrators) {
        const Scene scene =
            loadScene(std::string(R"({"settings": {"integrator": ")") + entry.name + R"("}, "bodies": []})", "x");
        EXPECT_EQ(scene.world.integrator, entry.integrator) << entry.name;
    }
}

// One row per scheme: every Integrator has exactly one name, and names do not repeat.
TEST(SceneLoader, EveryIntegratorHasOneName) {
    const Integrator schemes[] = {Integrator::NewtonEuler, Integrator::NewtonEulerGyroscopic,
                                  Integrator::NewtonEulerImplicit, Integrator::MomentumConserving};
    for (Integrator scheme : schemes) {
        int rows = 0;
        for (const IntegratorName &entry : kIntegrators) rows += entry.integrator == scheme;
        EXPECT_EQ(rows, 1) << static_cast<int>(scheme);
    }
    EXPECT_EQ(std::size(kIntegrators), std::size(schemes));
    for (const IntegratorName &a : kIntegrators)
        for (const IntegratorName &b : kIntegrators)
            if (&a != &b) {
                EXPECT_STRNE(a.name, b.name);
            }
    const Scene scene = loadScene(R"({"settings": {"integrator": "newton-euler-gyroscopic"}, "bodies": []})", "x");
    EXPECT_EQ(scene.world.integrator, Integrator::NewtonEulerGyroscopic);
    // The contract's name for the second-order scheme.
    const Scene conserving = loadScene(R"({"settings": {"integrator": "momentum-conserving"}, "bodies": []})", "x");
    EXPECT_EQ(conserving.world.integrator, Integrator::MomentumConserving);
}

TEST(SceneLoader, SpringForceIsReadAndChecked) {
    const std::string bodies = R"("bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.1}}])";
    const Scene automatic = loadScene("{" + bodies + R"(, "springs": [{"a": "b", "b": null}]})", "x");
    ASSERT_EQ(automatic.springs.size(), 1u);
    EXPECT_EQ(automatic.springs[0].settings.force, SpringForce::Automatic);
    const Scene explicitForce =
        loadScene("{" + bodies + R"(, "springs": [{"a": "b", "b": null, "force": "explicit"}]})", "x");
    EXPECT_EQ(explicitForce.springs[0].settings.force, SpringForce::Explicit);
    try {
        loadScene("{" + bodies + R"(, "springs": [{"a": "b", "b": null, "force": "implicit"}]})", "x");
        FAIL() << "accepted force \"implicit\"";
    } catch (const std::exception &e) {
        EXPECT_NE(std::string(e.what()).find("springs[0].force"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("\"implicit\""), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, EveryBodyFieldLandsInTheWorld) {
    const Scene scene = loadScene(R"({"bodies": [
        {"name": "moving", "shape": {"type": "box", "half_extents": [0.5, 1, 1.5]}, "static": false,
         "mass": 2.5, "inertia": [[2, 0.1, 0], [0.1, 3, 0], [0, 0, 4]],
         "position": [1, 2, 3], "orientation": [0, 0, 0, 2], "velocity": [4, 5, 6], "rotation": [0.1, 0.2, 0.3],
         "linear_damping": 0.9, "angular_damping": 0.8, "friction": 0.25, "restitution": 0.5,
         "rolling_friction": 0.01, "spinning_friction": 0.02, "can_sleep": false, "awake": true, "ccd": true},
        {"name": "sleeper", "shape": {"type": "sphere", "radius": 0.5}, "position": [10, 0, 0],
         "can_sleep": true, "awake": false}]})",
                                  "x");
    const BodySettings &given = scene.bodies[0].settings;
    EXPECT_TRUE(given.ccd);
    ASSERT_TRUE(given.inertia.has_value());
    SceneWorld built = buildWorld(scene);
    const World &world = built.world;
    const BodyId id = built.ids[0];
    const RigidBody &body = world.body(id);
    EXPECT_EQ(world.name(id), "moving");
    EXPECT_NE(world.motion(id), Motion::Static);
    EXPECT_DOUBLE_EQ(body.getMass(), 2.5);
    Matrix3 inertia;
    inertia << 2, 0.1, 0, 0.1, 3, 0, 0, 0, 4;
    EXPECT_TRUE(body.getInertiaTensor().isApprox(inertia, 1e-12));
    expectVector(body.getPosition(), 1, 2, 3);
    // [0, 0, 0, 2] is normalised to a half turn about z.
    EXPECT_TRUE(body.getOrientation().isApprox(Quaternion(0, 0, 0, 1), 1e-15));
    expectVector(body.getVelocity(), 4, 5, 6);
    expectVector(body.getRotation(), 0.1, 0.2, 0.3);
    EXPECT_DOUBLE_EQ(body.getLinearDamping(), 0.9);
    EXPECT_DOUBLE_EQ(body.getAngularDamping(), 0.8);
    EXPECT_DOUBLE_EQ(world.material(id).friction, 0.25);
    EXPECT_DOUBLE_EQ(world.material(id).restitution, 0.5);
    EXPECT_DOUBLE_EQ(world.material(id).rollingFriction, 0.01);
    EXPECT_DOUBLE_EQ(world.material(id).spinningFriction, 0.02);
    EXPECT_FALSE(body.getCanSleep());
    EXPECT_TRUE(body.getAwake());

    const RigidBody &sleeper = world.body(built.ids[1]);
    EXPECT_TRUE(sleeper.getCanSleep());
    EXPECT_FALSE(sleeper.getAwake());
}

TEST(SceneLoader, StaticBodyHasInfiniteMass) {
    const Scene scene = loadScene(oneBody(std::string(kBox) + R"(, "static": true, "position": [0, -1, 0])"), "x");
    SceneWorld built = buildWorld(scene);
    EXPECT_EQ(built.world.motion(built.ids[0]), Motion::Static);
    EXPECT_FALSE(built.world.body(built.ids[0]).hasFiniteMass());
    expectVector(built.world.body(built.ids[0]).getPosition(), 0, -1, 0);
}

TEST(SceneLoader, OrientationIsNormalisedAndZeroMeansIdentity) {
    const auto orientation = [](const std::string &q) {
        return loadScene(oneBody(std::string(kBox) + R"(, "orientation": )" + q), "x").bodies[0].settings.orientation;
    };
    EXPECT_TRUE(orientation("[0, 0, 0, 0]").isApprox(Quaternion::Identity()));
    EXPECT_TRUE(orientation("[2, 0, 0, 0]").isApprox(Quaternion::Identity()));
    const Quaternion half = orientation("[1, 1, 1, 1]");
    EXPECT_NEAR(half.w(), 0.5, 1e-15);
    EXPECT_NEAR(half.x(), 0.5, 1e-15);
    EXPECT_NEAR(half.y(), 0.5, 1e-15);
    EXPECT_NEAR(half.z(), 0.5, 1e-15);
    // Huge components do not overflow the norm.
    EXPECT_TRUE(orientation("[0, 1e300, 0, 1e300]").isApprox(Quaternion(0, std::sqrt(0.5), 0, std::sqrt(0.5))));
}

TEST(SceneLoader, EveryShapeLandsInTheWorld) {
    const Scene scene = loadScene(R"({"bodies": [
        {"name": "box", "shape": {"type": "box", "half_extents": [0.1, 0.2, 0.3]}},
        {"name": "sphere", "shape": {"type": "sphere", "radius": 0.7}, "position": [5, 0, 0]},
        {"name": "capsule", "shape": {"type": "capsule", "radius": 0.3, "length": 1.25}, "position": [10, 0, 0]},
        {"name": "cylinder", "shape": {"type": "cylinder", "radius": 0.4, "length": 2}, "position": [15, 0, 0]},
        {"name": "convex", "shape": {"type": "convex", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.1, 0.1, 0.1]]},
         "position": [20, 0, 0]},
        {"name": "plane", "static": true, "shape": {"type": "plane", "normal": [0, 2, 0], "offset": -3}},
        {"name": "mesh", "static": true, "position": [0, -10, 0],
         "shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 1]], "triangles": [[0, 2, 1], [1, 2, 3]]}}
        ]})",
                                  "x");
    SceneWorld built = buildWorld(scene);
    const World &world = built.world;
    const auto shape = [&](std::size_t i) -> const Shape & { return world.shape(built.ids[i]); };

    EXPECT_EQ(shape(0).type, ShapeType::Box);
    expectVector(shape(0).halfExtents, 0.1, 0.2, 0.3);
    EXPECT_EQ(shape(1).type, ShapeType::Sphere);
    EXPECT_DOUBLE_EQ(shape(1).radius, 0.7);
    EXPECT_EQ(shape(2).type, ShapeType::Capsule);
    EXPECT_DOUBLE_EQ(shape(2).radius, 0.3);
    EXPECT_DOUBLE_EQ(shape(2).length, 1.25);
    EXPECT_EQ(shape(3).type, ShapeType::Cylinder);
    EXPECT_DOUBLE_EQ(shape(3).radius, 0.4);
    EXPECT_DOUBLE_EQ(shape(3).length, 2.0);
    EXPECT_EQ(shape(4).type, ShapeType::Convex);
    ASSERT_EQ(shape(4).vertices.size(), 5u);
    expectVector(shape(4).vertices[3], 0, 0, 1);
    EXPECT_EQ(shape(5).type, ShapeType::Plane);
    EXPECT_DOUBLE_EQ(shape(5).normal.normalized().y(), 1.0);
    EXPECT_DOUBLE_EQ(shape(5).offset, -3.0);
    EXPECT_EQ(world.motion(built.ids[5]), Motion::Static);
    EXPECT_EQ(shape(6).type, ShapeType::Mesh);
    ASSERT_EQ(shape(6).vertices.size(), 4u);
    ASSERT_EQ(shape(6).triangles.size(), 2u);
    EXPECT_EQ(shape(6).triangles[1], (std::array<int, 3>{1, 2, 3}));
    EXPECT_EQ(world.motion(built.ids[6]), Motion::Static);

    // A sphere's default inertia comes from the shape: 2/5 m r^2.
    EXPECT_NEAR(world.body(built.ids[1]).getInertiaTensor()(0, 0), 0.4 * 0.49, 1e-12);
}

TEST(SceneLoader, ExtraFieldsAreAllowed) {
    const Scene scene = loadScene(R"({"format": 2, "comment": {"any": [1, 2]},
        "settings": {"future_option": true},
        "bodies": [{"name": "b", "colour": "red", "shape": {"type": "sphere", "radius": 1, "detail": 3}}],
        "springs": [], "events": []})",
                                  "x");
    EXPECT_EQ(scene.bodies.size(), 1u);
}

TEST(SceneLoader, IntegralFloatsAreIntegers) {
    const Scene scene = loadScene(R"({"settings": {"steps": 1e3, "substeps": 2.0}, "bodies": []})", "x");
    EXPECT_EQ(scene.steps, 1000);
    EXPECT_EQ(scene.world.substeps, 2);
}

TEST(SceneLoader, SpringsKeepTheirBodiesPointsAndConstants) {
    const Scene scene = loadScene(R"({"bodies": [
        {"name": "a", "shape": {"type": "sphere", "radius": 0.5}},
        {"name": "b", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 0, 0]}],
        "springs": [
        {"a": "a", "a_point": [0, 0.5, 0], "b": "b", "b_point": [0, -0.5, 0], "stiffness": 50, "damping": 0.5, "rest_length": 2},
        {"a": "b", "b": null, "b_point": [3, 4, 0]},
        {"a": "a"}]})",
                                  "x");
    ASSERT_EQ(scene.springs.size(), 3u);
    const SceneSpring &pair = scene.springs[0];
    EXPECT_EQ(pair.path, "springs[0]");
    EXPECT_EQ(pair.a, 0u);
    ASSERT_TRUE(pair.b.has_value());
    EXPECT_EQ(*pair.b, 1u);
    expectVector(pair.settings.aPoint, 0, 0.5, 0);
    expectVector(pair.settings.bPoint, 0, -0.5, 0);
    EXPECT_DOUBLE_EQ(pair.settings.stiffness, 50);
    EXPECT_DOUBLE_EQ(pair.settings.damping, 0.5);
    EXPECT_DOUBLE_EQ(pair.settings.restLength, 2);
    EXPECT_EQ(scene.springs[1].a, 1u);
    EXPECT_FALSE(scene.springs[1].b.has_value());
    expectVector(scene.springs[1].settings.bPoint, 3, 4, 0);
    EXPECT_FALSE(scene.springs[2].b.has_value());
    const SpringSettings defaults;
    EXPECT_DOUBLE_EQ(scene.springs[2].settings.stiffness, defaults.stiffness);
    EXPECT_DOUBLE_EQ(scene.springs[2].settings.damping, defaults.damping);
    EXPECT_DOUBLE_EQ(scene.springs[2].settings.restLength, defaults.restLength);
}

// Hooke's law over one semi-implicit step: v = (k * stretch / m) dt, without gravity. One
// sub-step, since the World evaluates springs at the start of every sub-step.
TEST(SceneLoader, SpringsPullInTheWorld) {
    const double k = 10, dt = 0.01;
    Scene scene = loadScene(R"({"settings": {"gravity": [0, 0, 0], "dt": 0.01, "steps": 1, "substeps": 1}, "bodies": [
        {"name": "hung", "shape": {"type": "sphere", "radius": 0.5}, "mass": 2},
        {"name": "left", "shape": {"type": "sphere", "radius": 0.5}, "position": [10, 0, 0]},
        {"name": "right", "shape": {"type": "sphere", "radius": 0.5}, "position": [13, 0, 0]}],
        "springs": [
        {"a": "hung", "b": null, "b_point": [0, 3, 0], "stiffness": 10, "rest_length": 1},
        {"a": "left", "b": "right", "stiffness": 10, "rest_length": 1}]})",
                            "x");
    SceneWorld built = buildWorld(scene);
    RunOptions options;
    options.steps = 1;
    options.dt = dt;
    runScene(scene, built, options);
    EXPECT_NEAR(built.world.body(built.ids[0]).getVelocity().y(), k * 2 / 2 * dt, 1e-9);
    EXPECT_NEAR(built.world.body(built.ids[1]).getVelocity().x(), k * 2 / 1 * dt, 1e-9);
    EXPECT_NEAR(built.world.body(built.ids[2]).getVelocity().x(), -k * 2 / 1 * dt, 1e-9);
}

TEST(SceneLoader, EventsKeepStepTargetAndValues) {
    const Scene scene = loadScene(R"({"bodies": [
        {"name": "a", "shape": {"type": "sphere", "radius": 0.5}},
        {"name": "b", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 0, 0]}],
        "events": [
        {"step": 120, "remove": "b"},
        {"step": 200, "set_velocity": "a", "velocity": [0, 0, -10]},
        {"step": 200, "set_rotation": "a", "rotation": [0, 5, 0]},
        {"step": 300, "set_position": "a", "position": [0, 3, 0]},
        {"step": 400, "apply_impulse": "a", "impulse": [0, 5, 0], "point": [0.5, 0.5, 0]},
        {"step": 401, "apply_impulse": "a", "impulse": [1, 0, 0]},
        {"step": 500, "set_awake": "a", "awake": false}]})",
                                  "x");
    ASSERT_EQ(scene.events.size(), 7u);
    const auto &e = scene.events;
    EXPECT_EQ(e[0].kind, EventKind::Remove);
    EXPECT_EQ(e[0].step, 120);
    EXPECT_EQ(e[0].body, 1u);
    EXPECT_EQ(e[1].kind, EventKind::SetVelocity);
    expectVector(e[1].value, 0, 0, -10);
    EXPECT_EQ(e[2].kind, EventKind::SetRotation);
    expectVector(e[2].value, 0, 5, 0);
    EXPECT_EQ(e[3].kind, EventKind::SetPosition);
    expectVector(e[3].value, 0, 3, 0);
    EXPECT_EQ(e[4].kind, EventKind::ApplyImpulse);
    expectVector(e[4].value, 0, 5, 0);
    ASSERT_TRUE(e[4].point.has_value());
    expectVector(*e[4].point, 0.5, 0.5, 0);
    EXPECT_FALSE(e[5].point.has_value());
    EXPECT_EQ(e[6].kind, EventKind::SetAwake);
    EXPECT_FALSE(e[6].awake);
    EXPECT_EQ(e[6].path, "events[6]");
    for (const SceneEvent &event : e) EXPECT_EQ(event.body, event.kind == EventKind::Remove ? 1u : 0u);
}

// Each event acts at the start of its step, through the World: checked against the state
// one step later, worked out by hand (no gravity, no contact).
class EventEffect : public ::testing::Test {
protected:
    static constexpr double dt = 0.01;

    SceneWorld runTo(const std::string &events, std::int64_t steps) {
        scene_ = loadScene(std::string(R"({"settings": {"gravity": [0, 0, 0], "sleep": false}, "bodies": [
            {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "mass": 2, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
            {"name": "other", "shape": {"type": "sphere", "radius": 0.5}, "position": [50, 0, 0]}],
            "events": [)") + events + "]}",
                           "x");
        SceneWorld built = buildWorld(scene_);
        RunOptions options;
        options.steps = steps;
        options.dt = dt;
        runScene(scene_, built, options);
        return built;
    }
    Scene scene_;
};

TEST_F(EventEffect, SetVelocityActsAtTheStartOfItsStep) {
    SceneWorld before = runTo(R"({"step": 2, "set_velocity": "ball", "velocity": [1, 2, 3]})", 2);
    expectVector(before.world.body(before.ids[0]).getVelocity(), 0, 0, 0);
    SceneWorld after = runTo(R"({"step": 2, "set_velocity": "ball", "velocity": [1, 2, 3]})", 3);
    expectVector(after.world.body(after.ids[0]).getVelocity(), 1, 2, 3);
    const Vector3 p = after.world.body(after.ids[0]).getPosition();
    EXPECT_NEAR(p.x(), 1 * dt, 1e-12);
    EXPECT_NEAR(p.y(), 2 * dt, 1e-12);
    EXPECT_NEAR(p.z(), 3 * dt, 1e-12);
}

TEST_F(EventEffect, SetRotationSetPositionAndRemove) {
    SceneWorld built = runTo(R"({"step": 0, "set_rotation": "ball", "rotation": [0, 5, 0]},
                                {"step": 1, "set_position": "ball", "position": [0, 3, 0]},
                                {"step": 1, "remove": "other"})",
                             2);
    expectVector(built.world.body(built.ids[0]).getRotation(), 0, 5, 0);
    expectVector(built.world.body(built.ids[0]).getPosition(), 0, 3, 0);
    EXPECT_FALSE(built.world.contains(built.ids[1]));
}

TEST_F(EventEffect, ImpulsesChangeVelocityByJOverMAndRotationByIInverseRCrossJ) {
    SceneWorld central = runTo(R"({"step": 0, "apply_impulse": "ball", "impulse": [4, 0, 0]})", 1);
    expectVector(central.world.body(central.ids[0]).getVelocity(), 2, 0, 0);
    expectVector(central.world.body(central.ids[0]).getRotation(), 0, 0, 0);
    // r = (0, 0.5, 0), J = (4, 0, 0): r x J = (0, 0, -2); I = identity.
    SceneWorld offset = runTo(R"({"step": 0, "apply_impulse": "ball", "impulse": [4, 0, 0], "point": [0, 0.5, 0]})", 1);
    expectVector(offset.world.body(offset.ids[0]).getVelocity(), 2, 0, 0);
    const Vector3 w = offset.world.body(offset.ids[0]).getRotation();
    EXPECT_NEAR(w.x(), 0, 1e-12);
    EXPECT_NEAR(w.y(), 0, 1e-12);
    EXPECT_NEAR(w.z(), -2, 1e-12);
}

TEST_F(EventEffect, SetAwakeFalsePutsTheBodyToSleep) {
    SceneWorld built = runTo(R"({"step": 0, "set_velocity": "ball", "velocity": [1, 0, 0]},
                                {"step": 3, "set_awake": "ball", "awake": false})",
                             4);
    const RigidBody &ball = built.world.body(built.ids[0]);
    EXPECT_FALSE(ball.getAwake());
    expectVector(ball.getVelocity(), 0, 0, 0);
    // Three steps of motion at 1 m/s, then asleep.
    EXPECT_NEAR(ball.getPosition().x(), 3 * dt, 1e-12);
}

TEST_F(EventEffect, EventsOfOneStepApplyInFileOrder) {
    SceneWorld built = runTo(R"({"step": 1, "set_velocity": "ball", "velocity": [1, 0, 0]},
                                {"step": 1, "set_velocity": "ball", "velocity": [0, 7, 0]},
                                {"step": 0, "set_velocity": "ball", "velocity": [0, 0, 9]})",
                             2);
    expectVector(built.world.body(built.ids[0]).getVelocity(), 0, 7, 0);
}

TEST(SceneLoader, FileOrderOfEventsDoesNotMatterForRemovals) {
    // Removed at step 5, used at step 3 (listed later): fine.
    EXPECT_NO_THROW(loadScene(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}],
        "events": [{"step": 5, "remove": "a"}, {"step": 3, "set_velocity": "a", "velocity": [1, 0, 0]}]})",
                              "x"));
}

}  // namespace
