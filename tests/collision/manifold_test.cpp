// Manifold behaviour beyond single pairs: tilted faces and the speculative margin,
// pairs apart, appending, meshes with internal edges and walls, far-away poses.
#include <gtest/gtest.h>

#include <random>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

const Shape kBox = Shape::box(Vector3(0.5, 0.5, 0.5));
const Shape kFloor = Shape::plane(Vector3::UnitY(), 0);

// A unit box turned by `angle` about z, its lowest edge `depth` below y = 0. Its bottom
// corners are at x = +-0.5, y = -0.5 before turning; after turning the corner with
// local x = -0.5 is lower by sin(angle) than the one with x = +0.5.
Matrix4 tiltedBox(real angle, real depth) {
    const real lowest = 0.5 * std::cos(angle) + 0.5 * std::sin(angle);
    return pose(Vector3(0, lowest - depth, 0), rotation(angle, Vector3::UnitZ()));
}

// Checks a tilted box's manifold: two points at `depth` on the low side (x < 0) and,
// if within the speculative distance, two at `highDepth` on the high side.
void expectTiltedContact(const std::vector<Manifold> &out, real depth, real highDepth, real speculative) {
    ASSERT_EQ(out.size(), 1u);
    const Manifold &m = out[0];
    EXPECT_LT((m.normal - Vector3(0, -1, 0)).norm(), 1e-9);
    const bool highKept = highDepth > -speculative;
    EXPECT_EQ(m.count, highKept ? 4 : 2);
    int low = 0, high = 0;
    for (int i = 0; i < m.count; ++i) {
        const detail::ContactPoint &p = m.points[i];
        const bool isLow = p.pointA.x() < 0;
        if (isLow) {
            ++low;
            EXPECT_NEAR(p.depth, depth, 1e-9);
        } else {
            ++high;
            EXPECT_NEAR(p.depth, highDepth, 1e-9);
            EXPECT_LT(p.depth, 0) << "the high side is speculative";
        }
    }
    EXPECT_EQ(low, 2);
    EXPECT_EQ(high, highKept ? 2 : 0);
}

TEST(Manifold, BoxTiltedSlightlyOnPlaneKeepsItsHighSideSpeculative) {
    // 0.02 rad: the high side is sin(0.02) - 0.005 = 0.015 above the plane, within the
    // 0.02 margin: four points, two at -0.015.
    expectTiltedContact(collide(kBox, tiltedBox(0.02, 0.005), kFloor, Matrix4::Identity()), 0.005,
                        0.005 - std::sin(0.02), 0.02);
}

TEST(Manifold, BoxTiltedMoreOnPlaneDropsItsHighSide) {
    // 0.05 rad: the high side is sin(0.05) - 0.005 = 0.045 above: two points.
    expectTiltedContact(collide(kBox, tiltedBox(0.05, 0.005), kFloor, Matrix4::Identity()), 0.005,
                        0.005 - std::sin(0.05), 0.02);
}

TEST(Manifold, BoxTiltedOnBox) {
    // The same on top of a box whose top is at y = 0.5. The low corners are at
    // x_low = -0.5 cos + 0.5 sin (inside the lower box's top); the high corners reach
    // beyond its side x = 0.5 and are clipped there, where the tilted bottom face is
    // (0.5 - x_low) tan(angle) above the low corners.
    for (real angle : {0.02, 0.05}) {
        SCOPED_TRACE("angle " + std::to_string(angle));
        Matrix4 a = tiltedBox(angle, 0.005);
        a.translation().y() += 0.5;
        std::vector<Manifold> out = collide(kBox, a, kBox, Matrix4::Identity());
        ASSERT_EQ(out.size(), 1u);
        const real lowX = -0.5 * std::cos(angle) + 0.5 * std::sin(angle);
        for (int i = 0; i < out[0].count; ++i) {
            EXPECT_NEAR(out[0].points[i].pointB.y(), 0.5, 1e-12);
            if (out[0].points[i].pointA.x() > 0) {
                EXPECT_NEAR(out[0].points[i].pointA.x(), 0.5, 1e-12);
            }
        }
        expectTiltedContact(out, 0.005, 0.005 - (0.5 - lowX) * std::tan(angle), 0.02);
    }
}

