// A hit is a hit: a sleeping body answers an impact as the same body awake does, and no
// mechanism of the step makes or destroys momentum in an impact.
//
// The impacts are head-on and one-dimensional: a sphere of mass m1 at v along x meets a
// target of mass m2 at rest whose centre of mass is on the line of the impact, so no
// turn is excited and the closed forms hold. With no friction and no gravity, momentum
// and kinetic energy before and after give, for restitution e = 0 (they move together)
//     v1' = v2' = m1 v / (m1 + m2),
// and for e = 1 (momentum and energy both kept)
//     v1' = (m1 - m2) v / (m1 + m2),   v2' = 2 m1 v / (m1 + m2).
#include <algorithm>
#include <string>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

enum class Target { Box, Sphere, Capsule, Cylinder, Hull, Compound };

const char *nameOf(Target t) {
    switch (t) {
        case Target::Box: return "box";
        case Target::Sphere: return "sphere";
        case Target::Capsule: return "capsule";
        case Target::Cylinder: return "cylinder";
        case Target::Hull: return "hull";
        case Target::Compound: return "compound";
    }
    return "?";
}

// Each target reaches 0.5 m from its centre towards -x, where the ball meets it, and is
// symmetric about its centre, so that the centre of mass is on the line of impact.
Shape targetShape(Target t) {
    switch (t) {
        case Target::Box: return Shape::box(Vector3(0.5, 0.5, 0.5));
        case Target::Sphere: return Shape::sphere(0.5);
        case Target::Capsule: return Shape::capsule(0.5, 1.0);   // along z: its round side faces the ball
        case Target::Cylinder: return Shape::cylinder(0.5, 1.0); // likewise
        case Target::Hull: {
            std::vector<Vector3> corners;
            for (int i = 0; i < 8; ++i)
                corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.4 : -0.4, i & 4 ? 0.3 : -0.3);
            return Shape::convex(corners);
        }
        case Target::Compound: {
            // Two slabs one on the other: the ball meets the seam between them, at the
            // centre of mass.
            CompoundChild lower{Shape::box(Vector3(0.5, 0.25, 0.5)), Vector3(0, -0.25, 0), Quaternion::Identity()};
            CompoundChild upper{Shape::box(Vector3(0.5, 0.25, 0.5)), Vector3(0, 0.25, 0), Quaternion::Identity()};
            return Shape::compound({lower, upper});
        }
    }
    return Shape::box(Vector3(0.5, 0.5, 0.5));
}

struct Impact {
    Vector3 ball, target;          // velocities after, m/s
    Vector3 ballSpin, targetSpin;  // rad/s
    real momentumBefore = 0, momentumAfter = 0;  // |linear momentum|, kg m/s
    real energyBefore = 0, energyAfter = 0;      // J
    Vector3 angularAfter;                        // about the origin, kg m^2/s
};

real kineticEnergy(const RigidBody &b) {
    const Vector3 w = b.getRotation();
    const Matrix3 inertia = b.getInertiaTensorWorld();
    return 0.5 * b.getMass() * b.getVelocity().squaredNorm() + 0.5 * w.dot(inertia * w);
}

Vector3 angularMomentum(const RigidBody &b) {
    return b.getPosition().cross(b.getMass() * b.getVelocity()) + b.getInertiaTensorWorld() * b.getRotation();
}

