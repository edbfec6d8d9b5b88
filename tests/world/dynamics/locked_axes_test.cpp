// Locked axes (BodySettings::lockedAxes, World::setLockedAxes): a body never moves along
// or turns about a locked world axis, whatever contacts, joints, springs or gravity do.
#include <algorithm>
#include <cmath>
#include <string>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

LockedAxes planar() {  // a 2D body in the x-y plane
    LockedAxes l;
    l.z = l.rx = l.ry = true;
    return l;
}

BodySettings lockedBox(const Vector3 &position, const LockedAxes &locks, const Vector3 &half = Vector3(0.5, 0.5, 0.5)) {
    BodySettings s;
    s.shape = Shape::box(half);
    s.position = position;
    s.lockedAxes = locks;
    return s;
}

// A ground box turned 25 degrees about x and 15 about z: its top face's normal has x, y and
// z components, so every contact pushes the locked box along z and turns it about x and y.
// Locked, its z stays 0.3 (the step puts it back on the value it began with: no rounding
// accumulates) and its orientation, identity at the start, only ever turns about z: the
// quaternion's x and y stay exactly 0. Checked after every step, at two step sizes.
TEST(LockedAxes, APlanarBodyStaysInItsPlaneOnATiltedSlope) {
    for (const double dt : {kDt, kDt / 2}) {
        WorldFixture f(noSleep());
        const Quaternion tilt = Quaternion(Eigen::AngleAxisd(0.436, Vector3::UnitX())) *
                                Quaternion(Eigen::AngleAxisd(0.262, Vector3::UnitZ()));
        f.staticBox(Vector3(0, -1, 0), Vector3(5, 1, 5), tilt);
        const BodyId box = f.world.addBody(lockedBox(Vector3(0, 1.5, 0.3), planar()));
        BodySettings ball;
        ball.shape = Shape::sphere(0.3);
        ball.position = Vector3(0.2, 3, 0.5);
        ball.lockedAxes = planar();
        const BodyId sphere = f.world.addBody(ball);
        const int steps = static_cast<int>(std::lround(3 / dt));
        for (int i = 0; i < steps; ++i) {
            f.world.step(dt);
            for (const BodyId id : {box, sphere}) {
                const RigidBody &b = f.world.body(id);
                ASSERT_EQ(b.getPosition().z(), id == box ? 0.3 : 0.5) << "step " << i;
                ASSERT_EQ(b.getOrientation().x(), 0) << "step " << i;
                ASSERT_EQ(b.getOrientation().y(), 0) << "step " << i;
                ASSERT_EQ(b.getVelocity().z(), 0);
                ASSERT_EQ(b.getRotation().x(), 0);
                ASSERT_EQ(b.getRotation().y(), 0);
            }
        }
        // It did move in its plane: the contacts pushed it and gravity pulled it.
        EXPECT_LT(f.position(box).y(), 1.4) << dt;
    }
}

// A spring (50 N/m, rest length 0) to the world point (1, 0, 4) from the body point
// (0.5, 0.5, 0.5) pulls a 1 kg body along x, y and z; locked along z and in every rotation,
// it swings in x-y only, never turning. Along x the force is 50 (1 - 0.5 - x), so x swings
// as 0.5 - 0.5 cos(sqrt(50) t): its largest value over 3 s is close to 1. Joints too: a box hanging from a
// ball joint at (0, 2, 0) with its anchor point 1 m off in z, which gravity would swing
// out of the plane, keeps its z and orientation.
TEST(LockedAxes, SpringsAndJointsDoNotMoveALockedAxis) {
    WorldFixture f(noSleep());
    LockedAxes locks;
    locks.z = locks.rx = locks.ry = locks.rz = true;
    const BodyId pulled = f.world.addBody(lockedBox(Vector3(0, 0, 0), locks));
    SpringSettings spring;
    spring.a = pulled;
    spring.aPoint = Vector3(0.5, 0.5, 0.5);  // off the centre: it would turn the body
    spring.bPoint = Vector3(1, 0, 4);
    spring.stiffness = 50;
    spring.restLength = 0;
    f.world.addSpring(spring);
    const BodyId hanging = f.world.addBody(lockedBox(Vector3(5, 1, 0), planar()));
    JointSettings joint;
    joint.type = JointType::Ball;
    joint.a = hanging;
    joint.anchor = Vector3(5, 1, 1);  // beside the box, off its plane
    f.world.addJoint(joint);
    real farthest = 0;
    for (int i = 0; i < 180; ++i) {
        f.world.step(kDt);
        farthest = std::max(farthest, f.position(pulled).x());
        ASSERT_EQ(f.position(pulled).z(), 0);
        ASSERT_EQ(f.world.body(pulled).getOrientation().coeffs(), Quaternion::Identity().coeffs());
        ASSERT_EQ(f.position(hanging).z(), 0);
        ASSERT_EQ(f.world.body(hanging).getOrientation().x(), 0);
        ASSERT_EQ(f.world.body(hanging).getOrientation().y(), 0);
    }
    EXPECT_GT(farthest, 0.9) << "the spring's x pull acts";
    EXPECT_LT(farthest, 1.1);
}