TEST(Manifold, ZeroSpeculativeDistanceKeepsOnlyPenetratingPoints) {
    expectTiltedContact(collide(kBox, tiltedBox(0.02, 0.005), kFloor, Matrix4::Identity(), 0), 0.005,
                        0.005 - std::sin(0.02), 0);
}

TEST(Manifold, CylinderCapTiltedOnPlane) {
    // Standing cylinder (r = 0.4, length 1) tilted 5 degrees about z: the deepest point is
    // the rim point at local x = -0.4 of the bottom cap; the cap's other points lie higher,
    // up to 0.8 sin 5 deg = 0.0697 above it, so only points within 0.02 of the plane stay.
    const real angle = 5 * kPi / 180;
    const Quaternion q = rotation(angle, Vector3::UnitZ()) * zUp();
    const real drop = 0.5 * std::cos(angle) + 0.4 * std::sin(angle);
    const std::vector<Manifold> out =
        collide(Shape::cylinder(0.4, 1), pose(Vector3(0, drop - 0.01, 0), q), kFloor, Matrix4::Identity());
    ASSERT_EQ(out.size(), 1u);
    const Manifold &m = out[0];
    EXPECT_LT((m.normal - Vector3(0, -1, 0)).norm(), 1e-12);
    ASSERT_GE(m.count, 3);
    real deepest = -1;
    for (int i = 0; i < m.count; ++i) {
        deepest = std::max(deepest, m.points[i].depth);
        EXPECT_GT(m.points[i].depth, -0.02);
        EXPECT_NEAR(m.points[i].pointB.y(), 0, 1e-12);
    }
    EXPECT_NEAR(deepest, 0.01, 1e-12);
    EXPECT_TRUE(nonCollinear(m));
}

TEST(Manifold, ContactOrderStartsFromTheDeepestPoint) {
    // Corners of a unit square, the second deepest: it comes first, then the corner
    // farthest from it (the diagonal, index 3); the other two span equal triangles with
    // those, and the first of them in the input wins the tie.
    const Vector3 pointB[4] = {Vector3(-0.5, 0, -0.5), Vector3(0.5, 0, -0.5), Vector3(0.5, 0, 0.5), Vector3(-0.5, 0, 0.5)};
    const real depth[4] = {0.001, 0.003, 0.002, 0.001};
    int order[4];
    detail::contactOrder(pointB, depth, 4, Vector3::UnitY(), order);
    EXPECT_EQ(order[0], 1);
    EXPECT_EQ(order[1], 3);
    EXPECT_EQ(order[2], 0);
    EXPECT_EQ(order[3], 2);
}

TEST(Manifold, ContactOrderKeepsPointsThatAddNothingLast) {
    // Three points on a line, equally deep: the ends are the farthest from the centre
    // (the first of them wins), then the other end; the middle spans no area and comes last.
    const Vector3 pointB[3] = {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0.5, 0, 0)};
    const real depth[3] = {0.001, 0.001, 0.001};
    int order[3];
    detail::contactOrder(pointB, depth, 3, Vector3::UnitY(), order);
    EXPECT_EQ(order[0], 0);
    EXPECT_EQ(order[1], 1);
    EXPECT_EQ(order[2], 2);
}

TEST(Manifold, ContactOrderGivesBackAFreshManifoldsOrder) {
    // A box tilted about two axes lies on its four bottom corners, each at its own depth
    // (0.5 cm down to about -1 cm). contactOrder on those points listed from the third
    // on must give the order collide() listed them in: a reused manifold is solved as a
    // fresh one. (The last two corners span equal triangles with the first two, and a
    // tie goes to the one listed first: the rotation keeps those two in their order.)
    const Quaternion tilt = rotation(0.01, Vector3::UnitZ()) * rotation(0.005, Vector3::UnitX());
    const Matrix4 boxPose = pose(Vector3(0, 0.49, 0), tilt);
    const std::vector<Manifold> fresh = collide(kBox, boxPose, kFloor, Matrix4::Identity());
    ASSERT_EQ(fresh.size(), 1u);
    const Manifold &m = fresh[0];
    ASSERT_EQ(m.count, 4);
    Vector3 pointB[4];
    real depth[4];
    for (int i = 0; i < 4; ++i) {
        pointB[i] = m.points[(i + 2) % 4].pointB;
        depth[i] = m.points[(i + 2) % 4].depth;
    }
    int order[4];
    detail::contactOrder(pointB, depth, 4, m.normal, order);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(order[i], (i + 2) % 4);
}

