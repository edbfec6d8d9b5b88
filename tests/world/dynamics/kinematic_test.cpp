// Kinematic bodies: moved only at the velocities they are given; they push and carry
// dynamic bodies, never sleep while moving, and are never tested against static bodies.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

BodySettings kinematicBox(const Vector3 &position, const Vector3 &half, const Vector3 &velocity,
                          const Vector3 &rotation = Vector3::Zero()) {
    BodySettings s;
    s.motion = Motion::Kinematic;
    s.shape = Shape::box(half);
    s.position = position;
    s.velocity = velocity;
    s.rotation = rotation;
    return s;
}

// The platform starts at 1 m/s under a crate at rest. Friction (mu = 0.6 on both: 0.6)
// accelerates the crate at mu g = 5.886 m/s^2 until it matches, after t = 1 / (mu g) =
// 0.17 s; meanwhile it slips 1 / (2 mu g) = 0.085 m behind. Afterwards it rides along.
TEST(Kinematic, PlatformCarriesACrateWithinTheSlipFrictionAllows) {
    for (int substeps : {1, 4}) {
        WorldSettings settings;
        settings.substeps = substeps;
        WorldFixture f(settings);
        const BodyId platform = f.world.addBody(kinematicBox(Vector3(0, 0.25, 0), Vector3(4, 0.25, 2), Vector3(1, 0, 0)));
        const BodyId crate = f.box(Vector3(-2, 1.0, 0));
        f.simulate(2.0);
        EXPECT_NEAR(f.position(platform).x(), 2.0, 1e-9) << "the platform keeps its speed exactly";
        EXPECT_NEAR(f.world.body(platform).getVelocity().x(), 1.0, 1e-12);
        const double slip = 1.0 / (2 * 0.6 * 9.81);
        const double travelled = f.position(crate).x() + 2;
        EXPECT_GT(travelled, 2.0 - slip - 0.02) << substeps;
        EXPECT_LT(travelled, 2.0 + 1e-3) << substeps;
        EXPECT_NEAR(f.world.body(crate).getVelocity().x(), 1.0, 0.01);
        EXPECT_NEAR(f.position(crate).y(), 1.0, 0.01) << "it rests on the platform";
    }
}

// A disc turning at omega = 1 rad/s; a crate at r = 1.5 m needs omega^2 r = 1.5 m/s^2 of
// friction, well within mu g = 5.9. The crate starts with the disc's motion there
// (velocity omega x r, rotation omega), so it never slips. Each step the disc turns
// theta = omega dt and the point under the crate goes along the chord of its arc; the
// contact's rows see the disc's surface velocity at mid-step, which points along that
// chord, so the crate moves straight along it and lands on the circle: it overshoots the
// chord's length 2 r sin(theta / 2) by r (theta - 2 sin(theta / 2)), which puts it
// r theta^4 / 48 (2.4e-9 m) further out a step. After 3 s the crate keeps r = 1.5 m (within
// the solver's convergence, 1 mm allowed; moving along the tangent instead, each step
// would multiply r by sqrt(1 + theta^2), 1.538 m at 3 s), it has gone round the same
// 3 rad as the disc, at omega r = 1.5 m/s and omega = 1 rad/s.
TEST(Kinematic, TurntableTurnsACrateAtItsRadiusAndAngularSpeed) {
    for (int substeps : {1, 4}) {
        WorldSettings settings;
        settings.substeps = substeps;
        WorldFixture f(settings);
        const BodyId disc =
            f.world.addBody(kinematicBox(Vector3::Zero(), Vector3(3, 0.25, 3), Vector3::Zero(), Vector3(0, 1, 0)));
        BodySettings s;
        s.shape = Shape::box(Vector3(0.25, 0.5, 0.25));
        s.position = Vector3(1.5, 0.75, 0);
        s.velocity = Vector3(0, 1, 0).cross(s.position);  // (0, 0, -1.5)
        s.rotation = Vector3(0, 1, 0);
        const BodyId crate = f.world.addBody(s);
        f.simulate(3.0);
        const Vector3 p = f.position(crate);
        EXPECT_NEAR(std::hypot(p.x(), p.z()), 1.5, 0.001) << substeps;
        // Turning about +y takes +x towards -z: the polar angle atan2(-z, x).
        EXPECT_NEAR(std::atan2(-p.z(), p.x()), 3.0, 0.005) << substeps;
        EXPECT_NEAR(f.world.body(crate).getVelocity().norm(), 1.5, 0.005) << substeps << ": omega r";
        EXPECT_NEAR(f.world.body(crate).getRotation().y(), 1.0, 0.01) << substeps;
        // The disc turned exactly 3 rad.
        const Quaternion expected(Eigen::AngleAxis<real>(3.0, Vector3::UnitY()));
        EXPECT_NEAR(f.world.body(disc).getOrientation().angularDistance(expected), 0, 1e-9);
    }
}

