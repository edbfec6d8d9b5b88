// Every supported shape pair against a hand-worked case, in both argument orders.
//
// Shapes: box of half size 0.5 (a unit cube), sphere r = 0.5, capsule r = 0.25 with a
// 1 m cylindrical part, cylinder r = 0.4 and 1 m long, the pyramid of
// collision_test_support.h (base 0.8 x 0.8 at local y = -0.25) and a convex unit cube.
// Unless a test says otherwise, B sits at the origin, A rests on it from above and
// sinks 0.05 m into it, so the normal from A to B is -y; B's top is at y = 0.5 for the
// box, the cylinder (standing) and the convex cube. Points on top of B at height `top`
// are (x, top - 0.05, z) on A and (x, top, z) on B.
#include <gtest/gtest.h>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

constexpr real kDepth = 0.05;
// libccd's MPR (capsule/cylinder sides, convex-convex without a supporting face) gives
// normals and depths that are close, not exact: within about a degree and a few %.
constexpr real kMprNormal = 0.02;
constexpr real kMprDepth = 0.03 * kDepth;
constexpr real kMprPoint = 0.01;

Shape box() { return Shape::box(Vector3(0.5, 0.5, 0.5)); }
Shape sphere() { return Shape::sphere(0.5); }
Shape capsule() { return Shape::capsule(0.25, 1); }
Shape cylinder() { return Shape::cylinder(0.4, 1); }
Shape floorPlane() { return Shape::plane(Vector3::UnitY(), 0); }

// Contact points at (x, z) pairs between A's bottom at top - depth and B's surface at top.
std::vector<ExpectedPoint> onTop(real top, std::initializer_list<std::pair<real, real>> xz, real depth = kDepth) {
    std::vector<ExpectedPoint> points;
    for (const auto &[x, z] : xz) points.push_back({Vector3(x, top - depth, z), Vector3(x, top, z)});
    return points;
}

Expected flat(const std::vector<ExpectedPoint> &points, const Vector3 &normal = kDown) {
    Expected e;
    e.normal = normal;
    e.depth = kDepth;
    e.points = points;
    e.minPoints = e.maxPoints = static_cast<int>(points.size());
    return e;
}

Expected mpr(const std::vector<ExpectedPoint> &points, const Vector3 &normal = kDown) {
    Expected e = flat(points, normal);
    e.normalTolerance = kMprNormal;
    e.depthTolerance = kMprDepth;
    e.pointTolerance = kMprPoint;
    return e;
}

// A cylinder's cap (radius 0.4 about the vertical line through (cx, cz)) lying flat on a
// surface at `top`: three or four points of the cap's rim, all at the same depth.
Expected capOn(real top, real cx, real cz) {
    Expected e;
    e.normal = kDown;
    e.depth = kDepth;
    e.minPoints = 3;
    e.maxPoints = 4;
    e.eachPoint = [=](const Vector3 &a, const Vector3 &b) {
        EXPECT_NEAR(a.y(), top - kDepth, 1e-9);
        EXPECT_NEAR(b.y(), top, 1e-9);
        EXPECT_NEAR(Vector3(a.x() - cx, 0, a.z() - cz).norm(), 0.4, 1e-9) << "on the rim";
        EXPECT_LT((a - b - kDepth * kDown).norm(), 1e-9);
    };
    return e;
}

// ---- Box ----

TEST(NarrowphasePairs, BoxOnBox) {
    // A at (0.3, 0.95, 0.2): its bottom square x in [-0.2, 0.8], z in [-0.3, 0.7] overlaps
    // B's top in x in [-0.2, 0.5], z in [-0.3, 0.5]: the four corners of that rectangle.
    expectContact(box(), pose(Vector3(0.3, 0.95, 0.2)), box(), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.2, -0.3}, {0.5, -0.3}, {0.5, 0.5}, {-0.2, 0.5}})));
}

TEST(NarrowphasePairs, SphereOnBox) {
    // Sphere centre (0.1, 0.95, 0.2), bottom at 0.45.
    expectContact(sphere(), pose(Vector3(0.1, 0.95, 0.2)), box(), Matrix4::Identity(), flat(onTop(0.5, {{0.1, 0.2}})));
}