TEST(Manifold, NothingWhenApart) {
    // 1 cm apart: within the speculative distance but not touching; FCL reports nothing.
    EXPECT_TRUE(collide(kBox, pose(Vector3(0, 0.51, 0)), kFloor, Matrix4::Identity()).empty());
    EXPECT_TRUE(collide(kBox, pose(Vector3(0, 1.01, 0)), kBox, Matrix4::Identity()).empty());
    EXPECT_TRUE(collide(Shape::sphere(0.5), pose(Vector3(3, 0.51, 0)), meshFloor(), Matrix4::Identity()).empty());
}

TEST(Manifold, CollideAppendsAndCountsWhatItAppended) {
    const auto box = detail::compileShape(kBox);
    const auto floor = detail::compileShape(kFloor);
    std::vector<Manifold> out(2);
    const int appended =
        detail::collide(*box, pose(Vector3(0, 0.45, 0)), *floor, Matrix4::Identity(), detail::NarrowphaseSettings(), out);
    EXPECT_EQ(appended, 1);
    EXPECT_EQ(out.size(), 3u);
    EXPECT_EQ(out[2].count, 4);
}

TEST(Manifold, ConcentricSpheresArePushedApartSideways) {
    // Coincident centres have no line between them: the normal is +x (sideways), and the
    // depth the sum of the radii, 0.5 + 0.3 = 0.8 m (the overlap along any direction).
    const std::vector<Manifold> out = collide(Shape::sphere(0.5), Matrix4::Identity(), Shape::sphere(0.3), Matrix4::Identity());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].normal, Vector3::UnitX());
    EXPECT_NEAR(out[0].points[0].depth, 0.8, 1e-15);
    // 1e-200 m apart along z: that direction still (it does not underflow to none).
    const std::vector<Manifold> apart = collide(Shape::sphere(0.5), Matrix4::Identity(), Shape::sphere(0.3), pose(Vector3(0, 0, 1e-200)));
    ASSERT_EQ(apart.size(), 1u);
    EXPECT_EQ(apart[0].normal, Vector3::UnitZ());
}

TEST(Manifold, SharedShapeBetweenTwoBodies) {
    // The World may give many bodies one compiled shape: FCL then sees the same geometry
    // pointer twice, and the normal must still point from A to B.
    const auto box = detail::compileShape(kBox);
    std::vector<Manifold> out;
    detail::collide(*box, pose(Vector3(0, 0.95, 0)), *box, Matrix4::Identity(), detail::NarrowphaseSettings(), out);
    detail::collide(*box, Matrix4::Identity(), *box, pose(Vector3(0, 0.95, 0)), detail::NarrowphaseSettings(), out);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_LT((out[0].normal - Vector3(0, -1, 0)).norm(), 1e-12);
    EXPECT_LT((out[1].normal - Vector3(0, 1, 0)).norm(), 1e-12);
}

TEST(Manifold, FarFromTheOriginOnAPlane) {
    // 10 km out, a plane contact keeps its precision: it is never clipped against the
    // plane's feature square.
    const Vector3 centre(1e4, 0.45, -1e4);
    const std::vector<Manifold> out = collide(kBox, pose(centre), kFloor, Matrix4::Identity());
    ASSERT_EQ(out.size(), 1u);
    ASSERT_EQ(out[0].count, 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(out[0].points[i].depth, 0.05, 1e-9);
        EXPECT_NEAR(std::abs(out[0].points[i].pointA.x() - centre.x()), 0.5, 1e-9);
        EXPECT_NEAR(std::abs(out[0].points[i].pointA.z() - centre.z()), 0.5, 1e-9);
    }
}

TEST(Manifold, PlaneWithAPose) {
    // The plane y <= 0 placed 1 m up: its surface is at y = 1.
    const std::vector<Manifold> out = collide(kBox, pose(Vector3(0, 1.45, 0)), kFloor, pose(Vector3(0, 1, 0)));
    ASSERT_EQ(out.size(), 1u);
    ASSERT_EQ(out[0].count, 4);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(out[0].points[i].depth, 0.05, 1e-12);
        EXPECT_NEAR(out[0].points[i].pointB.y(), 1, 1e-12);
    }
}

