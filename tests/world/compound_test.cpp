// Compound shapes: mass properties from the children, the frame the user places them by,
// contacts per child, queries, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

CompoundChild child(const Shape &shape, const Vector3 &position, const Quaternion &orientation = Quaternion::Identity()) {
    CompoundChild c;
    c.shape = shape;
    c.position = position;
    c.orientation = orientation;
    return c;
}

// An L of two boxes of equal volume: a bar 2 x 1 x 1 m centred on the frame origin and a
// post 1 x 2 x 1 m centred at (0.5, 1.5, 0), standing on the bar's right half.
Shape lShape() {
    return Shape::compound({child(Shape::box({1, 0.5, 0.5}), {0, 0, 0}),
                            child(Shape::box({0.5, 1, 0.5}), {0.5, 1.5, 0})});
}

BodyId staticBox(World &world, const Vector3 &position, const Vector3 &half) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = Shape::box(half);
    s.position = position;
    return world.addBody(s);
}

// A table: a 1.6 x 0.06 x 1 m top at 0.72 m on four 0.2 x 0.7 x 0.2 m legs, its frame
// on the floor under the top's centre.
Shape table() {
    std::vector<CompoundChild> children;
    for (real x : {-0.7, 0.7})
        for (real z : {-0.4, 0.4}) children.push_back(child(Shape::box({0.1, 0.35, 0.1}), {x, 0.35, z}));
    children.push_back(child(Shape::box({0.8, 0.03, 0.5}), {0, 0.72, 0}));
    return Shape::compound(children);
}

TEST(Compound, LShapeMassProperties) {
    // Each box holds half of the 4 kg (equal volumes, 2 m^3 each): m = 2 kg.
    // Centre of mass: the mean of the centres, ((0,0,0) + (0.5,1.5,0)) / 2 = (0.25, 0.75, 0).
    // Own inertia m (b^2 + c^2) / 12 with full sizes b, c:
    //   bar 2x1x1: Ixx = 2 (1+1)/12 = 1/3, Iyy = 2 (4+1)/12 = 5/6, Izz = 5/6;
    //   post 1x2x1: Ixx = 2 (4+1)/12 = 5/6, Iyy = 2 (1+1)/12 = 1/3, Izz = 5/6.
    // Offsets from the centre of mass d = -+(0.25, 0.75, 0), |d|^2 = 0.625; each adds
    // m (|d|^2 E - d d^T): xx 2 (0.625 - 0.0625) = 1.125, yy 2 (0.625 - 0.5625) = 0.125,
    // zz 2 (0.625) = 1.25, xy -2 (0.25)(0.75) = -0.375.
    // Sum: Ixx = 1/3 + 5/6 + 2.25 = 41/12, Iyy = 5/6 + 1/3 + 0.25 = 17/12,
    // Izz = 5/6 + 5/6 + 2.5 = 25/6, Ixy = -0.75, Ixz = Iyz = 0.
    World world;
    BodySettings s;
    s.shape = lShape();
    s.mass = 4;
    s.position = Vector3(10, 20, 30);
    const BodyId id = world.addBody(s);
    const RigidBody &body = world.body(id);
    EXPECT_NEAR((body.getPosition() - Vector3(10.25, 20.75, 30)).norm(), 0, 1e-12);
    EXPECT_NEAR((world.localCentreOfMass(id) - Vector3(0.25, 0.75, 0)).norm(), 0, 1e-12);
    EXPECT_NEAR((world.framePosition(id) - Vector3(10, 20, 30)).norm(), 0, 1e-12);
    Matrix3 expected;
    expected << 41.0 / 12, -0.75, 0, -0.75, 17.0 / 12, 0, 0, 0, 25.0 / 6;
    EXPECT_NEAR((body.getInertiaTensor() - expected).cwiseAbs().maxCoeff(), 0, 1e-9);
}