// A ball of m1 at `speed` along x into a target of m2 at rest, asleep or awake, in zero
// gravity with no friction; the state a second after.
Impact hit(Target target, bool asleep, real restitution, real m1 = 2, real m2 = 1, real speed = 6,
           bool ccd = false) {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    World world(settings);
    BodySettings t;
    t.shape = targetShape(target);
    t.mass = m2;
    t.material.friction = 0;
    t.material.restitution = restitution;
    t.awake = !asleep;
    t.canSleep = asleep;  // the awake one stays awake until the ball arrives
    const BodyId targetId = world.addBody(t);
    BodySettings b;
    b.shape = Shape::sphere(0.25);
    b.mass = m1;
    b.position = Vector3(-1.5, 0, 0);
    b.velocity = Vector3(speed, 0, 0);
    b.material.friction = 0;
    b.material.restitution = restitution;
    b.ccd = ccd;
    const BodyId ballId = world.addBody(b);
    Impact out;
    const auto total = [&]() -> Vector3 {
        return world.body(ballId).getMass() * world.body(ballId).getVelocity() +
               world.body(targetId).getMass() * world.body(targetId).getVelocity();
    };
    out.momentumBefore = total().norm();
    out.energyBefore = kineticEnergy(world.body(ballId)) + kineticEnergy(world.body(targetId));
    EXPECT_EQ(world.body(targetId).getAwake(), !asleep);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    out.ball = world.body(ballId).getVelocity();
    out.target = world.body(targetId).getVelocity();
    out.ballSpin = world.body(ballId).getRotation();
    out.targetSpin = world.body(targetId).getRotation();
    out.momentumAfter = total().norm();
    out.energyAfter = kineticEnergy(world.body(ballId)) + kineticEnergy(world.body(targetId));
    out.angularAfter = angularMomentum(world.body(ballId)) + angularMomentum(world.body(targetId));
    return out;
}

const Target kTargets[] = {Target::Box,  Target::Sphere,   Target::Capsule,
                           Target::Cylinder, Target::Hull, Target::Compound};

// Momentum to 1e-9 (relative), no energy gained, no turn, and the closed form's speeds.
void expectHonest(const Impact &i, real expectBall, real expectTarget, const std::string &what) {
    SCOPED_TRACE(what);
    EXPECT_NEAR(i.momentumAfter, i.momentumBefore, 1e-9 * i.momentumBefore);
    EXPECT_LE(i.energyAfter, i.energyBefore * (1 + 1e-12));
    // The ball starts on the x axis and moves along it: its angular momentum about the
    // origin is zero, and so must the total's stay.
    EXPECT_LT(i.angularAfter.norm(), 1e-9 * i.momentumBefore);
    EXPECT_NEAR(i.ball.x(), expectBall, 0.01 * std::abs(i.momentumBefore));
    EXPECT_NEAR(i.target.x(), expectTarget, 0.01 * std::abs(i.momentumBefore));
    EXPECT_LT(i.target.tail<2>().norm(), 1e-6);
    EXPECT_LT(i.targetSpin.norm(), 1e-6);
}

TEST(SleepingHits, PlasticImpactMovesTheTargetAsleepAsAwake) {
    // e = 0, m1 = 2, m2 = 1, v = 6: both leave at 2 * 6 / 3 = 4 m/s.
    for (Target t : kTargets) {
        const Impact awake = hit(t, false, 0);
        const Impact asleep = hit(t, true, 0);
        expectHonest(awake, 4, 4, std::string(nameOf(t)) + " awake");
        expectHonest(asleep, 4, 4, std::string(nameOf(t)) + " asleep");
        EXPECT_NEAR(asleep.target.x(), awake.target.x(), 0.05 * awake.target.x()) << nameOf(t);
    }
}

TEST(SleepingHits, ElasticImpactMovesTheTargetAsleepAsAwake) {
    // e = 1, m1 = 2, m2 = 1, v = 6: the ball goes on at (2 - 1) 6 / 3 = 2 m/s, the target
    // leaves at 2 * 2 * 6 / 3 = 8 m/s.
    for (Target t : kTargets) {
        const Impact awake = hit(t, false, 1);
        const Impact asleep = hit(t, true, 1);
        expectHonest(awake, 2, 8, std::string(nameOf(t)) + " awake");
        expectHonest(asleep, 2, 8, std::string(nameOf(t)) + " asleep");
        EXPECT_NEAR(asleep.target.x(), awake.target.x(), 0.05 * awake.target.x()) << nameOf(t);
    }
}

TEST(SleepingHits, BilliardsCueBallStopsAndTheStruckBallLeaves) {
    // Equal masses, e = 1: the cue ball stops and the struck one takes its 7 m/s.
    const Impact i = hit(Target::Sphere, true, 1, 1, 1, 7);
    expectHonest(i, 0, 7, "billiards");
}

