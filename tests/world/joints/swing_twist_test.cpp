// Ball joints' swing cones and twist ranges: a rod kicked in every direction stays in
// its elliptic cone and twist range, a heavy load rests on the cone's edge at its
// half-angle, and the API refuses bad limits.
#include <cmath>
#include <string>

#include "joints/joint_fixture.h"

namespace cyclone::test {
namespace {

// The rod's lean from the cone axis, measured from the poses alone: theta is the angle
// between a's twist axis n_c and b's n_m, its direction phi the angle of n_m's part
// across n_c from the normal towards n_c x normal. The cone allows
// theta <= theta_max(phi) = 1 / sqrt((cos phi / A)^2 + (sin phi / B)^2), which is A
// along the normal and B across it.
struct Lean {
    real theta = 0;
    real allowed = 0;  ///< theta_max(phi), rad.
};

Lean leanOf(const Vector3 &nc, const Vector3 &normal, const Vector3 &nm, const JointSwingLimit &cone) {
    Lean lean;
    lean.theta = std::atan2(nc.cross(nm).norm(), nc.dot(nm));
    const Vector3 across = nm - nm.dot(nc) * nc;
    if (!(across.norm() > 1e-12)) {
        lean.allowed = std::min(cone.normalAngle, cone.binormalAngle);
        return lean;
    }
    const real c = across.normalized().dot(normal), s = across.normalized().dot(nc.cross(normal));
    lean.allowed = 1 / std::sqrt(std::pow(c / cone.normalAngle, 2) + std::pow(s / cone.binormalAngle, 2));
    return lean;
}

// The twist of a relative to b about the twist axis (b's body space `axisB`): q =
// conj(q_b) q_a conj(q_b0) q_a0 (here q_a = q_a0 = identity, a static) is a swing after
// a twist psi about axisB, and q.vec . axisB = cos(theta/2) sin(psi/2), q.w =
// cos(theta/2) cos(psi/2), so psi = 2 atan2(q.vec . axisB, q.w).
real twistOf(const Quaternion &qb, const Quaternion &qb0, const Vector3 &axisB) {
    Quaternion q = qb.conjugate() * qb0;
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    return 2 * std::atan2(q.vec().dot(axisB), q.w());
}

BodyId addAnchor(World &world, const Vector3 &at) {
    BodySettings s;
    s.isStatic = true;
    s.shape = Shape::box(Vector3(0.1, 0.1, 0.1));
    s.position = at;
    s.collidesWith = 0;
    return world.addBody(s);
}

// A 1 kg rod 1 m long (0.1 m square) hung below `pivot` from a static anchor 0.2 m above
// it, on a ball joint with the swing and twist limits of `limits` (its bodies, anchor and
// twist axis, -y down the rod, are set here); returns the rod.
BodyId hangRod(World &world, const Vector3 &pivot, const JointSettings &limits) {
    const BodyId anchor = addAnchor(world, pivot + Vector3(0, 0.2, 0));
    const BodyId rod = addBox(world, pivot - Vector3(0, 0.5, 0), Vector3(0.05, 0.5, 0.05), 1);
    JointSettings j = limits;
    j.type = JointType::Ball;
    j.a = anchor;
    j.b = rod;
    j.anchor = pivot;
    j.axis = -Vector3::UnitY();
    world.addJoint(j);
    return rod;
}

// A 1 m rod hangs from a static anchor on a ball joint whose cone (axis down the rod,
// normal +x) allows 0.7 rad towards x and 0.35 rad towards z (axis x normal = -y x x =
// +z), and whose twist range is [-0.5, 0.25] rad. Without gravity, sixteen kicks at 6 m/s
// of the rod's centre in directions round the axis, with a spin of +-4 rad/s about it,
// throw it against the cone, along whose edge it then slides for 3 s. The lean never
// exceeds the cone's theta_max(phi) by more than 0.02 rad, the twist never leaves its
// range by more than 0.02 rad, and both reach their limits (the kicks are hard enough:
// the test fails if the limits were wider than asked).
TEST(SwingTwist, KickedRodStaysInItsEllipticConeAndTwistRange) {
    const JointSwingLimit cone{0.7, 0.35};
    const JointLimits twist{-0.5, 0.25};
    real lowestOfAll = 0, highestOfAll = 0;
    for (int kick = 0; kick < 16; ++kick) {
        WorldSettings settings = noSleep();
        settings.gravity = Vector3::Zero();
        World world(settings);
        JointSettings limits;
        limits.normal = Vector3::UnitX();
        limits.swingLimit = cone;
        limits.twistLimit = twist;
        const BodyId rod = hangRod(world, Vector3(0, 10, 0), limits);
        const real alpha = 2 * kPi * kick / 16;
        world.setVelocity(rod, 6 * Vector3(std::cos(alpha), 0, std::sin(alpha)));
        world.setRotation(rod, Vector3(0, kick % 2 == 0 ? 4 : -4, 0));
        const Quaternion q0 = world.body(rod).getOrientation();
        real worstSwing = -1, fullest = 0, lowest = 0, highest = 0;
        for (int step = 0; step < 180; ++step) {
            world.step(kDt);
            const Quaternion q = world.body(rod).getOrientation();
            const Lean lean = leanOf(-Vector3::UnitY(), Vector3::UnitX(), q * -Vector3::UnitY(), cone);
            worstSwing = std::max(worstSwing, lean.theta - lean.allowed);
            fullest = std::max(fullest, lean.theta / lean.allowed);
            const real psi = twistOf(q, q0, -Vector3::UnitY());
            lowest = std::min(lowest, psi);
            highest = std::max(highest, psi);
        }
        EXPECT_LE(worstSwing, 0.02) << "kick " << kick;
        EXPECT_GE(fullest, 0.98) << "kick " << kick;
        EXPECT_GE(lowest, twist.lower - 0.02) << "kick " << kick;
        EXPECT_LE(highest, twist.upper + 0.02) << "kick " << kick;
        lowestOfAll = std::min(lowestOfAll, lowest);
        highestOfAll = std::max(highestOfAll, highest);
    }
    // Some spin reaches each end of the range (the cone's wall, whose normal has a part
    // about the axis where the cone is elliptic, brakes the spin in some kicks).
    EXPECT_GE(highestOfAll, twist.upper - 0.02);
    EXPECT_LE(lowestOfAll, twist.lower + 0.02);
}

// The same rod spun about its own axis at 2 rad/s without a lean: the twist grows at
// 2 rad/s (the rod turning by +e about +y is q = conj(q_b), a turn by +e about the axis
// -y, so psi = +e) until it reaches the upper limit 0.25 rad at 0.125 s, where it stops.
// Each of the 24 sub-steps (h = 1/240 s) of the first 0.1 s turns the rod by
// q += h/2 (0, w) q and then normalises it, a turn by 2 atan(w h / 2): psi =
// 48 atan(1/240) = 0.1999988 rad then (to 1e-9); from 0.25 s on it stays within 0.02 rad
// of 0.25 rad.
TEST(SwingTwist, SpunRodStopsAtItsTwistLimit) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    World world(settings);
    JointSettings limits;
    limits.twistLimit = JointLimits{-0.5, 0.25};
    const BodyId rod = hangRod(world, Vector3(0, 10, 0), limits);
    world.setRotation(rod, Vector3(0, 2, 0));
    const Quaternion q0 = world.body(rod).getOrientation();
    for (int step = 1; step <= 60; ++step) {
        world.step(kDt);
        const real psi = twistOf(world.body(rod).getOrientation(), q0, -Vector3::UnitY());
        if (step == 6) {
            EXPECT_NEAR(psi, 48 * std::atan(1.0 / 240), 1e-9);
        }
        if (step >= 15) {
            EXPECT_NEAR(psi, 0.25, 0.02) << step;
        }
    }
}

// A 1 kg, 1 m rod laid out along +x from a static anchor, a 100 kg sphere welded to its
// end, on a ball joint whose twist axis is +x and whose cone allows 0.8 rad towards the
// normal +z and 0.4 rad across it (x x z = -y: downwards). Gravity pulls the load down,
// in the cone's binormal plane, so it comes to rest on the cone's lowest point: leaning
// exactly 0.4 rad below the horizontal, which the limit row holds against the load's
// 981 N (the 100:1 mass ratio of the heavy chain tests). Over 5 s the lean never exceeds
// 0.4 rad by more than 0.02 rad, and it ends within 0.02 rad of 0.4 rad, with no drift
// sideways (its z stays 0 by symmetry).
TEST(SwingTwist, HeavyLoadRestsOnTheConesEdgeAtItsHalfAngle) {
    World world(noSleep());
    const Vector3 pivot(0, 10, 0);
    const BodyId anchor = addAnchor(world, pivot - Vector3(0.2, 0, 0));
    const BodyId rod = addBox(world, pivot + Vector3(0.5, 0, 0), Vector3(0.5, 0.05, 0.05), 1);
    BodySettings ball;
    ball.shape = Shape::sphere(0.3);
    ball.mass = 100;
    ball.position = pivot + Vector3(1.3, 0, 0);
    ball.collidesWith = 0;
    const BodyId load = world.addBody(ball);
    JointSettings weld;
    weld.type = JointType::Fixed;
    weld.a = load;
    weld.b = rod;
    weld.anchor = pivot + Vector3(1, 0, 0);
    world.addJoint(weld);
    JointSettings j;
    j.type = JointType::Ball;
    j.a = anchor;
    j.b = rod;
    j.anchor = pivot;
    j.axis = Vector3::UnitX();
    j.normal = Vector3::UnitZ();
    j.swingLimit = JointSwingLimit{0.8, 0.4};
    world.addJoint(j);
    real worst = 0;
    for (int step = 0; step < 300; ++step) {
        world.step(kDt);
        const Vector3 along = world.body(rod).getOrientation() * Vector3::UnitX();
        worst = std::max(worst, std::atan2(-along.y(), along.x()));
    }
    const Vector3 along = world.body(rod).getOrientation() * Vector3::UnitX();
    EXPECT_LE(worst, 0.4 + 0.02);
    EXPECT_NEAR(std::atan2(-along.y(), along.x()), 0.4, 0.02);
    EXPECT_NEAR(along.z(), 0, 1e-6);
}

TEST(SwingTwist, BadLimitsAreRefusedAndNothingChanges) {
    World world(noSleep());
    const BodyId a = addBox(world, Vector3(0, 1, 0), Vector3(0.5, 0.5, 0.5), 1);
    const auto refused = [&](const JointSettings &j, const std::string &field) { expectJointRefused(world, j, field); };
    JointSettings base;
    base.a = a;
    base.anchor = Vector3(0, 1.5, 0);
    base.axis = Vector3::UnitY();
    JointSettings j = base;
    j.swingLimit = JointSwingLimit{0, 0.5};
    refused(j, "swingLimit.normalAngle");
    j.swingLimit = JointSwingLimit{0.5, 4};
    refused(j, "swingLimit.binormalAngle");
    j.swingLimit = JointSwingLimit{0.5, 0.3};  // elliptic: needs a normal
    refused(j, "normal");
    j.normal = Vector3(1, 1, 0);  // not perpendicular to y
    refused(j, "normal");
    j.normal = Vector3(kNaN, 0, 0);
    refused(j, "normal");
    j = base;
    j.normal = Vector3::UnitX();  // no swing limit
    refused(j, "normal");
    j = base;
    j.twistLimit = JointLimits{0.5, -0.5};
    refused(j, "twistLimit");
    j.twistLimit = JointLimits{-4, 0};
    refused(j, "twistLimit");
    j.twistLimit = JointLimits{kNaN, 0};
    refused(j, "twistLimit.lower");
    j = base;
    j.axis = Vector3::Zero();
    j.twistLimit = JointLimits{-0.5, 0.5};
    refused(j, "axis");
    j = base;
    j.type = JointType::Hinge;
    j.swingLimit = JointSwingLimit{0.5, 0.5};
    refused(j, "swingLimit");
    j = base;
    j.type = JointType::Slider;
    j.twistLimit = JointLimits{-0.5, 0.5};
    refused(j, "twistLimit");
    j = base;
    j.limitSpring = JointSpring{5, 1};  // a free ball: nothing to soften
    refused(j, "limitSpring");
    j.twistLimit = JointLimits{-0.5, 0.5};
    j.limitSpring = JointSpring{0, 1};
    refused(j, "limitSpring.frequency");
    j.limitSpring = JointSpring{5, -1};
    refused(j, "limitSpring.dampingRatio");
    // Nothing was added: the first joint takes slot 0.
    EXPECT_EQ(world.addJoint(base).index, 0u);
}

}  // namespace
}  // namespace cyclone::test
