// Physics against closed forms: free fall, friction on an incline, rolling, stacking.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// Semi-implicit Euler under constant g, N sub-steps of h: v_N = -g N h,
// y_N = y0 - g h^2 N (N + 1) / 2.
TEST(Physics, FreeFallFollowsTheSeedIntegratorExactly) {
    for (int substeps : {1, 4}) {
        WorldSettings settings;
        settings.substeps = substeps;
        WorldFixture f(settings);
        const BodyId ball = f.sphere(Vector3(0, 100, 0), 0.5);
        for (int i = 0; i < 60; ++i) f.world.step(kDt);
        const double n = 60.0 * substeps;
        const double h = kDt / substeps;
        EXPECT_NEAR(f.world.body(ball).getVelocity().y(), -9.81 * n * h, 1e-12);
        EXPECT_NEAR(f.position(ball).y(), 100 - 9.81 * h * h * n * (n + 1) / 2, 1e-9);
    }
}

struct Incline {
    WorldFixture f;
    Quaternion tilt;
    Vector3 downhill;
    BodyId body;

    // A static ramp tilted by `degrees` about z with the body resting on its surface.
    Incline(double degrees, real friction, const BodySettings &settings) {
        tilt = Quaternion(Eigen::AngleAxis<real>(degrees * kPi / 180, Vector3::UnitZ()));
        f.staticBox(Vector3::Zero(), Vector3(20, 0.25, 3), tilt, friction);
        const Vector3 up = tilt * Vector3::UnitY();
        downhill = tilt * -Vector3::UnitX();
        BodySettings s = settings;
        s.orientation = tilt;
        s.material.friction = friction;
        s.canSleep = false;
        const real lift = s.shape.type == ShapeType::Sphere ? s.shape.radius : s.shape.halfExtents.y();
        s.position = up * (0.25 + lift) + downhill * -10.0;
        body = f.world.addBody(s);
    }

    // Mean acceleration along the slope over `seconds`, after `settle` seconds: the change
    // of velocity over the interval (exact for a constant acceleration).
    double acceleration(double settle, double seconds) {
        f.simulate(settle);
        const double v0 = f.world.body(body).getVelocity().dot(downhill);
        f.simulate(seconds);
        const double v1 = f.world.body(body).getVelocity().dot(downhill);
        return (v1 - v0) / seconds;
    }
};

BodySettings smallBox() {
    BodySettings s;
    s.shape = Shape::box(Vector3(0.25, 0.25, 0.25));
    return s;
}

// Coulomb: a = g (sin 30 - 0.3 cos 30) = 9.81 (0.5 - 0.2598) = 2.356 m/s^2.
TEST(Physics, BoxSlidesDownInclineAtCoulombAcceleration) {
    Incline incline(30, 0.3, smallBox());
    const double expected = 9.81 * (std::sin(kPi / 6) - 0.3 * std::cos(kPi / 6));
    EXPECT_NEAR(incline.acceleration(0.25, 1.0), expected, 0.05 * expected);
}

// tan 30 = 0.577 < 0.7: static friction holds the box.
TEST(Physics, BoxHoldsOnInclineWithHighFriction) {
    Incline incline(30, 0.7, smallBox());
    incline.f.simulate(0.25);
    const Vector3 start = incline.f.position(incline.body);
    incline.f.simulate(2);
    EXPECT_LT((incline.f.position(incline.body) - start).norm(), 0.005);
}

// Rolling without slipping, solid sphere: a = g sin(theta) / (1 + 2/5) = 5/7 g sin(theta)
// = 3.504 m/s^2 at 30 degrees (needs mu >= 2/7 tan 30 = 0.165).
TEST(Physics, SphereRollsDownInclineAtFiveSevenths) {
    BodySettings s;
    s.shape = Shape::sphere(0.25);
    Incline incline(30, 0.6, s);
    const double expected = 5.0 / 7.0 * 9.81 * std::sin(kPi / 6);
    EXPECT_NEAR(incline.acceleration(0.25, 1.0), expected, 0.05 * expected);
}

// A speculative contact closes its gap within the sub-step and no further: each sub-step
// measures the gap anew. No gravity; a box resting on the ground is lifted 1.5 mm (its
// corners stay kept as speculative points, within 2 mm) and thrown down at 0.48 m/s,
// with 4 sub-steps of h = 1/240 s (2 mm each at that speed). Sub-step 0 lets it approach
// at 0.0015 / h = 0.36 m/s: it ends the sub-step touching. The next sub-steps find no
// gap and stop it there. Had they kept the first gap, each would let it sink another
// 1.5 mm. Without position iterations, whose pass also measures the depths after each
// sub-step, the velocity solve measures them on its own.
TEST(Physics, SpeculativeContactMeasuresTheGapEverySubstep) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    settings.substeps = 4;
    settings.positionIterations = 0;
    WorldFixture f(settings);
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.world.step(kDt);
    ASSERT_EQ(f.world.stats().contacts, 4);
    f.world.setPosition(box, Vector3(0, 0.5015, 0));
    f.world.setVelocity(box, Vector3(0, -0.48, 0));
    f.world.step(kDt);
    EXPECT_NEAR(f.position(box).y(), 0.5, 1e-6);
    EXPECT_NEAR(f.world.body(box).getVelocity().y(), 0, 1e-4);
}

