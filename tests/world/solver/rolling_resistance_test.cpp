// Rolling and spinning resistance (Material::rollingFriction, spinningFriction): a ball
// decelerates and stops as the torque limit says, a scene without them makes no rows.
#include <string>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


struct Resistance {
    real rolling = 0;
    real spinning = 0;
};

// Ground and a 1 kg ball of radius 0.25 m resting on it, with the given lengths.
struct BallOnGround {
    WorldFixture f;
    BodyId ground;
    BodyId ball;
    explicit BallOnGround(Resistance groundR, Resistance ballR, const WorldSettings &s = noSleep()) : f(s) {
        BodySettings g;
        g.motion = Motion::Static;
        g.shape = Shape::plane(Vector3::UnitY(), 0);
        g.material.rollingFriction = groundR.rolling;
        g.material.spinningFriction = groundR.spinning;
        ground = f.world.addBody(g);
        BodySettings b;
        b.shape = Shape::sphere(0.25);
        b.position = Vector3(0, 0.25, 0);
        b.material.rollingFriction = ballR.rolling;
        b.material.spinningFriction = ballR.spinning;
        ball = f.world.addBody(b);
    }
    // Rolling along x at v: w = v / r about -z.
    void roll(real v) {
        f.world.setVelocity(ball, Vector3(v, 0, 0));
        f.world.setRotation(ball, Vector3(0, 0, -v / 0.25));
    }
};

// A solid ball (I = 0.4 m r^2) rolling without slipping against a torque mu_r m g loses
// energy at mu_r m g w = mu_r m g v / r, so (m + I / r^2) v dv/dt = -mu_r m g v / r:
// a = mu_r g / (1.4 r). With mu_r = 1 cm, r = 0.25 m: 0.2803 m/s^2; from 2 m/s, v(2 s) =
// 1.439 m/s, stopped after 2 / a = 7.14 s and 7.14 m.
// The rows' limit is the normal impulse the contact held when the sub-step began (its warm
// start, rolling_resistance.h): m g h in every sub-step once the ball rests on the plane,
// so the rate holds to 1 % at 120 Hz and at 60 Hz. At 60 Hz the contact point moves
// 3.3 cm a step on both bodies, beyond the 2.5 cm within which an anchor matches; the
// point keeps its impulse because it stays below the ball's centre (pair_cache.h), and
// without that every step's first sub-step would have no limit (the rate 3/4 of this).
TEST(RollingResistance, ABallRollingDeceleratesAtMuRGOverOnePointFourR) {
    const real a = 0.01 * kG / (1.4 * 0.25);
    {
        BallOnGround s({0, 0}, {0.01, 0});
        s.roll(2);
        s.f.simulate(2, kDt / 2);
        const RigidBody &b = s.f.world.body(s.ball);
        EXPECT_NEAR(b.getVelocity().x(), 2 - a * 2, 0.01 * a * 2);
        EXPECT_NEAR(b.getRotation().z(), -b.getVelocity().x() / 0.25, 0.01) << "rolls without slipping";
        EXPECT_NEAR(s.f.position(s.ball).x(), 2 * 2 - a * 2 * 2 / 2, 0.02);
        s.f.simulate(5.5, kDt / 2);  // 7.5 s in all: past 2 / a = 7.14 s
        EXPECT_LT(s.f.world.body(s.ball).getVelocity().norm(), 1e-3);
        EXPECT_NEAR(s.f.position(s.ball).x(), 2 * 2 / (2 * a), 0.1);
    }
    {
        BallOnGround s({0, 0}, {0.01, 0});
        s.roll(2);
        s.f.simulate(2, kDt);
        const real measured = (2 - s.f.world.body(s.ball).getVelocity().x()) / 2;
        EXPECT_NEAR(measured, a, 0.01 * a);
    }
}

// A pair uses the larger length: the ground's 1 cm acts on a ball of 0.
TEST(RollingResistance, APairUsesTheLargerLength) {
    const real a = 0.01 * kG / (1.4 * 0.25);
    BallOnGround s({0.01, 0}, {0, 0});
    s.roll(2);
    s.f.simulate(2, kDt / 2);
    EXPECT_NEAR(s.f.world.body(s.ball).getVelocity().x(), 2 - a * 2, 0.01 * a * 2);
}

