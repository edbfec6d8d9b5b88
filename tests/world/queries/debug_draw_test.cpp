// Debug drawing: what World::debugDraw() hands to the game's DebugDraw.
#include <cmath>
#include <limits>
#include <map>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

bool same(const DebugColor &x, const DebugColor &y) { return x.r == y.r && x.g == y.g && x.b == y.b && x.a == y.a; }

// Records every line; keeps the default box, circle and contact, which draw lines.
struct Recorder : DebugDraw {
    struct Line {
        Vector3 from, to;
        DebugColor color;
    };
    std::vector<Line> lines;
    void line(const Vector3 &from, const Vector3 &to, const DebugColor &color) override {
        lines.push_back({from, to, color});
    }
    int count(const DebugColor &color) const {
        int n = 0;
        for (const Line &l : lines) n += same(l.color, color) ? 1 : 0;
        return n;
    }
};

// Records contacts instead of drawing them.
struct ContactRecorder : Recorder {
    struct Contact {
        Vector3 point, normal;
        real depth;
    };
    std::vector<Contact> contacts;
    void contact(const Vector3 &point, const Vector3 &normal, real depth, real, const DebugColor &,
                 const DebugColor &) override {
        contacts.push_back({point, normal, depth});
    }
};

DebugDrawOptions shapesOnly(int segments = 8) {
    DebugDrawOptions o;
    o.contacts = false;
    o.circleSegments = segments;
    return o;
}

int linesOf(const Shape &shape, const DebugDrawOptions &options = shapesOnly()) {
    World world;
    BodySettings s;
    s.shape = shape;
    s.motion = shape.type == ShapeType::Plane || shape.type == ShapeType::Mesh ? Motion::Static : Motion::Dynamic;
    world.addBody(s);
    Recorder r;
    world.debugDraw(r, options);
    return static_cast<int>(r.lines.size());
}

// With 8 segments per circle: a box has 12 edges; a sphere three circles; a cylinder two
// circles and four side lines; a capsule as a cylinder plus four half circles; a cube
// hull 12 edges (its coplanar facets merged); a two-triangle mesh 6; a plane a square,
// its two diagonals and its normal.
TEST(DebugDraw, LinesPerShape) {
    EXPECT_EQ(linesOf(Shape::box(Vector3(1, 2, 3))), 12);
    EXPECT_EQ(linesOf(Shape::sphere(1)), 3 * 8);
    EXPECT_EQ(linesOf(Shape::cylinder(1, 2)), 2 * 8 + 4);
    EXPECT_EQ(linesOf(Shape::capsule(1, 2)), 2 * 8 + 4 + 4 * 4);
    std::vector<Vector3> cube;
    for (int i = 0; i < 8; ++i) cube.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    EXPECT_EQ(linesOf(Shape::convex(cube)), 12);
    EXPECT_EQ(linesOf(Shape::mesh({Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 0, 1), Vector3(0, 0, 1)},
                                  {{0, 2, 1}, {0, 3, 2}})),
              6);
    EXPECT_EQ(linesOf(Shape::plane(Vector3::UnitY(), 0)), 7);
}

// The default box: 12 edges of lengths 2, 4 and 6 (four each), ends on the corners.
TEST(DebugDraw, DefaultBoxDrawsTheEdges) {
    Recorder r;
    Matrix4 pose = Matrix4::Identity();
    pose.translation() = Vector3(10, 0, 0);
    r.box(pose, Vector3(1, 2, 3), DebugColor());
    ASSERT_EQ(r.lines.size(), 12u);
    std::map<long, int> lengths;
    for (const Recorder::Line &l : r.lines) {
        ++lengths[std::lround((l.to - l.from).norm())];
        for (const Vector3 &end : {l.from, l.to}) {
            EXPECT_EQ(std::abs(end.x() - 10), 1);
            EXPECT_EQ(std::abs(end.y()), 2);
            EXPECT_EQ(std::abs(end.z()), 3);
        }
    }
    EXPECT_EQ(lengths, (std::map<long, int>{{2, 4}, {4, 4}, {6, 4}}));
}