TEST(Physics, BoxRestsOnPlaneWithoutDrift) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(5);
    // It sinks at most by the penetration slop (5 mm) plus one step of gravity.
    EXPECT_NEAR(f.position(box).y(), 0.5, 0.006);
    EXPECT_LT(std::hypot(f.position(box).x(), f.position(box).z()), 1e-4);
    EXPECT_LT(f.world.body(box).getVelocity().norm(), 1e-3);
}

TEST(Physics, TwelveBoxTowerWithOffsetsStands) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground();
    BodyId top;
    for (int i = 0; i < 12; ++i) top = f.box(Vector3(i % 2 ? 0.01 : -0.01, 0.5 + i, 0));
    const Vector3 start = f.position(top);
    f.simulate(10);
    EXPECT_LT((f.position(top) - start).norm(), 0.05);
}

TEST(Physics, HeavyBoxOnLightBoxStaysPut) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground();
    f.box(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5), 1);
    const BodyId heavy = f.box(Vector3(0, 1.5, 0), Vector3(0.5, 0.5, 0.5), 100);
    f.simulate(5);
    EXPECT_NEAR(f.position(heavy).y(), 1.5, 0.02);
    EXPECT_LT(std::hypot(f.position(heavy).x(), f.position(heavy).z()), 0.01);
}

// Without friction nothing opposes sliding: the speed is kept, and no friction rows exist.
TEST(Physics, FrictionlessBoxKeepsSliding) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground(0);
    const BodyId box = f.box(Vector3(0, 0.5, 0), Vector3(0.5, 0.5, 0.5), 1, 0);
    f.simulate(0.2);
    f.world.setVelocity(box, Vector3(2, f.world.body(box).getVelocity().y(), 0));
    f.simulate(1);
    EXPECT_NEAR(f.world.body(box).getVelocity().x(), 2, 1e-6);
    EXPECT_GT(f.world.stats().contacts, 0);
    EXPECT_EQ(f.world.stats().frictionRows, 0);
    EXPECT_EQ(f.world.stats().restitutionContacts, 0);
}

// A unit box (1 kg) spinning flat on the ground about the vertical stops by torsional
// friction. Its four corners lie r = sqrt(0.5^2 + 0.5^2) = 0.7071 m from the patch's
// centre, so friction gives at most tau = mu m g r = 0.6 * 9.81 * 0.7071 = 4.162 N m
// against I = m (1 + 1) / 12 = 1/6 kg m^2: alpha = 24.97 rad/s^2. From 5 rad/s: 2.503 rad/s
// after 0.1 s, at rest after 0.2002 s, having turned w0^2 / (2 alpha) = 0.5006 rad; the
// semi-implicit step turns the body with the velocity after each sub-step (4 of 1/240 s),
// sum over j of (5 - 0.10405 j) / 240 = 0.490 rad.
TEST(Physics, SpinningBoxStopsAtTorsionalFrictionRate) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground(0.6);
    const BodyId box = f.box(Vector3(0, 0.5, 0));
    f.simulate(0.2);
    const Quaternion start = f.world.body(box).getOrientation();
    f.world.setRotation(box, Vector3(0, 5, 0));
    f.simulate(0.1);
    EXPECT_NEAR(f.world.body(box).getRotation().y(), 2.503, 0.05);
    f.simulate(0.4);
    EXPECT_NEAR(f.world.body(box).getRotation().norm(), 0, 0.01);
    const Quaternion turn = f.world.body(box).getOrientation() * start.conjugate();
    EXPECT_NEAR(2 * std::atan2(turn.y(), turn.w()), 0.490, 0.015);
    EXPECT_NEAR(f.position(box).y(), 0.5, 0.002);
}

// A ball dropped from 2 m with e = 0.5 rebounds to about e^2 h = 0.5 m.
TEST(Physics, BouncingBallReachesRestitutionHeight) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground();
    BodySettings s;
    s.shape = Shape::sphere(0.1);
    s.position = Vector3(0, 2.1, 0);
    s.material.restitution = 0.5;
    const BodyId ball = f.world.addBody(s);
    double apex = 0;
    bool bounced = false;
    // Falling 2 m takes 0.64 s and rising 0.5 m 0.32 s: 1.1 s covers the first bounce.
    for (int i = 0; i < 264; ++i) {
        f.world.step(1.0 / 240.0);
        const double v = f.world.body(ball).getVelocity().y();
        if (v > 0) bounced = true;
        if (bounced) apex = std::max(apex, f.position(ball).y() - 0.1);
    }
    EXPECT_TRUE(bounced);
    EXPECT_NEAR(apex, 0.5, 0.05);
}

