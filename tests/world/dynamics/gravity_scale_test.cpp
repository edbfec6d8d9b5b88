// Gravity scale per body (BodySettings::gravityScale, World::setGravityScale).
#include <string>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A free body of scale s under gravity g accelerates at s g. With one sub-step the
// integrator is symplectic Euler: after n steps of h, v = n h s g and the body has moved
// s g h^2 (1 + 2 + ... + n) = s g h^2 n (n + 1) / 2. With s = -0.5 and g = -9.81 m/s^2
// the body rises at 4.905 m/s^2: after 60 steps of 1/60 s, v = +4.905 m/s and it has
// risen 4.905 * 61 / 120 = 2.4933750 m; after 120 steps of 1/120 s, 4.905 m/s and
// 4.905 * 121 / 240 = 2.4729375 m. A body of scale 1 beside it falls at g.
TEST(GravityScale, ANegativeHalfRisesAtHalfOfG) {
    for (const int n : {60, 120}) {
        const double h = 1.0 / n;
        WorldSettings settings = noSleep();
        settings.substeps = 1;
        WorldFixture f(settings);
        BodySettings s;
        s.shape = Shape::sphere(0.5);
        s.gravityScale = -0.5;
        const BodyId balloon = f.world.addBody(s);
        s.gravityScale = 1;
        s.position = Vector3(5, 0, 0);
        const BodyId stone = f.world.addBody(s);
        for (int i = 0; i < n; ++i) f.world.step(h);
        EXPECT_NEAR(f.world.body(balloon).getVelocity().y(), 0.5 * kG, 1e-12) << n;
        EXPECT_NEAR(f.position(balloon).y(), 0.5 * kG * (n + 1) / (2.0 * n), 1e-12) << n;
        EXPECT_NEAR(f.world.body(stone).getVelocity().y(), -kG, 1e-12) << n;
        EXPECT_DOUBLE_EQ(f.world.gravityScale(balloon), -0.5);
    }
}

// Scale 0 floats in place; setGravityScale takes effect from the next step, wakes the
// body, and survives a change of the world's gravity (the scale multiplies the new one).
TEST(GravityScale, TheSetterActsAndFollowsTheWorldsGravity) {
    WorldSettings settings;
    settings.substeps = 1;
    WorldFixture f(settings);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.gravityScale = 0;
    s.awake = false;
    const BodyId box = f.world.addBody(s);
    f.world.setGravityScale(box, 2);
    EXPECT_TRUE(f.awake(box));
    f.world.step(0.1);
    // one step of 0.1 s at 2 g: v = -1.962 m/s
    EXPECT_NEAR(f.world.body(box).getVelocity().y(), -2 * kG * 0.1, 1e-12);
    WorldSettings up = settings;
    up.gravity = Vector3(0, 3, 0);
    f.world.setSettings(up);
    f.world.step(0.1);
    // then 0.1 s at 2 * 3 m/s^2 upwards: -1.962 + 0.6 = -1.362 m/s
    EXPECT_NEAR(f.world.body(box).getVelocity().y(), -2 * kG * 0.1 + 0.6, 1e-12);
}

// Refusals name the function, the field and the value, and change nothing.
TEST(GravityScale, BadScalesAreRefused) {
    WorldFixture f;
    BodySettings s;
    s.shape = Shape::sphere(0.5);
    s.gravityScale = kNaN;
    try {
        f.world.addBody(s);
        FAIL() << "a NaN gravity scale was accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::addBody");
        EXPECT_EQ(e.field(), "gravityScale");
        EXPECT_NE(e.problem().find("nan"), std::string::npos) << e.what();
    }
    EXPECT_EQ(f.world.bodyCount(), 0u);
    s.gravityScale = 1;
    const BodyId ball = f.world.addBody(s);
    try {
        f.world.setGravityScale(ball, 1e308);  // times 9.81 overflows
        FAIL() << "an overflowing gravity scale was accepted";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::setGravityScale");
        EXPECT_EQ(e.field(), "scale");
        EXPECT_NE(e.problem().find("1e+308"), std::string::npos) << e.what();
    }
    EXPECT_EQ(f.world.gravityScale(ball), 1);
    const BodyId ground = f.ground();
    EXPECT_THROW(f.world.setGravityScale(ground, 0), InvalidArgument);
}

}  // namespace
}  // namespace cyclone::test