// A circle of radius 2 about y at (0, 1, 0): every end 2 from the centre, in y = 1.
TEST(DebugDraw, DefaultCircleLiesInItsPlane) {
    Recorder r;
    r.circle(Vector3(0, 1, 0), Vector3::UnitY(), 2, 12, DebugColor());
    ASSERT_EQ(r.lines.size(), 12u);
    for (const Recorder::Line &l : r.lines) {
        EXPECT_NEAR((l.from - Vector3(0, 1, 0)).norm(), 2, 1e-12);
        EXPECT_NEAR(l.from.y(), 1, 1e-12);
        // Chord of 30 degrees: 2 r sin(15 deg).
        EXPECT_NEAR((l.to - l.from).norm(), 4 * std::sin(kPi / 12), 1e-12);
    }
    EXPECT_LT((r.lines.back().to - r.lines.front().from).norm(), 1e-12);  // closed
}

// Awake, asleep and static bodies in their colours; statics can be left out.
TEST(DebugDraw, ColoursFollowTheBodyState) {
    WorldFixture f;
    f.staticBox(Vector3(0, -0.5, 0), Vector3(5, 0.5, 5));
    f.box(Vector3(0, 3, 0));
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = Vector3(3, 3, 0);
    s.awake = false;
    f.world.addBody(s);
    const DebugDrawOptions options = shapesOnly();
    Recorder r;
    f.world.debugDraw(r, options);
    EXPECT_EQ(r.count(options.awake), 12);
    EXPECT_EQ(r.count(options.asleep), 12);
    EXPECT_EQ(r.count(options.staticBody), 12);
    DebugDrawOptions noStatics = options;
    noStatics.staticBodies = false;
    Recorder fewer;
    f.world.debugDraw(fewer, noStatics);
    EXPECT_EQ(fewer.lines.size(), 24u);
}

// A unit box at the origin has the broadphase box [-0.5, 0.5]^3 enlarged by 2 cm.
TEST(DebugDraw, BoundingBoxesIncludeTheMargin) {
    WorldFixture f;
    f.box(Vector3::Zero());
    DebugDrawOptions options = shapesOnly();
    options.shapes = false;
    options.boundingBoxes = true;
    Recorder r;
    f.world.debugDraw(r, options);
    ASSERT_EQ(r.count(options.boundingBox), 12);
    for (const Recorder::Line &l : r.lines) EXPECT_NEAR(l.from.cwiseAbs().maxCoeff(), 0.52, 1e-12);
}

// A box resting on the ground touches it at its four bottom corners, y ~ 0, normal up
// (from the ground, added first, to the box).
TEST(DebugDraw, ContactsOfARestingBox) {
    WorldFixture f;
    f.ground();
    f.box(Vector3(0, 0.5, 0));
    f.simulate(0.5);
    ContactRecorder r;
    DebugDrawOptions options;
    options.shapes = false;
    f.world.debugDraw(r, options);
    ASSERT_EQ(r.contacts.size(), 4u);
    for (const ContactRecorder::Contact &c : r.contacts) {
        EXPECT_NEAR(std::abs(c.point.x()), 0.5, 1e-3);
        EXPECT_NEAR(std::abs(c.point.z()), 0.5, 1e-3);
        EXPECT_NEAR(c.point.y(), 0, 2e-3);
        EXPECT_NEAR(c.normal.y(), 1, 1e-9);
    }
    // The default contact: a three-line cross and the normal, in their colours.
    Recorder lines;
    f.world.debugDraw(lines, options);
    EXPECT_EQ(lines.count(options.contactPoint), 4 * 3);
    EXPECT_EQ(lines.count(options.contactNormal), 4);
}

TEST(DebugDraw, RefusesBadOptionsBeforeDrawing) {
    WorldFixture f;
    f.box(Vector3::Zero());
    auto expectRefused = [&](const DebugDrawOptions &o, const std::string &field) {
        Recorder r;
        try {
            f.world.debugDraw(r, o);
            FAIL() << "accepted a bad " << field;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "World::debugDraw");
            EXPECT_EQ(e.field(), field) << e.what();
        }
        EXPECT_TRUE(r.lines.empty());
    };
    DebugDrawOptions o;
    o.normalLength = 0;
    expectRefused(o, "options.normalLength");
    o = DebugDrawOptions();
    o.planeHalfSize = std::numeric_limits<double>::infinity();
    expectRefused(o, "options.planeHalfSize");
    o = DebugDrawOptions();
    o.circleSegments = 3;
    expectRefused(o, "options.circleSegments");
    o = DebugDrawOptions();
    o.asleep.g = 1.5f;
    expectRefused(o, "options.asleep");
    o = DebugDrawOptions();
    o.jointSize = 0;
    expectRefused(o, "options.jointSize");
    o = DebugDrawOptions();
    o.jointLimit.a = -1;
    expectRefused(o, "options.jointLimit");
}