TEST(Manifold, MeshFloorGivesOneManifoldWhereverABoxOrSphereIs) {
    // Sliding across the diagonal x = z: every position gives one manifold with the
    // floor's normal, never a tilted normal from the shared edge.
    for (int k = -10; k <= 10; ++k) {
        const real x = 0.05 * k;
        SCOPED_TRACE("x = " + std::to_string(x));
        for (const Shape &shape : {kBox, Shape::sphere(0.5)}) {
            const std::vector<Manifold> out = collide(shape, pose(Vector3(x, 0.49, -x / 3)), meshFloor(), Matrix4::Identity());
            ASSERT_EQ(out.size(), 1u);
            EXPECT_LT((out[0].normal - Vector3(0, -1, 0)).norm(), 1e-9);
            EXPECT_EQ(out[0].count, shape.type == ShapeType::Box ? 4 : 1);
            for (int i = 0; i < out[0].count; ++i) EXPECT_NEAR(out[0].points[i].depth, 0.01, 1e-9);
        }
    }
}

TEST(Manifold, MeshCollidesOnBothSidesUnlessOneIsSolid) {
    // The floor's triangles wound facing down. Two-sided (the default), a unit box 0.01 m
    // into it from above is pushed up (normal A to B: -y) and one from below is pushed
    // down, each 0.01 deep at its four corners. One-sided with the solid behind the
    // winding's side (Front: the solid above), the box from above is inside the solid
    // and pushed out downwards, through the floor: its top must clear y = 0, 0.99 m.
    const std::vector<Vector3> corners{Vector3(-5, 0, -5), Vector3(5, 0, -5), Vector3(5, 0, 5), Vector3(-5, 0, 5)};
    const std::vector<std::array<int, 3>> down{{0, 1, 2}, {0, 2, 3}};
    struct Case {
        MeshSides sides;
        real y;
        Vector3 normal;
        real depth;
    };
    for (const Case &c : {Case{MeshSides::Both, 0.49, Vector3(0, -1, 0), 0.01},
                          Case{MeshSides::Both, -0.49, Vector3(0, 1, 0), 0.01},
                          Case{MeshSides::Front, 0.49, Vector3(0, 1, 0), 0.99}}) {
        SCOPED_TRACE("y = " + std::to_string(c.y));
        const std::vector<Manifold> out =
            collide(kBox, pose(Vector3(0.1, c.y, 0.2)), Shape::mesh(corners, down, c.sides), Matrix4::Identity());
        ASSERT_EQ(out.size(), 1u);
        EXPECT_LT((out[0].normal - c.normal).norm(), 1e-9);
        ASSERT_EQ(out[0].count, 4);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(out[0].points[i].depth, c.depth, 1e-9);
    }
}

TEST(Manifold, MeshFloorAndWallGiveTwoManifolds) {
    // The floor plus a wall x = 1 facing -x (its triangles share the floor's corner
    // vertices 1 and 2). A box at x = 0.55 sinks 0.05 into the wall and 0.05 into the floor:
    // one manifold with normal -y (A to B) and one with +x.
    const Shape mesh = Shape::mesh({Vector3(-5, 0, -5), Vector3(1, 0, -5), Vector3(1, 0, 5), Vector3(-5, 0, 5),
                                    Vector3(1, 3, -5), Vector3(1, 3, 5)},
                                   {{0, 2, 1}, {0, 3, 2}, {1, 2, 5}, {1, 5, 4}});
    const std::vector<Manifold> out = collide(kBox, pose(Vector3(0.55, 0.45, 0)), mesh, Matrix4::Identity());
    ASSERT_EQ(out.size(), 2u);
    int floor = out[0].normal.y() < -0.5 ? 0 : 1;
    const Manifold &onFloor = out[floor];
    const Manifold &onWall = out[1 - floor];
    EXPECT_LT((onFloor.normal - Vector3(0, -1, 0)).norm(), 1e-9);
    EXPECT_LT((onWall.normal - Vector3(1, 0, 0)).norm(), 1e-9);
    EXPECT_GE(onFloor.count, 3);
    EXPECT_GE(onWall.count, 3);
    for (int i = 0; i < onFloor.count; ++i) EXPECT_NEAR(onFloor.points[i].depth, 0.05, 1e-9);
    for (int i = 0; i < onWall.count; ++i) EXPECT_NEAR(onWall.points[i].depth, 0.05, 1e-9);
    EXPECT_TRUE(nonCollinear(onFloor));
    EXPECT_TRUE(nonCollinear(onWall));
}