TEST(NarrowphasePairs, SphereOnBoxEdge) {
    // Centre (0.8, 0.8, 0) is nearest B's edge x = y = 0.5, at distance sqrt(0.18): the
    // normal is (-1, -1, 0)/sqrt 2, depth 0.5 - sqrt(0.18) = 0.07574, B's point on the edge.
    const real distance = std::sqrt(0.18);
    const Vector3 n = Vector3(-1, -1, 0).normalized();
    Expected e = flat({{Vector3(0.8, 0.8, 0) + 0.5 * n, Vector3(0.5, 0.5, 0)}}, n);
    e.depth = 0.5 - distance;
    expectContact(sphere(), pose(Vector3(0.8, 0.8, 0)), box(), Matrix4::Identity(), e);
}

TEST(NarrowphasePairs, CapsuleSideOnBox) {
    // Capsule along x at (0.3, 0.7, 0): its lowest line x in [-0.2, 0.8] at y = 0.45,
    // clipped to the box's top x <= 0.5: two points.
    expectContact(capsule(), pose(Vector3(0.3, 0.7, 0), zAlongX()), box(), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.2, 0}, {0.5, 0}})));
}

TEST(NarrowphasePairs, CylinderCapOnBox) {
    // Standing cylinder at (0, 0.95, 0): its bottom cap (radius 0.4) at y = 0.45 lies
    // inside the box's top face.
    expectContact(cylinder(), pose(Vector3(0, 0.95, 0), zUp()), box(), Matrix4::Identity(), capOn(0.5, 0, 0));
}

TEST(NarrowphasePairs, CylinderCapOverhangingBox) {
    // Cap centred at x = 0.3 overhangs the box's side x = 0.5: points on the rim inside
    // the face, and at the cut x = 0.5 where the rim leaves it.
    Expected e;
    e.normal = kDown;
    e.depth = kDepth;
    e.minPoints = 3;
    e.eachPoint = [](const Vector3 &a, const Vector3 &b) {
        EXPECT_LE(b.x(), 0.5 + 1e-9);
        EXPECT_NEAR(b.y(), 0.5, 1e-9);
        const real r = Vector3(a.x() - 0.3, 0, a.z()).norm();
        EXPECT_TRUE(std::abs(r - 0.4) < 1e-9 || std::abs(b.x() - 0.5) < 1e-9) << "rim or cut, at " << b.transpose();
    };
    expectContact(cylinder(), pose(Vector3(0.3, 0.95, 0), zUp()), box(), Matrix4::Identity(), e);
}

TEST(NarrowphasePairs, CylinderSideOnBox) {
    // Cylinder along x at (0.1, 0.85, 0): its lowest line x in [-0.4, 0.6] at y = 0.45,
    // clipped to x <= 0.5.
    expectContact(cylinder(), pose(Vector3(0.1, 0.85, 0), zAlongX()), box(), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.4, 0}, {0.5, 0}})));
}

TEST(NarrowphasePairs, ConvexBaseOnBox) {
    // Pyramid at (0, 0.7, 0): base corners (+-0.4, 0.45, +-0.4).
    expectContact(pyramid(), pose(Vector3(0, 0.7, 0)), box(), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.4, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.4, 0.4}})));
}

TEST(NarrowphasePairs, ConvexApexOnBox) {
    // Pyramid upside down (half a turn about z): apex at centre - 0.75 y; centre
    // (0.1, 1.2, 0.1) puts it at (0.1, 0.45, 0.1). One point; FCL's MPR normal is replaced
    // by the box's face normal, along which the overlap is least.
    expectContact(pyramid(), pose(Vector3(0.1, 1.2, 0.1), rotation(kPi, Vector3::UnitZ())), box(), Matrix4::Identity(),
                  flat(onTop(0.5, {{0.1, 0.1}})));
}

TEST(NarrowphasePairs, BoxEdgeAcrossBoxEdge) {
    // B turned 45 degrees about z has a top edge along z at y = sqrt(2)/2; A turned 45
    // degrees about x has a bottom edge along x at its centre height - sqrt(2)/2. With A's
    // centre at sqrt(2) - 0.05 the edges cross at the origin's vertical, 0.05 deep.
    const real h = std::sqrt(0.5);
    Expected e = flat({{Vector3(0, h - kDepth, 0), Vector3(0, h, 0)}});
    expectContact(box(), pose(Vector3(0, 2 * h - kDepth, 0), rotation(kPi / 4, Vector3::UnitX())), box(),
                  pose(Vector3::Zero(), rotation(kPi / 4, Vector3::UnitZ())), e);
}