// Without resistance a ball rolls on at its speed (to 0.25 %), and no row is made.
TEST(RollingResistance, ZeroLengthsMakeNoRowsAndTheBallRollsOn) {
    BallOnGround s({0, 0}, {0, 0});
    s.roll(2);
    s.f.simulate(2);
    EXPECT_NEAR(s.f.world.body(s.ball).getVelocity().x(), 2, 0.005);
    EXPECT_EQ(s.f.world.stats().resistanceRows, 0);
}

// A ball spinning about the vertical at w0 against a torque mu_s m g slows at
// mu_s g / (0.4 r^2): 5 mm on r = 0.25 m is 1.962 rad/s^2; from 5 rad/s, 3.04 rad/s at
// 1 s, stopped at 2.55 s, and (sleep on) asleep within sleepDelay of stopping.
TEST(SpinningResistance, ABallSpinningInPlaceStopsAndSleeps) {
    const real alpha = 0.005 * kG / (0.4 * 0.25 * 0.25);
    WorldSettings settings;
    BallOnGround s({0, 0}, {0, 0.005}, settings);
    s.f.world.setRotation(s.ball, Vector3(0, 5, 0));
    s.f.simulate(1);
    EXPECT_NEAR(s.f.world.body(s.ball).getRotation().y(), 5 - alpha, 0.03);
    EXPECT_EQ(s.f.world.stats().resistanceRows, 1) << "a spinning row, no rolling rows";
    s.f.simulate(5 / alpha - 1 + 0.05);
    EXPECT_LT(s.f.world.body(s.ball).getRotation().norm(), 0.01);
    s.f.simulate(0.45);
    EXPECT_FALSE(s.f.awake(s.ball));
}

// The defaults are small but not zero: a ball spinning in place stops within a few seconds.
TEST(SpinningResistance, DefaultsStopASpinningBallWithinAFewSeconds) {
    const Material defaults;
    EXPECT_GT(defaults.rollingFriction, 0);
    EXPECT_GT(defaults.spinningFriction, 0);
    WorldFixture f;
    f.ground();
    const BodyId ball = f.sphere(Vector3(0, 0.25, 0), 0.25);
    f.world.setRotation(ball, Vector3(0, 5, 0));
    f.simulate(4);
    EXPECT_FALSE(f.awake(ball));
}

// A box resting on a face (four points) resists rolling and spinning through its points
// and its patch's twist: no resistance rows; a ball on the ground has three.
TEST(RollingResistance, AFaceContactMakesNoRowsAPointContactThree) {
    WorldFixture f(noSleep());
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    f.simulate(0.1);
    EXPECT_EQ(f.world.stats().resistanceRows, 0);
    f.sphere(Vector3(3, 0.25, 0), 0.25);
    f.simulate(0.1);
    EXPECT_EQ(f.world.stats().resistanceRows, 3);
}

TEST(RollingResistance, NegativeLengthsAreRefused) {
    WorldFixture f;
    const BodyId ground = f.ground();
    const BodyId ball = f.sphere(Vector3(0, 0.25, 0), 0.25);
    Material m;
    m.rollingFriction = -0.5;
    try {
        f.world.setMaterial(ball, m);
        FAIL();
    } catch (const InvalidArgument &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("World::setMaterial"), std::string::npos) << what;
        EXPECT_NE(what.find("rollingFriction"), std::string::npos) << what;
        EXPECT_NE(what.find("-0.5"), std::string::npos) << what;
    }
    EXPECT_EQ(f.world.material(ball).rollingFriction, Material().rollingFriction);
    m.rollingFriction = 0;
    m.spinningFriction = -1;
    EXPECT_THROW(f.world.setMaterial(ground, m), InvalidArgument);
    BodySettings b;
    b.shape = Shape::sphere(0.25);
    b.material.spinningFriction = NAN;
    try {
        f.world.addBody(b);
        FAIL();
    } catch (const InvalidArgument &e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("World::addBody"), std::string::npos) << what;
        EXPECT_NE(what.find("material.spinningFriction"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace cyclone::test