// The plane's solid is normal.x <= offset as given (shape.h, the scene format): normal
// (0, 2, 0) with offset 1 is the ground y <= 0.5, and a plane body placed at (0, 2, 0)
// has its surface at y = 2.
// The broadphase must agree with the narrowphase on both, or a box falls through to
// where the broadphase thinks the plane is.
TEST(Physics, BoxRestsOnPlanesWithLongNormalsOrMovedBodies) {
    for (const auto &[shape, position, surface] :
         {std::tuple{Shape::plane(Vector3(0, 2, 0), 1), Vector3(0, 0, 0), 0.5},
          std::tuple{Shape::plane(Vector3::UnitY(), 0), Vector3(0, 2, 0), 2.0}}) {
        WorldFixture f;
        BodySettings plane;
        plane.motion = Motion::Static;
        plane.shape = shape;
        plane.position = position;
        f.world.addBody(plane);
        // Dropped from 5 cm it lands at 1 m/s and sinks about one step's travel, 1.7 cm.
        const BodyId box = f.box(Vector3(0, surface + 0.55, 0));
        double lowest = surface + 1;
        for (int i = 0; i < 120; ++i) {
            f.world.step(kDt);
            lowest = std::min(lowest, f.position(box).y());
        }
        EXPECT_GT(lowest, surface + 0.5 - 0.025) << "surface at y = " << surface;
        EXPECT_NEAR(f.position(box).y(), surface + 0.5, 0.005) << "surface at y = " << surface;
    }
}

}  // namespace
}  // namespace cyclone::test

namespace cyclone::test {
namespace {

// Every dynamic shape placed just touching a large static box rests there. FCL's MPR
// once gave a small hull on a large box the box's side face as normal (2.3 m deep) and
// the hull shot away; a resting body may only settle by the slop and one step of gravity.
TEST(Physics, EveryShapeRestsOnALargeStaticBox) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.staticBox(Vector3(0, -0.5, 0), Vector3(6, 0.5, 2));
    std::vector<BodySettings> shapes(5);
    shapes[0].shape = Shape::box(Vector3(0.3, 0.2, 0.4));
    shapes[0].position = Vector3(-4, 0.2, 0);
    shapes[1].shape = Shape::sphere(0.3);
    shapes[1].position = Vector3(-2, 0.3, 0);
    shapes[2].shape = Shape::capsule(0.2, 0.6);  // lying on its side
    shapes[2].position = Vector3(0, 0.2, 0);
    shapes[3].shape = Shape::cylinder(0.3, 0.5);  // standing on a cap
    shapes[3].orientation = Quaternion(Eigen::AngleAxis<real>(-kPi / 2, Vector3::UnitX()));
    shapes[3].position = Vector3(2, 0.25, 0);
    shapes[4].shape = Shape::convex({{-0.3, -0.2, -0.3}, {0.3, -0.2, -0.3}, {0.3, -0.2, 0.3}, {-0.3, -0.2, 0.3},
                                     {0, 0.3, 0}, {0.2, 0.1, 0.1}});
    shapes[4].position = Vector3(4, 0.2, 0);
    std::vector<BodyId> ids;
    for (const BodySettings &s : shapes) ids.push_back(f.world.addBody(s));
    f.simulate(3);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        EXPECT_LT((f.position(ids[i]) - shapes[i].position).norm(), 0.002) << shapeTypeName(shapes[i].shape.type);
        EXPECT_LT(f.world.body(ids[i]).getVelocity().norm(), 0.01) << shapeTypeName(shapes[i].shape.type);
    }
    EXPECT_LT(f.world.stats().maxPenetration, 0.002);
}

// A column of three unit boxes on a ramp (friction 0.6, which holds it from sliding up to
// atan 0.6 = 31 degrees) tips over once its centre of mass, 1.5 m above the ramp's surface,
// passes over the downhill edge of its 1 m base: beyond atan(0.5 / 1.5) = 18.4 degrees.
// Returns how far the top box moved in 10 s, sleep off.
double topOfColumnMoved(double degrees) {
    WorldFixture f(noSleep());
    const Quaternion tilt(Eigen::AngleAxis<real>(degrees * kPi / 180, Vector3::UnitZ()));
    f.staticBox(Vector3::Zero(), Vector3(20, 0.25, 3), tilt);
    const Vector3 up = tilt * Vector3::UnitY();
    BodyId top{};
    Vector3 start;
    for (int k = 0; k < 3; ++k) {
        BodySettings s;
        s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        s.position = up * (0.75 + k);
        s.orientation = tilt;
        top = f.world.addBody(s);
        start = s.position;
    }
    f.simulate(10);
    return (f.position(top) - start).norm();
}

TEST(Physics, ColumnOnARampStandsBelowItsTippingAngleAndFallsBeyond) {
    // 3.4 degrees either side of 18.4: standing, the top box may settle by the slop of its
    // three contacts (0.2 mm each); falling, it ends on the ramp, more than its height away.
    EXPECT_LT(topOfColumnMoved(15), 3 * 0.0002);
    EXPECT_GT(topOfColumnMoved(21.8), 1.0);
}

}  // namespace
}  // namespace cyclone::test