TEST(NarrowphasePairs, BoxTurnedOnBox) {
    // A turned 45 degrees about y: the overlap of the two squares is an octagon; four of
    // its corners are kept, all 0.05 deep, well spread.
    Expected e;
    e.normal = kDown;
    e.depth = kDepth;
    e.minPoints = 4;
    e.eachPoint = [](const Vector3 &a, const Vector3 &b) {
        EXPECT_NEAR(a.y(), 0.45, 1e-9);
        EXPECT_NEAR(b.y(), 0.5, 1e-9);
        EXPECT_LE(std::max(std::abs(b.x()), std::abs(b.z())), 0.5 + 1e-9);
        EXPECT_LE(std::abs(b.x()) + std::abs(b.z()), std::sqrt(0.5) + 1e-9);
    };
    expectContact(box(), pose(Vector3(0, 0.95, 0), rotation(kPi / 4, Vector3::UnitY())), box(), Matrix4::Identity(), e);
}

// ---- Sphere ----

TEST(NarrowphasePairs, SphereSphere) {
    // Radii 0.5 and 0.3, centres 0.7 apart along x: depth 0.1, normal +x from A to B.
    Expected e = flat({{Vector3(0.5, 0, 0), Vector3(0.4, 0, 0)}}, Vector3::UnitX());
    e.depth = 0.1;
    expectContact(sphere(), Matrix4::Identity(), Shape::sphere(0.3), pose(Vector3(0.7, 0, 0)), e);
}

TEST(NarrowphasePairs, SphereAgainstCapsuleSide) {
    // Standing capsule at the origin; sphere centre (0.7, 0.2, 0) is 0.7 from the axis:
    // depth 0.5 + 0.25 - 0.7, normal -x.
    expectContact(sphere(), pose(Vector3(0.7, 0.2, 0)), capsule(), pose(Vector3::Zero(), zUp()),
                  flat({{Vector3(0.2, 0.2, 0), Vector3(0.25, 0.2, 0)}}, -Vector3::UnitX()));
}

TEST(NarrowphasePairs, SphereOnCapsuleEnd) {
    // The capsule's top end sphere is centred at y = 0.5; the sphere at (0, 1.2, 0) is 0.7
    // above it: depth 0.05, B's point at y = 0.75.
    expectContact(sphere(), pose(Vector3(0, 1.2, 0)), capsule(), pose(Vector3::Zero(), zUp()),
                  flat(onTop(0.75, {{0, 0}})));
}

TEST(NarrowphasePairs, SphereOnCylinderCap) {
    expectContact(sphere(), pose(Vector3(0.1, 0.95, 0)), cylinder(), pose(Vector3::Zero(), zUp()),
                  flat(onTop(0.5, {{0.1, 0}})));
}

TEST(NarrowphasePairs, SphereAgainstCylinderSide) {
    // Centre 0.85 from the axis of a cylinder of radius 0.4: depth 0.05, normal -x.
    expectContact(sphere(), pose(Vector3(0.85, 0, 0)), cylinder(), pose(Vector3::Zero(), zUp()),
                  flat({{Vector3(0.35, 0, 0), Vector3(0.4, 0, 0)}}, -Vector3::UnitX()));
}

TEST(NarrowphasePairs, SphereOnConvex) {
    expectContact(sphere(), pose(Vector3(0.1, 0.95, 0.2)), convexCube(0.5), Matrix4::Identity(),
                  flat(onTop(0.5, {{0.1, 0.2}})));
}

// ---- Capsule ----

TEST(NarrowphasePairs, CapsuleOnCapsuleParallel) {
    // Both along x; A at (0, 0.45, 0), B at (0.2, 0, 0): axes 0.45 apart, radii 0.25 each.
    // A's lowest line y = 0.2 over B's highest y = 0.25, overlapping in x in [-0.3, 0.5].
    expectContact(capsule(), pose(Vector3(0, 0.45, 0), zAlongX()), capsule(), pose(Vector3(0.2, 0, 0), zAlongX()),
                  mpr(onTop(0.25, {{-0.3, 0}, {0.5, 0}})));
}

