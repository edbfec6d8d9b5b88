// The World API's refusals name the function, the field and the value, and come before
// anything changes; the kinetic energy is a number wherever the state is.
#include <cmath>
#include <limits>
#include <string>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


// Runs `call`, which must throw InvalidArgument from `function` about `field` with `shown`
// (the value) in its message.
template <typename Call>
void expectRefusal(Call call, const std::string &function, const std::string &field, const std::string &shown) {
    try {
        call();
        FAIL() << function << " accepted a bad " << field;
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), function) << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(e.problem().find(shown), std::string::npos) << e.what();
    }
}

TEST(ApiMessages, SettingsRefuseEnumValuesThatNameNothing) {
    WorldFixture f;
    const BodyId box = f.box(Vector3(0, 5, 0));
    WorldSettings bad;
    bad.integrator = static_cast<Integrator>(99);
    expectRefusal([&] { f.world.setSettings(bad); }, "World::setSettings", "integrator", "got 99");
    expectRefusal([&] { World world(bad); }, "World::World", "integrator", "got 99");
    bad.integrator = static_cast<Integrator>(-1);
    expectRefusal([&] { f.world.setSettings(bad); }, "World::setSettings", "integrator", "got -1");
    EXPECT_EQ(f.world.settings().integrator, Integrator::NewtonEuler);
    f.world.step(kDt);
    EXPECT_LT(f.position(box).y(), 5.0);
}

// A spring point at 1e300 m used to be accepted, and the force it gave overflowed.
TEST(ApiMessages, SpringPointsBeyondTheCoordinateBoundAreRefused) {
    BodySettings sleeping;
    sleeping.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    sleeping.awake = false;
    WorldFixture f;
    const BodyId box = f.world.addBody(sleeping);
    SpringSettings spring;
    spring.a = box;
    spring.aPoint = Vector3(1e300, 0, 0);
    expectRefusal([&] { f.world.addSpring(spring); }, "World::addSpring", "aPoint", "1e+300");
    spring.aPoint = Vector3::Zero();
    spring.bPoint = Vector3(0, -2e30, 0);  // anchored: a world point
    expectRefusal([&] { f.world.addSpring(spring); }, "World::addSpring", "bPoint", "-2e+30");
    EXPECT_FALSE(f.awake(box));  // nothing was woken by the refusals
    spring.bPoint = Vector3(0, -1e12, 0);  // at kMaxCoordinate: accepted
    EXPECT_NO_THROW(f.world.addSpring(spring));
}

TEST(ApiMessages, OrientationRefusalsShowTheValue) {
    WorldFixture f;
    BodySettings s;
    s.shape = Shape::sphere(1);
    s.orientation = Quaternion(kNaN, 0, 0, 1);
    expectRefusal([&] { f.world.addBody(s); }, "World::addBody", "orientation", "got [nan, 0, 0, 1]");
    const BodyId ball = f.sphere(Vector3::Zero());
    expectRefusal([&] { f.world.setOrientation(ball, Quaternion(1, INFINITY, 0, 0)); }, "World::setOrientation",
                  "orientation", "got [1, inf, 0, 0]");
    EXPECT_EQ(f.world.body(ball).getOrientation().coeffs(), Quaternion::Identity().coeffs());
}

// 5e-324 kg is > 0, but 1 / 5e-324 overflows: the World says so itself, whether or not the
// inertia is given (with it, RigidBody::setMass used to be the one to refuse).
TEST(ApiMessages, AMassTooSmallToInvertIsRefusedByAddBody) {
    for (bool explicitInertia : {false, true}) {
        WorldFixture f;
        BodySettings s;
        s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        s.mass = 5e-324;
        if (explicitInertia) s.inertia = Matrix3::Identity();
        expectRefusal([&] { f.world.addBody(s); }, "World::addBody", "mass", "[1e-100, 1e100] kg (the solver's range), got 5e-324");
        EXPECT_EQ(f.world.bodyCount(), 0u);
    }
}

// An impulse whose velocity change overflows (1e300 N s on 1e-10 kg) is refused before the
// sleeping body is woken; one whose sum with the velocity does (1e308 + 1e308 m/s, on a
// moving body: a sleeping one has no velocity) is refused with the velocity unchanged.
TEST(ApiMessages, AnImpulseThatWouldOverflowIsRefusedBeforeWaking) {
    WorldFixture f;
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.awake = false;
    s.mass = 1e-10;
    const BodyId light = f.world.addBody(s);
    s.mass = 1;
    s.awake = true;
    s.velocity = Vector3(1e308, 0, 0);
    s.position = Vector3(5, 0, 0);
    const BodyId fast = f.world.addBody(s);
    expectRefusal([&] { f.world.applyImpulse(light, Vector3(0, 1e300, 0)); }, "World::applyImpulse", "impulse",
                  "would make the velocity non-finite, got [0, 1e+300, 0]");
    expectRefusal([&] { f.world.applyImpulse(fast, Vector3(1e308, 0, 0)); }, "World::applyImpulse", "impulse",
                  "got [1e+308, 0, 0]");
    expectRefusal([&] { f.world.applyImpulse(fast, Vector3(1e308, 0, 0), Vector3(5, 0, 0)); }, "World::applyImpulse",
                  "impulse", "got [1e+308, 0, 0] at [5, 0, 0]");
    EXPECT_FALSE(f.awake(light));
    EXPECT_EQ(f.world.body(light).getVelocity(), Vector3::Zero());
    EXPECT_EQ(f.world.body(fast).getRotation(), Vector3::Zero());
    EXPECT_EQ(f.world.body(fast).getVelocity(), Vector3(1e308, 0, 0));
}

// E = m v^2 / 2 + w.(I w) / 2, worked by hand: 1e99 kg at 3 m/s is 4.5e99 J; 1e-100 kg at
// 1e200 m/s is 5e299 J (v^2 alone overflows); a 2 kg ball of radius 1 (I = 0.8) at 5 rad/s is 10 J.
TEST(ApiMessages, KineticEnergyIsFiniteWheneverItFitsADouble) {
    const auto energyOf = [](BodySettings s) {
        World world;
        world.addBody(s);
        return world.kineticEnergy();
    };
    BodySettings heavy;
    heavy.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    heavy.mass = 1e99;
    heavy.velocity = Vector3(3, 0, 0);
    EXPECT_NEAR(energyOf(heavy) / 4.5e99, 1.0, 1e-12);
    BodySettings light = heavy;
    light.mass = 1e-100;
    light.inertia = Matrix3::Identity();
    light.velocity = Vector3(0, 1e200, 0);
    EXPECT_NEAR(energyOf(light) / 5e299, 1.0, 1e-12);
    BodySettings ball;
    ball.shape = Shape::sphere(1);
    ball.mass = 2;
    ball.rotation = Vector3(0, 0, 5);
    EXPECT_NEAR(energyOf(ball), 10.0, 1e-12);
    ball.rotation = Vector3(0, 0, 1e200);  // 0.4 * 1e400 J: beyond any double
    EXPECT_EQ(energyOf(ball), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace cyclone::test