// The same disc under a 0.5 m cube at rest at r = 1.5 m (low enough not to tip: it would
// take mu g > g (half width / half height) = g). Friction brings it to omega r = 1.5 m/s
// within 1.5 / (mu g) = 0.25 s, while it slips (1.5 m/s)^2 / (2 mu g) = 0.19 m behind the
// disc's point it started on: it then lags the disc by 0.19 / 1.5 = 0.127 rad. The slip
// moves it outward by less than sliding 0.19 m along the tangent would, sqrt(1.5^2 +
// 0.19^2) - 1.5 = 0.012 m. Once it turns with the disc its radius stays: from 1 s to 3 s
// it changes by under 1 mm (moving along the tangent, it would grow by 0.8 % a second,
// 24 mm).
TEST(Kinematic, TurntableKeepsTheRadiusACrateCaughtUpAt) {
    WorldFixture f;
    f.world.addBody(kinematicBox(Vector3::Zero(), Vector3(3, 0.25, 3), Vector3::Zero(), Vector3(0, 1, 0)));
    const BodyId crate = f.box(Vector3(1.5, 0.5, 0), Vector3(0.25, 0.25, 0.25));
    const auto radius = [&] { return std::hypot(f.position(crate).x(), f.position(crate).z()); };
    f.simulate(1.0);
    const double caughtUp = radius();
    EXPECT_GE(caughtUp, 1.5 - 0.001);
    EXPECT_LE(caughtUp, 1.512);
    f.simulate(2.0);
    EXPECT_NEAR(radius(), caughtUp, 0.001);
    const double slip = 1.5 * 1.5 / (2 * 0.6 * 9.81);
    EXPECT_NEAR(std::atan2(-f.position(crate).z(), f.position(crate).x()), 3.0 - slip / 1.5, 0.01);
    EXPECT_NEAR(f.world.body(crate).getVelocity().norm(), 1.0 * radius(), 0.005) << "omega r";
    EXPECT_NEAR(f.world.body(crate).getRotation().y(), 1.0, 0.01);
}

// A wall at 2 m/s meets a 1 kg box at rest on the ground: the box is pushed ahead at the
// wall's speed and the wall does not slow at all.
TEST(Kinematic, WallPushesABoxWithoutSlowing) {
    WorldFixture f;
    f.ground();
    const BodyId wall = f.world.addBody(kinematicBox(Vector3(-2, 1, 0), Vector3(0.25, 1, 2), Vector3(2, 0, 0)));
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(2.0);
    EXPECT_NEAR(f.position(wall).x(), 2.0, 1e-9);
    EXPECT_NEAR(f.world.body(wall).getVelocity().x(), 2.0, 0.0);
    // The box's back face stays at the wall's front face (2.25) give or take the slop.
    EXPECT_NEAR(f.position(box).x() - 0.5, 2.25, 0.02);
    EXPECT_NEAR(f.world.body(box).getVelocity().x(), 2.0, 0.05);
}