TEST(SleepingHits, FastCcdBallIntoASleepingBoxKeepsMomentum) {
    // 120 m/s: 2 m a step, four times the target's width; the sweep stops the ball at
    // the surface with its velocity, and the next step's contact shares it (e = 0: both
    // at 2 * 120 / 3 = 80 m/s).
    const Impact i = hit(Target::Box, true, 0, 2, 1, 120, true);
    expectHonest(i, 80, 80, "ccd");
}

// A sleeping target on the ground and a ball rolling into it, as in a game.
struct GroundHit {
    real awakeSpeed = 0, asleepSpeed = 0;  // the target's fastest horizontal speed, m/s
};

real fastestAfterHit(const Shape &targetShape, const Quaternion &q, real targetMass, bool asleep, real ballSpeed) {
    World world;
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    BodySettings t;
    t.shape = targetShape;
    t.orientation = q;
    t.mass = targetMass;
    t.position = Vector3(0, 0.5, 0);
    t.canSleep = asleep;
    const BodyId target = world.addBody(t);
    // Settle: asleep, or awake at rest (it cannot sleep).
    for (int i = 0; i < 120; ++i) world.step(kDt);
    EXPECT_EQ(world.body(target).getAwake(), !asleep);
    BodySettings b;
    b.shape = Shape::sphere(0.4);
    b.mass = 5;
    b.position = Vector3(-3, 0.4, 0);
    b.velocity = Vector3(ballSpeed, 0, 0);
    b.rotation = Vector3(0, 0, -ballSpeed / 0.4);  // rolling without slipping
    world.addBody(b);
    real fastest = 0;
    for (int i = 0; i < 90; ++i) {
        world.step(kDt);
        const Vector3 v = world.body(target).getVelocity();
        fastest = std::max(fastest, std::hypot(v.x(), v.z()));
    }
    return fastest;
}

TEST(SleepingHits, ARollingBallKnocksASleepingTargetAsAnAwakeOne) {
    // A 5 kg ball at 7 m/s into a 1 kg target: e = 0 gives the target at least
    // 5 * 7 / 6 = 5.8 m/s; the awake target's speed is the reference.
    const Quaternion upright(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitX()));
    struct Case {
        const char *name;
        Shape shape;
        Quaternion q;
    } cases[] = {{"box", Shape::box(Vector3(0.5, 0.5, 0.5)), Quaternion::Identity()},
                 {"capsule", Shape::capsule(0.3, 0.4), upright},
                 {"cylinder", Shape::cylinder(0.5, 1.0), upright}};
    for (const Case &c : cases) {
        const real awake = fastestAfterHit(c.shape, c.q, 1, false, 7);
        const real asleep = fastestAfterHit(c.shape, c.q, 1, true, 7);
        EXPECT_GT(awake, 5.0) << c.name;
        EXPECT_NEAR(asleep, awake, 0.05 * awake) << c.name;
    }
}

TEST(SleepingHits, AKinematicBodyPushesASleepingBoxInsteadOfSinkingIntoIt) {
    // A kinematic slab at 10 m/s meets a sleeping 1 kg box in zero gravity: the box is
    // pushed ahead at the slab's speed (e = 0) and never lets it in deeper than the slop.
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    World world(settings);
    BodySettings box;
    box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    box.awake = false;
    box.material.friction = 0;
    const BodyId target = world.addBody(box);
    BodySettings k;
    k.motion = Motion::Kinematic;
    k.shape = Shape::box(Vector3(0.1, 1, 1));
    k.position = Vector3(-2, 0, 0);
    k.velocity = Vector3(10, 0, 0);
    const BodyId pusher = world.addBody(k);
    real deepest = 0;
    for (int i = 0; i < 30; ++i) {
        world.step(kDt);
        const real gap = (world.body(target).getPosition().x() - 0.5) - (world.body(pusher).getPosition().x() + 0.1);
        deepest = std::max(deepest, -gap);
    }
    EXPECT_NEAR(world.body(target).getVelocity().x(), 10, 0.05);
    EXPECT_LT(deepest, 0.01);
}

