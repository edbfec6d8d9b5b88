// Cylinders landing on a lying cylinder (collision/cylinder_pairs.cpp): dropped across it,
// and nearly parallel to it but tilted, rim first, as the deepest pairs of the mixed piles
// landed. The tilted one turns about its rim as it lands and its other end comes down
// within a step: that end needs its point (a gap that the contact lets close) before it
// arrives, or it goes 20 mm into the side.
//
// The bound: the speculative contact acts in the step of the impact, letting the gap
// close and no more; what gravity adds within that step, g dt^2 = 9.81 / 60^2 = 2.7 mm,
// plus the slop (0.2 mm) is the most that should remain, within the drop tests' 5 mm
// (speculative_contact_test.cpp). A contact measured along a wrong normal lets the body
// slide along the round side and into it, far deeper.
#include <cmath>

#include "collision/round_pairs.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr real kLandingDeepest = 0.005;
constexpr real kCylinderRadius = 0.25;  // Both cylinders'.

// How deep cylinder `id` (radius kCylinderRadius, length `length`) reaches into the static
// cylinder lying along x at the origin (radius kCylinderRadius, length 2): the radius less the
// least distance from that axis segment to the lines of the cylinder's side (its rims
// are their ends), sampled every degree around the axis.
real depthIntoLyingCylinder(const World &world, BodyId id, real length) {
    const RigidBody &body = world.body(id);
    const Matrix3 turn = body.getOrientation().toRotationMatrix();
    const Vector3 axis = turn.col(2), u = turn.col(0), v = turn.col(1);
    const Vector3 c = body.getPosition();
    const Vector3 q0(-1, 0, 0), q1(1, 0, 0);
    real least = 1e300;
    for (int degree = 0; degree < 360; ++degree) {
        const real angle = degree * kPi / 180;
        const Vector3 offset = kCylinderRadius * (std::cos(angle) * u + std::sin(angle) * v);
        const Vector3 p0 = c - 0.5 * length * axis + offset, p1 = c + 0.5 * length * axis + offset;
        real s = 0, t = 0;
        detail::closestOnSegments(p0, p1, q0, q1, s, t);
        least = std::min(least, ((p0 + s * (p1 - p0)) - (q0 + t * (q1 - q0))).norm());
    }
    return kCylinderRadius - least;
}

BodyId lyingCylinder(WorldFixture &f) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = Shape::cylinder(kCylinderRadius, 2);
    s.orientation = Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
    return f.world.addBody(s);
}

// Steps `seconds` and returns the deepest that cylinder `id` reached into the lying one.
real deepestOver(WorldFixture &f, BodyId id, real length, double seconds) {
    real deepest = 0;
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < steps; ++i) {
        f.world.step(kDt);
        deepest = std::max(deepest, depthIntoLyingCylinder(f.world, id, length));
    }
    return deepest;
}

TEST(CylinderLanding, DroppedAcrossALyingCylinder) {
    WorldFixture f;
    lyingCylinder(f);
    // Along z, 1 m above touching: it lands at sqrt(2 g 1) = 4.4 m/s.
    BodySettings s;
    s.shape = Shape::cylinder(kCylinderRadius, 1);
    s.position = Vector3(0.1, 2 * kCylinderRadius + 1, 0);
    s.mass = 1;
    const BodyId falling = f.world.addBody(s);
    EXPECT_LE(deepestOver(f, falling, 1, 1.5), kLandingDeepest);
}

TEST(CylinderLanding, TiltedRimFirstOntoALyingCylinder) {
    WorldFixture f;
    lyingCylinder(f);
    // Along x like the lying one but tilted 9 degrees, its lower rim 1 m above the lying
    // cylinder's top: it lands rim first.
    const real alpha = 9 * kPi / 180;
    BodySettings s;
    s.shape = Shape::cylinder(kCylinderRadius, 1);
    s.orientation = Quaternion(Eigen::AngleAxis<real>(-alpha, Vector3::UnitZ())) *
                    Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
    const Vector3 axis(std::cos(alpha), -std::sin(alpha), 0);
    const Vector3 lowerEnd(0.3, 0, 0.05);
    const real lift = kCylinderRadius + 1 + kCylinderRadius * std::cos(alpha);
    s.position = lowerEnd + Vector3(0, lift, 0) - 0.5 * axis;
    s.mass = 1;
    const BodyId falling = f.world.addBody(s);
    EXPECT_LE(deepestOver(f, falling, 1, 1.5), kLandingDeepest);
}

}  // namespace
}  // namespace cyclone::test