TEST(NarrowphasePairs, CapsuleAcrossCapsule) {
    // A along x above B along z: the axes cross at the origin's vertical: one point.
    expectContact(capsule(), pose(Vector3(0, 0.45, 0), zAlongX()), capsule(), Matrix4::Identity(),
                  mpr(onTop(0.25, {{0, 0}})));
}

TEST(NarrowphasePairs, CapsuleOnCylinderCap) {
    // Capsule along x at (0, 0.7, 0) across the standing cylinder's cap (radius 0.4, a
    // 16-gon with corners at x = +-0.4 on the x axis): clipped to x in [-0.4, 0.4].
    expectContact(capsule(), pose(Vector3(0, 0.7, 0), zAlongX()), cylinder(), pose(Vector3::Zero(), zUp()),
                  flat(onTop(0.5, {{-0.4, 0}, {0.4, 0}})));
}

TEST(NarrowphasePairs, CapsuleOnConvex) {
    expectContact(capsule(), pose(Vector3(0.3, 0.7, 0), zAlongX()), convexCube(0.5), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.2, 0}, {0.5, 0}})));
}

// ---- Cylinder ----

TEST(NarrowphasePairs, CylinderCapOnCylinderCap) {
    // Two standing cylinders, A's axis 0.1 to the side: every point lies in both caps.
    Expected e;
    e.normal = kDown;
    e.depth = kDepth;
    e.minPoints = 3;
    e.eachPoint = [](const Vector3 &a, const Vector3 &b) {
        EXPECT_NEAR(a.y(), 0.45, 1e-9);
        EXPECT_NEAR(b.y(), 0.5, 1e-9);
        EXPECT_LE(Vector3(b.x(), 0, b.z()).norm(), 0.4 + 1e-9);
        EXPECT_LE(Vector3(b.x() - 0.1, 0, b.z()).norm(), 0.4 + 1e-9);
    };
    expectContact(cylinder(), pose(Vector3(0.1, 0.95, 0), zUp()), cylinder(), pose(Vector3::Zero(), zUp()), e);
}

TEST(NarrowphasePairs, CylinderSideOnCylinderSide) {
    // Both along x, A at (0.1, 0.75, 0): axes 0.75 apart, radii 0.4 each; lines overlap in
    // x in [-0.4, 0.5].
    expectContact(cylinder(), pose(Vector3(0.1, 0.75, 0), zAlongX()), cylinder(), pose(Vector3::Zero(), zAlongX()),
                  mpr(onTop(0.4, {{-0.4, 0}, {0.5, 0}})));
}

TEST(NarrowphasePairs, CylinderCapOnConvex) {
    expectContact(cylinder(), pose(Vector3(0, 0.95, 0), zUp()), convexCube(0.5), Matrix4::Identity(), capOn(0.5, 0, 0));
}

// ---- Convex ----

TEST(NarrowphasePairs, ConvexOnConvex) {
    expectContact(pyramid(), pose(Vector3(0, 0.7, 0)), convexCube(0.5), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.4, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.4, 0.4}})));
}

TEST(NarrowphasePairs, ConvexCubeOnBoxOffset) {
    expectContact(convexCube(0.5), pose(Vector3(0.3, 0.95, 0.2)), box(), Matrix4::Identity(),
                  flat(onTop(0.5, {{-0.2, -0.3}, {0.5, -0.3}, {0.5, 0.5}, {-0.2, 0.5}})));
}

// ---- Plane (y <= 0) ----

TEST(NarrowphasePairs, BoxOnPlane) {
    expectContact(box(), pose(Vector3(0.1, 0.45, -0.2)), floorPlane(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.4, -0.7}, {0.6, -0.7}, {0.6, 0.3}, {-0.4, 0.3}})));
}

TEST(NarrowphasePairs, SphereOnPlane) {
    expectContact(sphere(), pose(Vector3(0.2, 0.45, -0.1)), floorPlane(), Matrix4::Identity(),
                  flat(onTop(0, {{0.2, -0.1}})));
}

TEST(NarrowphasePairs, CapsuleSideOnPlane) {
    expectContact(capsule(), pose(Vector3(0, 0.2, 0), zAlongX()), floorPlane(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.5, 0}, {0.5, 0}})));
}