TEST(SleepingHits, AJoinedSleepingPairIsHitWithItsWholeMass) {
    // Two 1 kg boxes joined by a ball joint, asleep, hit by a 2 kg ball at 6 m/s along
    // their line, e = 0, zero gravity: the three move together at 2 * 6 / 4 = 3 m/s.
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    World world(settings);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.material.friction = 0;
    s.awake = false;
    const BodyId near = world.addBody(s);
    s.position = Vector3(1.5, 0, 0);
    const BodyId far = world.addBody(s);
    JointSettings j;
    j.type = JointType::Ball;
    j.a = near;
    j.b = far;
    j.anchor = Vector3(0.75, 0, 0);
    world.addJoint(j);
    BodySettings b;
    b.shape = Shape::sphere(0.25);
    b.mass = 2;
    b.position = Vector3(-1.5, 0, 0);
    b.velocity = Vector3(6, 0, 0);
    b.material.friction = 0;
    const BodyId ball = world.addBody(b);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    const real p = 2 * world.body(ball).getVelocity().x() + world.body(near).getVelocity().x() +
                   world.body(far).getVelocity().x();
    EXPECT_NEAR(p, 12, 12e-9);
    // The contact and the joint are solved in turn, a finite number of passes: the pair
    // leaves the ball a little faster than the closed form (1 % measured), as it does
    // when the pair is awake.
    EXPECT_NEAR(world.body(far).getVelocity().x(), 3, 0.06);
    EXPECT_NEAR(world.body(near).getVelocity().x(), 3, 0.06);
}


// Ten bowling pins (1.5 kg cylinders, 0.38 m tall, 0.12 m across, 12 inches apart) asleep
// on the lane when a 7 kg ball arrives at `speed`; how many lie down at the end, with
// their axis within 45 degrees of the floor.
int pinsDown(real speed, int threads = 1) {
    WorldSettings settings;
    settings.threads = threads;
    World world(settings);
    BodySettings lane;
    lane.motion = Motion::Static;
    lane.shape = Shape::plane(Vector3::UnitY(), 0);
    lane.material.friction = 0.2;
    world.addBody(lane);
    std::vector<BodyId> pins;
    const real spacing = 0.3048;
    for (int row = 0; row < 4; ++row)
        for (int k = 0; k <= row; ++k) {
            BodySettings pin;
            pin.shape = Shape::cylinder(0.06, 0.38);
            pin.mass = 1.5;
            pin.material.friction = 0.4;
            pin.orientation = Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitX()));
            pin.position = Vector3(4 + row * spacing * std::sqrt(3.0) / 2, 0.19, (k - row / 2.0) * spacing);
            pins.push_back(world.addBody(pin));
        }
    for (int i = 0; i < 90; ++i) world.step(kDt);
    for (BodyId pin : pins) EXPECT_FALSE(world.body(pin).getAwake());  // asleep before the ball comes
    BodySettings ball;
    ball.shape = Shape::sphere(0.108);
    ball.mass = 7;
    ball.position = Vector3(0, 0.108, 0.03);
    ball.velocity = Vector3(speed, 0, 0);
    ball.rotation = Vector3(0, 0, -speed / 0.108);
    ball.material.friction = 0.2;
    world.addBody(ball);
    for (int i = 0; i < 180; ++i) world.step(kDt);
    int down = 0;
    for (BodyId pin : pins) {
        const Vector3 axis = world.body(pin).getTransform().linear() * Vector3::UnitZ();
        if (std::abs(axis.y()) < std::sqrt(0.5)) ++down;
    }
    return down;
}

TEST(SleepingHits, ABowlingBallKnocksMostOfTenSleepingPinsDown) {
    for (real speed : {7.0, 8.0}) EXPECT_GE(pinsDown(speed), 6) << speed << " m/s";
}

// A wall of 80 bricks (0.2 x 0.2 x 0.4 m, 2 kg, in staggered courses) asleep when a 50 kg
// ball rolls into it at 13.4 m/s.
struct WallHit {
    int knockedOut = 0;     // bricks moved more than a brick's depth
    real fastest = 0;       // m/s, any brick at any step
    std::vector<RigidBody> end;
};