// With all three translations locked the solver gives the body zero inverse mass: a box
// dropped onto it is stopped (as by a static one) and the locked box stays where it was,
// to the bit; its rotations, free, are turned by the off-centre hit.
TEST(LockedAxes, AllTranslationsLockedStaysPut) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3(0, -9.81, 0);
    WorldFixture f(settings);
    LockedAxes pinned;
    pinned.x = pinned.y = pinned.z = true;
    const BodyId pivot = f.world.addBody(lockedBox(Vector3(0, 0, 0), pinned, Vector3(1, 0.1, 0.2)));
    const BodyId dropped = f.box(Vector3(0.8, 0.7, 0), Vector3(0.1, 0.1, 0.1));
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        ASSERT_EQ(f.position(pivot), Vector3::Zero());
    }
    EXPECT_GT(std::abs(f.world.body(pivot).getRotation().z()), 0.01) << "the hit turned it about z";
    EXPECT_LT(f.position(dropped).y(), 0.7);
}

// The rotation locks alone keep a box upright: it lands on a 20-degree slope on an edge
// first, which would tip it over, and slides down without ever turning.
TEST(LockedAxes, RotationLocksKeepABodyUpright) {
    WorldFixture f(noSleep());
    f.staticBox(Vector3(0, -1, 0), Vector3(10, 1, 10), Quaternion(Eigen::AngleAxisd(0.349, Vector3::UnitZ())));
    LockedAxes upright;
    upright.rx = upright.ry = upright.rz = true;
    BodySettings s = lockedBox(Vector3(0, 1.5, 0), upright);
    s.material.friction = 0.1;
    const BodyId box = f.world.addBody(s);
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        ASSERT_EQ(f.world.body(box).getOrientation().coeffs(), Quaternion::Identity().coeffs()) << i;
    }
    EXPECT_LT(f.position(box).x(), -0.1) << "it slid down the slope (towards -x)";
}

// The setter locks from the body's current pose, drops the locked velocity at once and is
// read back; static bodies are refused, and a refusal changes nothing.
TEST(LockedAxes, SetterAndRefusals) {
    WorldFixture f(noSleep());
    const BodyId box = f.box(Vector3(0, 5, 2));
    f.world.setVelocity(box, Vector3(1, 2, 3));
    f.world.setLockedAxes(box, planar());
    EXPECT_EQ(f.world.body(box).getVelocity(), Vector3(1, 2, 0));
    EXPECT_EQ(f.world.lockedAxes(box), planar());
    f.world.step(kDt);
    EXPECT_EQ(f.position(box).z(), 2);
    const BodyId ground = f.ground();
    try {
        f.world.setLockedAxes(ground, planar());
        FAIL() << "a static body was locked";
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::setLockedAxes");
    }
    EXPECT_FALSE(f.world.lockedAxes(ground).any());
    f.world.setLockedAxes(box, LockedAxes());
    f.world.setVelocity(box, Vector3(0, 0, 1));
    f.world.step(kDt);
    EXPECT_GT(f.position(box).z(), 2) << "unlocked, it moves along z again";
}

}  // namespace
}  // namespace cyclone::test