TEST(NarrowphasePairs, CylinderCapOnPlane) {
    expectContact(cylinder(), pose(Vector3(0, 0.45, 0), zUp()), floorPlane(), Matrix4::Identity(), capOn(0, 0, 0));
}

TEST(NarrowphasePairs, CylinderSideOnPlane) {
    expectContact(cylinder(), pose(Vector3(0, 0.35, 0), zAlongX()), floorPlane(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.5, 0}, {0.5, 0}})));
}

TEST(NarrowphasePairs, CylinderRimOnPlane) {
    // Standing cylinder tilted 30 degrees about z: its lowest point is the rim point
    // centre + R (0.4 (local x), -0.5 (local axis)), 0.5 cos 30 + 0.4 sin 30 = 0.63301 below
    // the centre. With the centre at 0.63301 - 0.05 one point, exact for a plane.
    const Quaternion q = rotation(kPi / 6, Vector3::UnitZ()) * zUp();
    const real drop = 0.5 * std::cos(kPi / 6) + 0.4 * std::sin(kPi / 6);
    const Vector3 centre(0.2, drop - kDepth, 0.1);
    const Vector3 rim = centre + q.toRotationMatrix() * Vector3(-0.4, 0, -0.5);
    ASSERT_NEAR(rim.y(), -kDepth, 1e-12);  // The rim point really is the lowest one.
    expectContact(cylinder(), pose(centre, q), floorPlane(), Matrix4::Identity(),
                  flat({{rim, Vector3(rim.x(), 0, rim.z())}}));
}

TEST(NarrowphasePairs, ConvexBaseOnPlane) {
    expectContact(pyramid(), pose(Vector3(0, 0.2, 0)), floorPlane(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.4, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.4, 0.4}})));
}

TEST(NarrowphasePairs, PlaneWithALongNormal) {
    // Normal (0, 2, 0) and offset 0.2: the solid is 2y <= 0.2, y <= 0.1.
    expectContact(box(), pose(Vector3(0, 0.55, 0)), Shape::plane(Vector3(0, 2, 0), 0.2), Matrix4::Identity(),
                  flat(onTop(0.1, {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}})));
}

TEST(NarrowphasePairs, SphereOnSlopedPlane) {
    // Plane x + y <= 0; the sphere's centre 0.45 along its unit normal n: depth 0.05,
    // A's point at -0.05 n, B's at the origin; the normal from A to B is -n.
    const Vector3 n = Vector3(1, 1, 0).normalized();
    expectContact(sphere(), pose(0.45 * n), Shape::plane(Vector3(1, 1, 0), 0), Matrix4::Identity(),
                  flat({{-kDepth * n, Vector3::Zero()}}, -n));
}

// ---- Mesh floor (two triangles meeting along x = z, normals up) ----

TEST(NarrowphasePairs, BoxOnMeshAcrossTheDiagonal) {
    // The box's bottom x in [-0.2, 0.8], z in [-0.3, 0.7] lies on both triangles: one
    // manifold of its four corners.
    expectContact(box(), pose(Vector3(0.3, 0.45, 0.2)), meshFloor(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.2, -0.3}, {0.8, -0.3}, {0.8, 0.7}, {-0.2, 0.7}})));
}

TEST(NarrowphasePairs, SphereOnMeshNearTheDiagonal) {
    // The sphere also touches the other triangle's edge, 0.1/sqrt(2) away; that edge
    // contact is an internal edge of the floor and is dropped: one point, normal -y.
    expectContact(sphere(), pose(Vector3(0.3, 0.45, 0.2)), meshFloor(), Matrix4::Identity(),
                  flat(onTop(0, {{0.3, 0.2}})));
}

TEST(NarrowphasePairs, CapsuleOnMeshAcrossTheDiagonal) {
    expectContact(capsule(), pose(Vector3(0.3, 0.2, 0.2), zAlongX()), meshFloor(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.2, 0.2}, {0.8, 0.2}})));
}

TEST(NarrowphasePairs, CylinderCapOnMesh) {
    expectContact(cylinder(), pose(Vector3(0.3, 0.45, 0.2), zUp()), meshFloor(), Matrix4::Identity(),
                  capOn(0, 0.3, 0.2));
}

