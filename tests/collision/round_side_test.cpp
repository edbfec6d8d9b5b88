// The round side of a contact (collision/round_side.h): which shapes are round where,
// the core point below an anchor, and how much deeper the surface reaches than a point
// fixed on the body once the body has turned.
#include <gtest/gtest.h>

#include <cmath>

#include "collision/collision_shape.h"
#include "collision/round_side.h"

namespace cyclone::test {
namespace {

using detail::compileShape;
using detail::RoundCore;

// The outward normal at the contact, in the body's frame, after the body turned by
// `angle` about `axis` (body frame) while the normal stayed put in the world: the
// body-frame normal turns the other way.
Vector3 turned(const Vector3 &outward, const Vector3 &axis, real angle) {
    return Eigen::AngleAxis<real>(-angle, axis.normalized()) * outward;
}

TEST(RoundSide, WhichShapesAreRoundWhere) {
    const auto sphere = compileShape(Shape::sphere(0.25));
    const auto capsule = compileShape(Shape::capsule(0.2, 1.0));
    const auto cylinder = compileShape(Shape::cylinder(0.3, 0.8));
    const auto box = compileShape(Shape::box(Vector3(0.5, 0.5, 0.5)));
    const Vector3 down = -Vector3::UnitY();
    const Vector3 alongAxis = -Vector3::UnitZ();
    EXPECT_EQ(detail::roundSideAt(*sphere, 0, down).radius, 0.25);
    EXPECT_EQ(detail::roundSideAt(*capsule, 0, alongAxis).radius, 0.2) << "its end cap is a half sphere";
    EXPECT_EQ(detail::roundSideAt(*cylinder, 0, down).radius, 0.3) << "on its side";
    // On its cap the cylinder is flat: within 15 degrees of its axis it is not round, at
    // 20 degrees it leans on its rim, a circle.
    EXPECT_EQ(detail::roundSideAt(*cylinder, 0, alongAxis).radius, 0);
    const real tilt10 = 10 * std::acos(real(-1)) / 180;
    const real tilt20 = 2 * tilt10;
    EXPECT_EQ(detail::roundSideAt(*cylinder, 0, turned(alongAxis, Vector3::UnitX(), tilt10)).radius, 0);
    EXPECT_EQ(detail::roundSideAt(*cylinder, 0, turned(alongAxis, Vector3::UnitX(), tilt20)).radius, 0.3);
    EXPECT_EQ(detail::roundSideAt(*box, 0, down).radius, 0);
    EXPECT_FALSE(detail::mayBeRound(*box));
}

TEST(RoundSide, ACompoundsChildIsRoundInTheBodysFrame) {
    // A unit box and a sphere of radius 0.25 at x = 1: the sphere child's core is its
    // centre, where the compound put it, in the body's frame (whose origin is the
    // children's centre of mass, not the box's centre).
    Shape compound;
    compound.type = ShapeType::Compound;
    CompoundChild box;
    box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    CompoundChild ball;
    ball.shape = Shape::sphere(0.25);
    ball.position = Vector3(1, 0, 0);
    compound.children = {box, ball};
    const auto c = compileShape(compound);
    const Vector3 centreOfBall = c->children()[1].pose.translation();
    const RoundCore core = detail::roundSideAt(*c, 1, -Vector3::UnitY());
    EXPECT_EQ(core.radius, 0.25);
    EXPECT_NEAR((detail::nearestCorePoint(core, centreOfBall - 0.25 * Vector3::UnitY()) - centreOfBall).norm(), 0,
                1e-15);
    EXPECT_EQ(detail::roundSideAt(*c, 0, -Vector3::UnitY()).radius, 0) << "the box child";
}

TEST(RoundSide, TheCoreBelowAnAnchor) {
    // Capsule of radius 0.2 and segment z in [-0.5, 0.5]: a point of its side lies over the
    // segment point of the same z; a point of an end cap over the segment's end.
    const RoundCore capsule = detail::roundCore(*compileShape(Shape::capsule(0.2, 1.0)), 0);
    EXPECT_NEAR((detail::nearestCorePoint(capsule, Vector3(0, -0.2, 0.3)) - Vector3(0, 0, 0.3)).norm(), 0, 1e-15);
    EXPECT_NEAR((detail::nearestCorePoint(capsule, Vector3(0, 0, 0.7)) - Vector3(0, 0, 0.5)).norm(), 0, 1e-15);
    // A sphere's core is its centre.
    const RoundCore sphere = detail::roundCore(*compileShape(Shape::sphere(0.25)), 0);
    EXPECT_EQ(detail::nearestCorePoint(sphere, Vector3(0.1, -0.2, 0.05)), Vector3::Zero());
}

TEST(RoundSide, DepthChangeAfterATurn) {
    // A ball of radius r whose contact point turned by a about an axis across the normal:
    // the fixed point rose r (1 - cos a) above the surface's deepest point. 0.072 rad is
    // a sub-step's turn of a 0.25 m ball at 4.3 m/s (4.3 / 0.25 / 240): 0.65 mm.
    const RoundCore sphere = detail::roundCore(*compileShape(Shape::sphere(0.25)), 0);
    const Vector3 down = -Vector3::UnitY();
    for (real a : {0.0, 0.072, 0.29, 1.0}) {
        EXPECT_NEAR(detail::roundDepthChange(sphere, down, turned(down, Vector3::UnitZ(), a)), 0.25 * (1 - std::cos(a)),
                    1e-15);
    }
    // Turning about the normal itself (spinning) moves nothing along it.
    EXPECT_NEAR(detail::roundDepthChange(sphere, down, turned(down, Vector3::UnitY(), 0.5)), 0, 1e-15);
    // A cylinder (radius 0.3, along z) on its side, rolling about its axis: as the ball.
    const RoundCore cylinder = detail::roundCore(*compileShape(Shape::cylinder(0.3, 0.8)), 0);
    EXPECT_NEAR(detail::roundDepthChange(cylinder, down, turned(down, Vector3::UnitZ(), 0.2)), 0.3 * (1 - std::cos(0.2)),
                1e-15);
    // Tipping about the axis across (x): its rims' circles stay as deep: the anchor, a
    // point of the circle, moves with the circle and nothing changes.
    EXPECT_NEAR(detail::roundDepthChange(cylinder, down, turned(down, Vector3::UnitX(), 0.2)), 0, 1e-15);
    // Leaning on its rim at 30 degrees from its side (the normal's component across the
    // axis cos 30), then rolling about the axis by b: the rim circle's deepest point is
    // as deep as before, the fixed point rose r cos 30 (1 - cos b).
    const Vector3 leaning = turned(down, Vector3::UnitX(), std::acos(real(-1)) / 6);
    const real b = 0.3;
    EXPECT_NEAR(detail::roundDepthChange(cylinder, leaning, turned(leaning, Vector3::UnitZ(), b)),
                0.3 * std::cos(std::acos(real(-1)) / 6) * (1 - std::cos(b)), 1e-15);
}

}  // namespace
}  // namespace cyclone::test