// A door on a hinge about y at the origin, limits [-1, 1] rad, with 24 segments a circle
// and joints of size 0.5: the anchor's three-line cross; the axis, 0.5 m either side of
// the anchor, and the current angle (the door's perpendicular to the axis, at angle 0:
// the hinge's zero line); the range as an arc of ceil(24 * 2 / (2 pi)) = 8 segments
// between two spokes 0.5 m long, whose ends are the zero line turned by -1 and +1 rad.
TEST(DebugDraw, AHingeIsDrawnWithItsAxisAndLimits) {
    World world;
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 1, 0.05));
    s.position = Vector3(0.5, 0, 0);
    const BodyId door = world.addBody(s);
    JointSettings j;
    j.type = JointType::Hinge;
    j.a = door;
    j.axis = Vector3::UnitY();
    j.limits = JointLimits{-1, 1};
    world.addJoint(j);
    DebugDrawOptions o;
    o.shapes = false;
    o.jointSize = 0.5;
    Recorder r;
    world.debugDraw(r, o);
    EXPECT_EQ(r.count(o.jointAnchor), 3);
    EXPECT_EQ(r.count(o.jointAxis), 2);
    EXPECT_EQ(r.count(o.jointLimit), 8 + 2);
    EXPECT_EQ(r.lines.size(), 15u);
    Vector3 zero = Vector3::Zero();
    std::vector<Vector3> spokes;
    for (const Recorder::Line &l : r.lines) {
        if (same(l.color, o.jointAxis) && l.from.isZero(0) && l.to.y() == 0) zero = l.to;
        if (same(l.color, o.jointLimit) && l.from.isZero(0)) spokes.push_back(l.to);
    }
    EXPECT_NEAR(zero.norm(), 0.5, 1e-12);
    ASSERT_EQ(spokes.size(), 2u);
    for (const Vector3 &end : spokes) {
        EXPECT_NEAR(end.norm(), 0.5, 1e-12);
        EXPECT_NEAR(end.y(), 0, 1e-12);
        EXPECT_NEAR(std::acos(end.dot(zero) / 0.25), 1, 1e-9);
    }
}

// A ball joint with a swing cone of half-angles 0.6 (towards the normal x) and 0.3 (z)
// about the axis -y, size 1: the rim's 24 lines and four spokes; the spokes towards +-x
// lean 0.6 rad from -y and those towards +-z 0.3 rad (their ends at (sin 0.6, -cos 0.6, 0)
// and so on).
TEST(DebugDraw, ABallJointsSwingConeIsDrawnWithItsHalfAngles) {
    World world;
    BodySettings s;
    s.shape = Shape::capsule(0.05, 0.8);
    s.position = Vector3(0, -0.5, 0);
    const BodyId rod = world.addBody(s);
    JointSettings j;
    j.type = JointType::Ball;
    j.a = rod;
    j.axis = -Vector3::UnitY();
    j.normal = Vector3::UnitX();
    j.swingLimit = JointSwingLimit{0.6, 0.3};
    world.addJoint(j);
    DebugDrawOptions o;
    o.shapes = false;
    o.jointSize = 1;
    Recorder r;
    world.debugDraw(r, o);
    EXPECT_EQ(r.count(o.jointLimit), 24 + 4);
    int spokes = 0;
    for (const Recorder::Line &l : r.lines) {
        if (!same(l.color, o.jointLimit) || !l.from.isZero(0)) continue;
        ++spokes;
        const real lean = std::acos(-l.to.y());
        EXPECT_NEAR(lean, std::abs(l.to.x()) > std::abs(l.to.z()) ? 0.6 : 0.3, 1e-9);
    }
    EXPECT_EQ(spokes, 4);
}

}  // namespace
}  // namespace cyclone::test