TEST(Compound, UserMassAndInertiaAreKept) {
    World world;
    BodySettings s;
    s.shape = lShape();
    s.mass = 3;
    s.inertia = Matrix3(Vector3(1, 2, 3).asDiagonal());
    const BodyId id = world.addBody(s);
    EXPECT_DOUBLE_EQ(world.body(id).getMass(), 3);
    EXPECT_NEAR((world.body(id).getInertiaTensor() - Matrix3(Vector3(1, 2, 3).asDiagonal())).norm(), 0, 1e-12);
}

TEST(Compound, TurnedFrameKeepsItsPlace) {
    // Turned a quarter about z, the L's centre of mass (0.25, 0.75, 0) in the frame lies
    // at (-0.75, 0.25, 0) from the frame's origin.
    World world;
    BodySettings s;
    s.shape = lShape();
    s.position = Vector3(1, 2, 3);
    s.orientation = Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitZ()));
    const BodyId id = world.addBody(s);
    EXPECT_NEAR((world.body(id).getPosition() - Vector3(0.25, 2.25, 3)).norm(), 0, 1e-12);
    EXPECT_NEAR((world.framePosition(id) - Vector3(1, 2, 3)).norm(), 0, 1e-12);
    EXPECT_NEAR((world.framePose(id).translation() - Vector3(1, 2, 3)).norm(), 0, 1e-12);
    world.setFramePosition(id, Vector3(4, 5, 6));
    EXPECT_NEAR((world.framePosition(id) - Vector3(4, 5, 6)).norm(), 0, 1e-12);
    EXPECT_NEAR((world.body(id).getPosition() - Vector3(3.25, 5.25, 6)).norm(), 0, 1e-12);
}

