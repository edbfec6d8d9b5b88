// Capsules and cylinders along a chosen local axis (Shape::capsule/cylinder's Axis): z by
// default, as FCL and the scene format have it; Axis::Y stands a character upright.
#include <gtest/gtest.h>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// The height of the centre of a body of `shape` dropped 5 cm onto the ground plane y = 0,
// after 2 s; it must not have turned (the shapes rest on a face or a rounded side
// symmetric about the vertical, so nothing tips them).
real restingHeight(const Shape &shape, real dropHeight) {
    WorldFixture f(noSleep());
    f.ground();
    BodySettings s;
    s.shape = shape;
    s.position = Vector3(0, dropHeight + 0.05, 0);
    const BodyId id = f.world.addBody(s);
    for (int i = 0; i < 120; ++i) f.world.step(kDt);
    EXPECT_LT(f.world.body(id).getOrientation().angularDistance(Quaternion::Identity()), 1e-3);
    return f.world.body(id).getPosition().y();
}

// A capsule of radius r and cylindrical length 2h stood along y touches the ground with
// the bottom of its lower half sphere: its centre rests at h + r. Along z (the default) it
// lies on its side, centre at r. Tolerance: the penetration slop (2e-4 m) and a little.
TEST(ShapeAxis, AnUprightCapsuleRestsOnItsEnd) {
    const real r = 0.3, h = 0.5;
    EXPECT_NEAR(restingHeight(Shape::capsule(r, 2 * h, Axis::Y), h + r), h + r, 1e-3);
    EXPECT_NEAR(restingHeight(Shape::capsule(r, 2 * h), r), r, 1e-3);
    EXPECT_NEAR(restingHeight(Shape::capsule(r, 2 * h, Axis::X), r), r, 1e-3);
}

// A cylinder of radius 0.4 and length 2 stood along y rests on its flat end, centre at
// 1; along x it lies on its round side, centre at 0.4.
TEST(ShapeAxis, AnUprightCylinderRestsOnItsFlatEnd) {
    EXPECT_NEAR(restingHeight(Shape::cylinder(0.4, 2, Axis::Y), 1), 1, 1e-3);
    EXPECT_NEAR(restingHeight(Shape::cylinder(0.4, 2, Axis::X), 0.4), 0.4, 1e-3);
}

// Along z the shape is the plain capsule (FCL's own); along y or x, one turned child whose
// local z lies along that axis.
TEST(ShapeAxis, TheAxisTurnsTheShapesZ) {
    EXPECT_EQ(Shape::capsule(0.3, 1).type, ShapeType::Capsule);
    EXPECT_EQ(Shape::cylinder(0.3, 1, Axis::Z).type, ShapeType::Cylinder);
    const Shape upright = Shape::capsule(0.3, 1, Axis::Y);
    ASSERT_EQ(upright.type, ShapeType::Compound);
    ASSERT_EQ(upright.children.size(), 1u);
    EXPECT_EQ(upright.children[0].shape.type, ShapeType::Capsule);
    EXPECT_TRUE(upright.children[0].position.isZero());
    EXPECT_LT((upright.children[0].orientation * Vector3::UnitZ() - Vector3::UnitY()).norm(), 1e-12);
    const Shape sideways = Shape::cylinder(0.3, 1, Axis::X);
    ASSERT_EQ(sideways.children.size(), 1u);
    EXPECT_LT((sideways.children[0].orientation * Vector3::UnitZ() - Vector3::UnitX()).norm(), 1e-12);
}

// A bad size is still refused by addBody, naming the value.
TEST(ShapeAxis, ABadRadiusIsRefused) {
    WorldFixture f;
    BodySettings s;
    s.shape = Shape::capsule(-1, 1, Axis::Y);
    EXPECT_THROW(f.world.addBody(s), InvalidArgument);
    EXPECT_EQ(f.world.bodyCount(), 0u);
}

}  // namespace
}  // namespace cyclone::test