WallHit hitWall(int threads) {
    WorldSettings settings;
    settings.threads = threads;
    World world(settings);
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    std::vector<BodyId> bricks;
    for (int course = 0; course < 8; ++course)
        for (int k = 0; k < 10; ++k) {
            BodySettings brick;
            brick.shape = Shape::box(Vector3(0.1, 0.1, 0.2));
            brick.mass = 2;
            brick.position = Vector3(0, 0.1 + 0.2 * course, -1.8 + 0.4 * k + (course % 2 ? 0.2 : 0.0));
            bricks.push_back(world.addBody(brick));
        }
    for (int i = 0; i < 150; ++i) world.step(kDt);
    int asleep = 0;
    for (BodyId b : bricks) asleep += !world.body(b).getAwake();
    EXPECT_GE(asleep, 76) << "the wall should be asleep before the ball comes";
    BodySettings ball;
    ball.shape = Shape::sphere(0.4);
    ball.mass = 50;
    ball.position = Vector3(-4, 0.4, 0.1);
    ball.velocity = Vector3(13.4, 0, 0);
    ball.rotation = Vector3(0, 0, -13.4 / 0.4);
    world.addBody(ball);
    WallHit out;
    std::vector<Vector3> start;
    for (BodyId b : bricks) start.push_back(world.body(b).getPosition());
    for (int i = 0; i < 120; ++i) {
        world.step(kDt);
        for (BodyId b : bricks) out.fastest = std::max(out.fastest, world.body(b).getVelocity().norm());
    }
    for (std::size_t k = 0; k < bricks.size(); ++k) {
        if ((world.body(bricks[k]).getPosition() - start[k]).norm() > 0.2) ++out.knockedOut;
        out.end.push_back(world.body(bricks[k]));
    }
    return out;
}

TEST(SleepingHits, AHeavyBallKnocksBricksOutOfASleepingWallNoneFasterThan20) {
    // The ball's 13.4 m/s bounds what it can give a brick in an elastic-free hit:
    // 2 * 50 / 52 * 13.4 = 25.8 m/s at the very most; bricks slowed by the wall's other
    // bricks leave well below it, and nothing may fly off faster than 20 m/s.
    const WallHit one = hitWall(1);
    EXPECT_GE(one.knockedOut, 10);
    EXPECT_LE(one.fastest, 20);
    const WallHit two = hitWall(2);
    ASSERT_EQ(one.end.size(), two.end.size());
    for (std::size_t k = 0; k < one.end.size(); ++k) EXPECT_TRUE(sameBits(one.end[k], two.end[k])) << "brick " << k;
}

// A column of three 1 kg boxes on the ground, asleep or awake (it cannot sleep), hit at
// its bottom box by a 5 kg ball at 7 m/s: the bottom box's fastest speed.
real hitStack(bool asleep) {
    World world;
    addStatic(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    std::vector<BodyId> boxes;
    for (int k = 0; k < 3; ++k) {
        BodySettings box;
        box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        box.position = Vector3(0, 0.5 + k, 0);
        box.canSleep = asleep;
        boxes.push_back(world.addBody(box));
    }
    for (int i = 0; i < 120; ++i) world.step(kDt);
    for (BodyId b : boxes) EXPECT_EQ(world.body(b).getAwake(), !asleep);
    BodySettings ball;
    ball.shape = Shape::sphere(0.4);
    ball.mass = 5;
    ball.position = Vector3(-3, 0.4, 0);
    ball.velocity = Vector3(7, 0, 0);
    ball.rotation = Vector3(0, 0, -7 / 0.4);
    world.addBody(ball);
    real fastest = 0;
    for (int i = 0; i < 60; ++i) {
        world.step(kDt);
        fastest = std::max(fastest, world.body(boxes[0]).getVelocity().norm());
    }
    return fastest;
}

TEST(SleepingHits, ASleepingStackIsHitAsAnAwakeOne) {
    const real awake = hitStack(false);
    const real asleep = hitStack(true);
    EXPECT_GT(awake, 1.0);
    EXPECT_NEAR(asleep, awake, 0.05 * awake);
}

}  // namespace
}  // namespace cyclone::test