TEST(Manifold, DeepBoxInMeshFloor) {
    // 0.3 m deep: still the floor's normal and depth.
    const std::vector<Manifold> out = collide(kBox, pose(Vector3(0.1, 0.2, 0.3)), meshFloor(), Matrix4::Identity());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_LT((out[0].normal - Vector3(0, -1, 0)).norm(), 1e-9);
    ASSERT_EQ(out[0].count, 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(out[0].points[i].depth, 0.3, 1e-9);
}

TEST(Manifold, InvariantsOverRandomShallowContacts) {
    // Every pair of shapes, at random orientations, brought into contact 0.01 deep along
    // a random direction (bisection on FCL's yes/no answer, then 0.01 back). Whatever the
    // pair: unit normals, at most four points, depth = (pointA - pointB).normal, no point
    // beyond the speculative distance, a deepest point no deeper than the 0.01 step (the
    // step along its direction separates them, so the least overlap is at most that), and
    // the same number of manifolds in both argument orders.
    const std::vector<Shape> shapes = {Shape::box(Vector3(0.5, 0.3, 0.4)), Shape::sphere(0.4), Shape::capsule(0.25, 0.8),
                                       Shape::cylinder(0.35, 0.9), pyramid(), Shape::plane(Vector3::UnitY(), 0),
                                       meshFloor()};
    std::vector<std::shared_ptr<const CollisionShape>> compiled;
    for (const Shape &shape : shapes) compiled.push_back(detail::compileShape(shape));
    std::mt19937 random(5);
    std::uniform_real_distribution<real> uniform(-1, 1);
    auto randomRotation = [&] {
        return Quaternion(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random))
                              .normalized());
    };
    auto touching = [](const CollisionShape &a, const Matrix4 &pa, const CollisionShape &b, const Matrix4 &pb) {
        fcl::CollisionRequestd request;
        fcl::CollisionResultd result;
        return fcl::collide(a.geometry().get(), pa, b.geometry().get(), pb, request, result) > 0;
    };
    const real step = 0.01;
    detail::NarrowphaseSettings settings;
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 7; ++j) {
            for (int trial = 0; trial < 40; ++trial) {
                SCOPED_TRACE(std::string(shapeTypeName(shapes[i].type)) + " against " + shapeTypeName(shapes[j].type) +
                             ", trial " + std::to_string(trial));
                const bool ground = j >= 5;
                const Matrix4 poseB = ground ? Matrix4::Identity() : pose(Vector3::Zero(), randomRotation());
                Vector3 direction(uniform(random), uniform(random), uniform(random));
                if (ground) direction = Vector3(0.3 * uniform(random), 1, 0.3 * uniform(random));
                direction.normalize();
                const Vector3 origin = ground ? Vector3(2 * uniform(random), 0, 2 * uniform(random)) : Vector3::Zero();
                const Quaternion orientation = randomRotation();
                auto at = [&](real t) { return pose(origin + t * direction, orientation); };
                real lo = 0, hi = 4;
                ASSERT_FALSE(touching(*compiled[i], at(hi), *compiled[j], poseB));
                for (int k = 0; k < 40; ++k) {
                    const real mid = (lo + hi) / 2;
                    (touching(*compiled[i], at(mid), *compiled[j], poseB) ? lo : hi) = mid;
                }
                const Matrix4 poseA = at(hi - step);
                std::vector<Manifold> out, reversed;
                detail::collide(*compiled[i], poseA, *compiled[j], poseB, settings, out);
                detail::collide(*compiled[j], poseB, *compiled[i], poseA, settings, reversed);
                ASSERT_FALSE(out.empty());
                EXPECT_EQ(out.size(), reversed.size());
                real deepest = -1;
                for (const Manifold &m : out) {
                    EXPECT_NEAR(m.normal.norm(), 1, 1e-12);
                    EXPECT_GE(m.count, 1);
                    EXPECT_LE(m.count, 4);
                    for (int k = 0; k < m.count; ++k) {
                        const detail::ContactPoint &p = m.points[k];
                        EXPECT_NEAR((p.pointA - p.pointB).dot(m.normal), p.depth, 1e-9);
                        EXPECT_GT(p.depth, -settings.speculativeDistance);
                        deepest = std::max(deepest, p.depth);
                    }
                }
                EXPECT_LE(deepest, 1.05 * step);
            }
        }
    }
}

}  // namespace
}  // namespace cyclone::test