TEST(NarrowphasePairs, ConvexBaseOnMesh) {
    expectContact(pyramid(), pose(Vector3(0.3, 0.2, 0.2)), meshFloor(), Matrix4::Identity(),
                  flat(onTop(0, {{-0.1, -0.2}, {0.7, -0.2}, {0.7, 0.6}, {-0.1, 0.6}})));
}

// ---- Normals that FCL's MPR only approximates, refined ----
// Refinement stops once the depth no longer improves, which leaves the normal within
// about 1e-4 rad of the true one and the depth within 1e-5 m.
constexpr real kRefinedNormal = 1e-4;
constexpr real kRefinedDepth = 1e-5;
constexpr real kRefinedPoint = 1e-4;

TEST(NarrowphasePairs, CapsulesCrossingAtAnAngle) {
    // A along x at height 0.45; B at the origin along (cos t, 0, sin t) but shifted 0.3
    // along its own axis. The axes are skew lines whose common perpendicular is the y axis
    // (through x = z = 0 on both), 0.45 long: depth 0.25 + 0.25 - 0.45 = 0.05 there.
    for (real degrees : {20.0, 50.0, 75.0}) {
        SCOPED_TRACE("angle " + std::to_string(degrees));
        const real t = degrees * kPi / 180;
        const Vector3 axis(std::cos(t), 0, std::sin(t));
        const Quaternion q = Quaternion::FromTwoVectors(Vector3::UnitZ(), axis);
        Expected e = flat(onTop(0.25, {{0, 0}}));
        e.normalTolerance = kRefinedNormal;
        e.depthTolerance = kRefinedDepth;
        e.pointTolerance = kRefinedPoint;
        expectContact(capsule(), pose(Vector3(0, 0.45, 0), zAlongX()), capsule(), pose(0.3 * axis, q), e);
    }
}

TEST(NarrowphasePairs, SphereOnConvexApex) {
    // Pyramid at the origin, apex at (0, 0.75, 0). The sphere's centre (0.1, 1.2, 0) is
    // sqrt(0.1^2 + 0.45^2) = 0.46098 from the apex and within the apex's normal cone (its
    // direction is 12.5 degrees from vertical, the side faces lean 68 degrees): the apex
    // is the nearest point, depth 0.5 - 0.46098, normal from the centre to the apex.
    const Vector3 apex(0, 0.75, 0);
    const Vector3 centre(0.1, 1.2, 0);
    const Vector3 n = (apex - centre).normalized();
    Expected e = flat({{centre + 0.5 * n, apex}}, n);
    e.depth = 0.5 - (centre - apex).norm();
    e.normalTolerance = kRefinedNormal;
    e.depthTolerance = kRefinedDepth;
    e.pointTolerance = kRefinedPoint;
    expectContact(sphere(), pose(centre), pyramid(), Matrix4::Identity(), e);
}

TEST(NarrowphasePairs, CylinderSideAcrossBoxEdge) {
    // A cylinder lying along z rests across the box's top edge x = 0.5, y = 0.5, its axis
    // at (0.5 + 0.4 s, 0.5 + 0.4 c) - 0.05 (s, c) for the direction (s, c) = (sin, cos) 30
    // degrees from vertical: the edge is 0.35 from the axis, 0.05 deep, normal -(s, c).
    const real s = 0.5, c = std::sqrt(0.75);
    const Vector3 out(s, c, 0);
    const Vector3 edge(0.5, 0.5, 0);
    const Vector3 centre = edge + 0.35 * out;
    // Along the edge the contact is a line: one or two points on it.
    Expected e = flat({}, -out);
    e.minPoints = 1;
    e.maxPoints = 2;
    e.normalTolerance = kRefinedNormal;
    e.depthTolerance = kRefinedDepth;
    e.eachPoint = [&](const Vector3 &a, const Vector3 &b) {
        EXPECT_NEAR(b.x(), 0.5, kRefinedPoint);
        EXPECT_NEAR(b.y(), 0.5, kRefinedPoint);
        EXPECT_LT((a - (b - kDepth * out)).norm(), kRefinedPoint);
    };
    expectContact(cylinder(), pose(centre), box(), Matrix4::Identity(), e);
}

}  // namespace
}  // namespace cyclone::test