TEST(Kinematic, MovingKinematicNeverSleepsAndWakesWhatItTouches) {
    WorldFixture f;
    const BodyId platform = f.world.addBody(kinematicBox(Vector3(0, 0.25, 0), Vector3(4, 0.25, 2), Vector3::Zero()));
    const BodyId crate = f.box(Vector3(0, 1.0, 0));
    f.simulate(4.0);
    EXPECT_FALSE(f.awake(crate)) << "a crate on a still platform sleeps";
    f.world.setVelocity(platform, Vector3(0, 0.5, 0));  // an elevator going up
    f.world.step(kDt);
    EXPECT_TRUE(f.awake(crate));
    f.simulate(5.0);
    EXPECT_TRUE(f.awake(platform));
    EXPECT_TRUE(f.awake(crate)) << "it rises with the elevator";
    EXPECT_EQ(f.world.stats().movingKinematicBodies, 1);
    EXPECT_NEAR(f.position(crate).y() - f.position(platform).y(), 0.75, 0.01);
    EXPECT_NEAR(f.world.body(crate).getVelocity().y(), 0.5, 0.01);
    f.world.setVelocity(platform, Vector3::Zero());
    f.simulate(4.0);
    EXPECT_FALSE(f.awake(platform));
    EXPECT_FALSE(f.awake(crate)) << "it settles when the elevator stops";
}

TEST(Kinematic, PairsWithStaticAndKinematicBodiesAreNeverTested) {
    WorldFixture f;
    f.staticBox(Vector3::Zero(), Vector3(1, 1, 1));
    f.world.addBody(kinematicBox(Vector3(0.5, 0, 0), Vector3(1, 1, 1), Vector3(1, 0, 0)));
    f.world.addBody(kinematicBox(Vector3(-0.5, 0, 0), Vector3(1, 1, 1), Vector3(0, 1, 0)));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().immovablePairsSkipped, 3);
    EXPECT_EQ(f.world.stats().pairsTested, 0);
    EXPECT_EQ(f.world.stats().contacts, 0);
}

TEST(Kinematic, MoveKinematicReachesThePoseInOneStep) {
    WorldFixture f;
    const BodyId lift = f.world.addBody(kinematicBox(Vector3::Zero(), Vector3(1, 0.1, 1), Vector3::Zero()));
    const Quaternion target(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
    f.world.moveKinematic(lift, Vector3(1, 2, 3), target, kDt);
    EXPECT_NEAR((f.world.body(lift).getVelocity() - Vector3(60, 120, 180)).norm(), 0, 1e-9);
    EXPECT_NEAR((f.world.body(lift).getRotation() - Vector3(0, 30 * kPi, 0)).norm(), 0, 1e-9);
    f.world.step(kDt);
    EXPECT_NEAR((f.position(lift) - Vector3(1, 2, 3)).norm(), 0, 1e-9);
    EXPECT_NEAR(f.world.body(lift).getOrientation().angularDistance(target), 0, 1e-9);
}

TEST(Kinematic, BadInputIsRefused) {
    WorldFixture f;
    const BodyId box = f.box(Vector3::Zero());
    try {
        f.world.moveKinematic(box, Vector3::Zero(), Quaternion::Identity(), kDt);
        FAIL();
    } catch (const InvalidArgument &e) {
        EXPECT_NE(std::string(e.what()).find("World::moveKinematic"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("dynamic"), std::string::npos);
    }
    BodySettings plane = kinematicBox(Vector3::Zero(), Vector3(1, 1, 1), Vector3::Zero());
    plane.shape = Shape::plane(Vector3::UnitY(), 0);
    EXPECT_THROW(f.world.addBody(plane), InvalidArgument);
    const BodyId k = f.world.addBody(kinematicBox(Vector3(5, 0, 0), Vector3(1, 1, 1), Vector3::Zero()));
    EXPECT_THROW(f.world.applyImpulse(k, Vector3(1, 0, 0)), InvalidArgument);
    EXPECT_THROW(f.world.moveKinematic(k, Vector3::Zero(), Quaternion::Identity(), 0), InvalidArgument);
    EXPECT_EQ(f.world.motion(k), Motion::Kinematic);
    EXPECT_EQ(f.world.bodyCount(), 2u);
}

}  // namespace
}  // namespace cyclone::test