TEST(Compound, ConvexChildUsesItsCentroid) {
    // A tetrahedron with corners at the origin and at 1 m along each axis has its centroid
    // at (1/4, 1/4, 1/4), whatever its frame: alone in a compound, that is the body's
    // centre of mass.
    World world;
    BodySettings s;
    s.shape = Shape::compound({child(Shape::convex({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), {2, 0, 0})});
    const BodyId id = world.addBody(s);
    EXPECT_NEAR((world.localCentreOfMass(id) - Vector3(2.25, 0.25, 0.25)).norm(), 0, 1e-12);
}

// A table set down 1 mm above a static floor settles onto its legs: its frame (on the
// floor, under the top) stays within a millimetre of where it was put. Nothing turns it
// about the vertical: gravity acts through its centre of mass
// and the floor's normal forces are vertical, so its angular momentum about the vertical
// stays zero, and friction can only take motion away. Its orientation stays the identity;
// 0.001 rad (under a millimetre at the legs, 0.8 m from the centre) allows for the
// solver's convergence. The legs' tangent friction, not their small twist limit, holds
// the turn (docs/compound.md), with or without sub-steps.
TEST(Compound, TableKeepsItsOrientation) {
    for (int substeps : {1, 4}) {
        WorldSettings settings;
        settings.substeps = substeps;
        World world(settings);
        staticBox(world, Vector3(0, -0.5, 0), Vector3(10, 0.5, 10));
        BodySettings s;
        s.shape = table();
        s.mass = 20;
        s.position = Vector3(3, 0.001, -2);
        const BodyId id = world.addBody(s);
        for (int i = 0; i < 120; ++i) world.step(kDt);
        EXPECT_LT(world.body(id).getOrientation().angularDistance(Quaternion::Identity()), 0.001) << substeps;
        EXPECT_NEAR((world.framePosition(id) - Vector3(3, 0, -2)).norm(), 0, 0.001);
    }
}

TEST(Compound, ChildContactIsWhereTheChildTouches) {
    // A sphere (x = -1) and a box (x = +1, 0.5 m cube) joined: only the box is over a
    // static block whose top is y = 0 between x = 0.5 and 1.5. Set 1 mm into it, the box
    // child touches along its bottom face: the contact lies under the box, at y = 0, with
    // the normal along y; the sphere, far from the block, touches nothing.
    World world;
    const BodyId block = staticBox(world, Vector3(1, -0.5, 0), Vector3(0.5, 0.5, 0.5));
    BodySettings s;
    s.shape = Shape::compound({child(Shape::sphere(0.25), {-1, 0, 0}), child(Shape::box({0.25, 0.25, 0.25}), {1, 0, 0})});
    s.position = Vector3(0, 0.249, 0);
    const BodyId id = world.addBody(s);
    world.step(kDt);
    ASSERT_EQ(world.events().contactBegins.size(), 1u);
    const ContactBegin &begin = world.events().contactBegins[0];
    EXPECT_TRUE((begin.a == block && begin.b == id) || (begin.a == id && begin.b == block));
    EXPECT_GE(begin.point.x(), 0.75 - 1e-9);
    EXPECT_LE(begin.point.x(), 1.25 + 1e-9);
    EXPECT_NEAR(begin.point.y(), 0, 0.002);
    EXPECT_NEAR(std::abs(begin.normal.y()), 1, 1e-6);
}

TEST(Compound, RayHitsAChildAndPassesBetween) {
    // Two 1 m cubes at x = -2 and +2 of a frame at the origin: a ray down at x = 2 meets
    // the top of the right one (y = 0.5, 4.5 m below y = 5); one at x = 0 passes between.
    World world;
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = Shape::compound({child(Shape::box({0.5, 0.5, 0.5}), {-2, 0, 0}), child(Shape::box({0.5, 0.5, 0.5}), {2, 0, 0})});
    const BodyId id = world.addBody(s);
    const auto hit = world.rayCast(Vector3(2, 5, 0), Vector3(0, -1, 0));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, id);
    EXPECT_NEAR(hit->distance, 4.5, 1e-12);
    EXPECT_NEAR((hit->normal - Vector3::UnitY()).norm(), 0, 1e-12);
    EXPECT_FALSE(world.rayCast(Vector3(0, 5, 0), Vector3(0, -1, 0)));

    std::vector<BodyId> out;
    EXPECT_EQ(world.overlap(Shape::sphere(0.2), Vector3(-2, 0.6, 0), Quaternion::Identity(), out), 1u);
    EXPECT_EQ(world.overlap(Shape::sphere(0.2), Vector3(0, 0, 0), Quaternion::Identity(), out), 0u);
}

TEST(Compound, BadInputIsRefusedAndChangesNothing) {
    World world;
    const auto refused = [&](const Shape &shape, const std::string &field) {
        BodySettings s;
        s.shape = shape;
        try {
            world.addBody(s);
            ADD_FAILURE() << "accepted a compound with a bad " << field;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.field(), field);
            EXPECT_EQ(e.function(), "World::addBody");
        }
        EXPECT_EQ(world.bodyCount(), 0u);
    };
    refused(Shape::compound({}), "shape.children");
    refused(Shape::compound({child(Shape::mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}), {0, 0, 0})}),
            "shape.children[0].shape.type");
    refused(Shape::compound({child(Shape::sphere(1), {0, 0, 0}), child(Shape::plane(Vector3::UnitY(), 0), {0, 0, 0})}),
            "shape.children[1].shape.type");
    refused(Shape::compound({child(lShape(), {0, 0, 0})}), "shape.children[0].shape.type");
    refused(Shape::compound({child(Shape::sphere(-1), {0, 0, 0})}), "shape.children[0].shape.radius");
    refused(Shape::compound({child(Shape::sphere(1), {0, std::nan(""), 0})}), "shape.children[0].position[1]");
    refused(Shape::compound({child(Shape::sphere(1), {0, 0, 0}, Quaternion(std::nan(""), 0, 0, 0))}),
            "shape.children[0].orientation");
}

}  // namespace
}  // namespace cyclone::test
