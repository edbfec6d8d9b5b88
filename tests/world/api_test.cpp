// The World API refuses bad input with a clear error and changes nothing.
#include <cmath>
#include <limits>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


BodySettings validBox() {
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    return s;
}

// Expects addBody to refuse `s` naming `field`, with the world unchanged.
void expectRefused(const BodySettings &s, const std::string &field) {
    WorldFixture f;
    f.ground();
    try {
        f.world.addBody(s);
        FAIL() << "accepted a body with a bad " << field;
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::addBody");
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos);
    }
    EXPECT_EQ(f.world.bodyCount(), 1u);
}

TEST(Api, AddBodyRefusesBadInput) {
    BodySettings s = validBox();
    s.mass = -1;
    expectRefused(s, "mass");
    s = validBox();
    s.mass = 0;
    expectRefused(s, "mass");
    s = validBox();
    s.position = Vector3(kNaN, 0, 0);
    expectRefused(s, "position");
    s = validBox();
    s.velocity = Vector3(0, INFINITY, 0);
    expectRefused(s, "velocity");
    s = validBox();
    s.linearDamping = 1.5;
    expectRefused(s, "linearDamping");
    s = validBox();
    s.material.friction = -0.1;
    expectRefused(s, "material.friction");
    s = validBox();
    s.material.restitution = 2;
    expectRefused(s, "material.restitution");
    s = validBox();
    s.inertia = Matrix3::Identity() * -1;
    expectRefused(s, "inertia");
    s = validBox();
    s.shape = Shape::sphere(-1);
    expectRefused(s, "shape.radius");
    s = validBox();
    s.shape = Shape::plane(Vector3::UnitY(), 0);
    expectRefused(s, "shape.type");
    s = validBox();
    s.name = "ground";
    expectRefused(s, "name");
    // FCL's AABB tree fails on boxes of such size; the World refuses them.
    s = validBox();
    s.shape = Shape::box(Vector3(1e200, 1, 1));
    expectRefused(s, "shape");
    s = validBox();
    s.position = Vector3(0, 1e31, 0);
    expectRefused(s, "position");
}

TEST(Api, StaleHandlesAreRefused) {
    WorldFixture f;
    const BodyId box = f.box(Vector3::Zero());
    f.world.removeBody(box);
    EXPECT_FALSE(f.world.contains(box));
    EXPECT_THROW(f.world.body(box), InvalidArgument);
    EXPECT_THROW(f.world.removeBody(box), InvalidArgument);
    const BodyId reused = f.box(Vector3::Zero());
    EXPECT_EQ(reused.index, box.index);  // the slot is reused, the handle is not
    EXPECT_THROW(f.world.setVelocity(box, Vector3::Zero()), InvalidArgument);
    EXPECT_NO_THROW(f.world.setVelocity(reused, Vector3::Zero()));
}

TEST(Api, StaticBodiesRefuseVelocityAndForces) {
    WorldFixture f;
    const BodyId wall = f.staticBox(Vector3::Zero(), Vector3(1, 1, 1));
    EXPECT_THROW(f.world.setVelocity(wall, Vector3(1, 0, 0)), InvalidArgument);
    EXPECT_THROW(f.world.applyImpulse(wall, Vector3(1, 0, 0)), InvalidArgument);
    EXPECT_THROW(f.world.addForce(wall, Vector3(1, 0, 0)), InvalidArgument);
    EXPECT_EQ(f.world.body(wall).getVelocity(), Vector3::Zero());
}

TEST(Api, SettersRefuseNonFiniteAndKeepState) {
    WorldFixture f;
    const BodyId box = f.box(Vector3(1, 2, 3));
    EXPECT_THROW(f.world.setPosition(box, Vector3(kNaN, 0, 0)), InvalidArgument);
    EXPECT_THROW(f.world.applyImpulse(box, Vector3(1, 0, 0), Vector3(INFINITY, 0, 0)), InvalidArgument);
    EXPECT_THROW(f.world.setMaterial(box, Material{-1, 0}), InvalidArgument);
    EXPECT_EQ(f.position(box), Vector3(1, 2, 3));
    EXPECT_EQ(f.world.body(box).getVelocity(), Vector3::Zero());
    EXPECT_EQ(f.world.material(box).friction, 0.6);
}

TEST(Api, SettingsAndStepAreValidated) {
    WorldSettings bad;
    bad.velocityIterations = 0;
    EXPECT_THROW(World{bad}, InvalidArgument);
    WorldFixture f;
    const BodyId box = f.box(Vector3(0, 5, 0));
    EXPECT_THROW(f.world.step(0), InvalidArgument);
    EXPECT_THROW(f.world.step(-1), InvalidArgument);
    EXPECT_THROW(f.world.step(kNaN), InvalidArgument);
    EXPECT_THROW(f.world.setSettings(bad), InvalidArgument);
    EXPECT_EQ(f.world.settings().velocityIterations, WorldSettings().velocityIterations);
    EXPECT_EQ(f.position(box), Vector3(0, 5, 0));
}

// 1e300 N added twice (2e300 N on 1 kg): the velocity it gives overflows within the step,
// so the step reports and isolates that body, and no NaN or overflow reaches any other
// body: not the box it rests on, nor
// the one on top, nor a ball joined to it by a spring, whatever the integrator, with the
// victim asking for continuous collision and spinning (so that every stage touches it).
TEST(Api, NonFiniteBodyIsIsolated) {
    for (Integrator integrator :
         {Integrator::NewtonEuler, Integrator::NewtonEulerGyroscopic, Integrator::NewtonEulerImplicit}) {
        WorldSettings settings;
        settings.sleep = false;
        settings.integrator = integrator;
        WorldFixture f(settings);
        f.ground();
        const BodyId below = f.box(Vector3(0, 0.5, 0));
        BodySettings v;
        v.shape = Shape::box(Vector3(0.5, 0.25, 0.4));
        v.position = Vector3(0, 1.25, 0);
        v.rotation = Vector3(0, 3, 0.5);
        v.ccd = true;
        const BodyId victim = f.world.addBody(v);
        const BodyId above = f.box(Vector3(0, 2, 0));
        const BodyId ball = f.sphere(Vector3(3, 1.25, 0));
        SpringSettings spring;
        spring.a = ball;
        spring.b = victim;
        spring.stiffness = 1000;
        spring.restLength = 3;
        f.world.addSpring(spring);
        f.simulate(0.1);
        f.world.addForce(victim, Vector3(1e300, 0, 0));
        f.world.addForce(victim, Vector3(1e300, 0, 0));
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().isolatedBodies, 1);
        f.simulate(0.5);
        EXPECT_EQ(f.world.stats().isolatedBodies, 1);
        for (BodyId id : {below, above, ball}) {
            const RigidBody &n = f.world.body(id);
            EXPECT_TRUE(n.getPosition().allFinite()) << static_cast<int>(integrator);
            EXPECT_TRUE(n.getVelocity().allFinite()) << static_cast<int>(integrator);
            EXPECT_TRUE(n.getRotation().allFinite()) << static_cast<int>(integrator);
            EXPECT_TRUE(n.getOrientation().coeffs().allFinite()) << static_cast<int>(integrator);
        }
    }
}

TEST(Api, NamesFindBodies) {
    WorldFixture f;
    const BodyId g = f.ground();
    EXPECT_EQ(f.world.findBody("ground"), g);
    EXPECT_FALSE(f.world.findBody("nothing").has_value());
    f.world.removeBody(g);
    EXPECT_FALSE(f.world.findBody("ground").has_value());
}

}  // namespace
}  // namespace cyclone::test
