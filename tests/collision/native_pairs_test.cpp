// The pairs with a test of their own (box-box, box-hull and hull-hull by separating axes,
// sphere-sphere, sphere-box, a plane against a solid shape): hand-worked cases in both
// argument orders, and agreement with the FCL path (NarrowphaseSettings::forceFcl) over
// seeded random poses.
//
// Boxes are unit cubes (half size 0.5) unless a test says otherwise; B sits at the
// origin and A comes from above, so the normal from A to B is -y. h = sqrt(0.5) is the
// height of the top edge of a unit cube turned 45 degrees about a horizontal axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "collision/polytope.h"
#include "collision_test_support.h"

namespace cyclone::test {
namespace {

const Shape kUnitBox = Shape::box(Vector3(0.5, 0.5, 0.5));
const real kH = std::sqrt(0.5);

std::vector<Manifold> viaFcl(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b,
                             const Matrix4 &poseB) {
    detail::NarrowphaseSettings settings;
    settings.forceFcl = true;
    std::vector<Manifold> out;
    detail::collide(a, poseA, b, poseB, settings, out);
    return out;
}

std::vector<Manifold> native(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b,
                             const Matrix4 &poseB) {
    std::vector<Manifold> out;
    detail::collide(a, poseA, b, poseB, detail::NarrowphaseSettings(), out);
    return out;
}

// ---- hand-worked box-box cases ----

TEST(BoxBox, SmallBoxRestingOnAFace) {
    // A (half 0.3, 0.2, 0.3) at (0.1, 0.69, -0.1): its bottom at 0.49 is 0.01 into B's top
    // at 0.5, and its bottom square x in [-0.2, 0.4], z in [-0.4, 0.2] lies inside B's top.
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    e.minPoints = e.maxPoints = 4;
    for (real x : {-0.2, 0.4})
        for (real z : {-0.4, 0.2}) e.points.push_back({Vector3(x, 0.49, z), Vector3(x, 0.5, z)});
    expectContact(Shape::box(Vector3(0.3, 0.2, 0.3)), pose(Vector3(0.1, 0.69, -0.1)), kUnitBox, Matrix4::Identity(), e);
}

TEST(BoxBox, SmallBoxTurned45DegreesOnAFace) {
    // A (half 0.3) turned 45 degrees about y at (0, 0.79, 0): its bottom corners are
    // 0.3 sqrt 2 = 0.4243 from the axis along x and z, inside B's top (0.5), 0.01 deep.
    const real r = 0.3 * std::sqrt(2.0);
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    for (const Vector3 &c : {Vector3(r, 0, 0), Vector3(-r, 0, 0), Vector3(0, 0, r), Vector3(0, 0, -r)})
        e.points.push_back({c + Vector3(0, 0.49, 0), c + Vector3(0, 0.5, 0)});
    expectContact(Shape::box(Vector3(0.3, 0.3, 0.3)), pose(Vector3(0, 0.79, 0), rotation(kPi / 4, Vector3::UnitY())),
                  kUnitBox, Matrix4::Identity(), e);
}

TEST(BoxBox, FaceOnAnEdge) {
    // B turned 45 degrees about z has a top edge along z at height h; A flat above with
    // its bottom at h - 0.01. A's face normal is the least overlap (0.01): the two ends of
    // the edge, at z = +-0.5, are the points.
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    for (real z : {-0.5, 0.5}) e.points.push_back({Vector3(0, kH - 0.01, z), Vector3(0, kH, z)});
    expectContact(kUnitBox, pose(Vector3(0, kH + 0.5 - 0.01, 0)), kUnitBox,
                  pose(Vector3::Zero(), rotation(kPi / 4, Vector3::UnitZ())), e);
}

// Two unit cubes (`cube`: a box or a hull). B turned 45 degrees about z: top edge along z
// at height h. A turned 45 degrees about x at (0.2, 2h - 0.02, -0.1): bottom edge along x
// at height h - 0.02 and z = -0.1, over x in [-0.3, 0.7]. The edges cross above (0, -0.1),
// 0.02 deep, along y (the cross product of the edges); every face axis overlaps by far more.
void expectEdgeAcrossEdge(const Shape &cube) {
    Expected e;
    e.normal = kDown;
    e.depth = 0.02;
    e.points = {{Vector3(0, kH - 0.02, -0.1), Vector3(0, kH, -0.1)}};
    e.minPoints = e.maxPoints = 1;
    expectContact(cube, pose(Vector3(0.2, 2 * kH - 0.02, -0.1), rotation(kPi / 4, Vector3::UnitX())), cube,
                  pose(Vector3::Zero(), rotation(kPi / 4, Vector3::UnitZ())), e);
}

TEST(BoxBox, EdgeAcrossEdge) { expectEdgeAcrossEdge(kUnitBox); }

TEST(BoxBox, EdgesJustApartAreSeparatedByTheirCrossProductAlone) {
    // The edge-edge case lifted to 1 mm apart: along y nothing overlaps, but along B's face
    // normal (1, 1, 0)/sqrt 2 the boxes still overlap (B's radius 0.5, A's
    // 0.5 (sqrt(0.5) + 0.5 + 0.5) = 0.854, centres 1.142 apart along it): only the
    // edge-edge axis separates them.
    const auto box = detail::compileShape(kUnitBox);
    const Matrix4 poseA = pose(Vector3(0.2, 2 * kH + 0.001, -0.1), rotation(kPi / 4, Vector3::UnitX()));
    const Matrix4 poseB = pose(Vector3::Zero(), rotation(kPi / 4, Vector3::UnitZ()));
    const Vector3 faceOfB = Vector3(1, 1, 0).normalized();
    const real alongFace = (box->supportPoint(poseA, -faceOfB, -1) - box->supportPoint(poseB, faceOfB, -1)).dot(-faceOfB);
    EXPECT_NEAR(alongFace, 0.5 + 0.5 * (kH + 1) - (0.2 + 2 * kH + 0.001) / std::sqrt(2.0), 1e-12);
    EXPECT_GT(alongFace, 0.2);
    EXPECT_TRUE(native(*box, poseA, *box, poseB).empty());
    EXPECT_TRUE(native(*box, poseB, *box, poseA).empty());
    EXPECT_TRUE(viaFcl(*box, poseA, *box, poseB).empty());
}

TEST(BoxBox, JustApartGivesNothingAndTouchingGivesZeroDepth) {
    // As FCL: 0.1 mm apart is no contact; faces exactly touching are a contact 0 deep.
    const auto box = detail::compileShape(kUnitBox);
    EXPECT_TRUE(native(*box, pose(Vector3(0.2, 1.0001, 0)), *box, Matrix4::Identity()).empty());
    EXPECT_TRUE(viaFcl(*box, pose(Vector3(0.2, 1.0001, 0)), *box, Matrix4::Identity()).empty());
    for (const std::vector<Manifold> &out : {native(*box, pose(Vector3(0.2, 1, 0)), *box, Matrix4::Identity()),
                                             viaFcl(*box, pose(Vector3(0.2, 1, 0)), *box, Matrix4::Identity())}) {
        ASSERT_EQ(out.size(), 1u);
        EXPECT_EQ(out[0].count, 4);
        EXPECT_NEAR(deepestDepth(out[0]), 0, 1e-12);
    }
}

// ---- agreement with the FCL path ----

// Seeded random poses: A approaches B along a random direction until FCL says they
// touch (bisection), then moves on by 0.5-50.5 mm, or back by 0.5-20.5 mm for a miss.
struct RandomContacts {
    std::mt19937 random;
    std::uniform_real_distribution<real> uniform{-1, 1};
    explicit RandomContacts(unsigned seed) : random(seed) {}

    Quaternion orientation() {
        return Quaternion(
            Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
    }

    // A's pose; `hit` says whether it was pushed in (3 trials in 4) or pulled back.
    Matrix4 place(const CollisionShape &a, const CollisionShape &b, const Matrix4 &poseB, bool planeB, bool &hit) {
        const Quaternion q = orientation();
        Vector3 direction(uniform(random), uniform(random), uniform(random));
        // Against a plane: away from its surface, within about 30 degrees of its normal.
        if (planeB) direction = poseB.linear() * b.planeNormal() + 0.5 * direction;
        direction.normalize();
        auto at = [&](real t) { return pose(poseB.translation() + t * direction, q); };
        // From inside (a plane: from below it) to well outside.
        real lo = planeB ? -5 : 0.05, hi = 5;
        for (int k = 0; k < 50; ++k) {
            const real mid = (lo + hi) / 2;
            (viaFcl(a, at(mid), b, poseB).empty() ? hi : lo) = mid;
        }
        hit = random() % 4 != 0;
        const real offset = 0.0005 + (hit ? 0.025 : 0.01) * (uniform(random) + 1);
        return at(hit ? hi - offset : hi + offset);
    }

    // B at a random pose, A placed against it, and both paths' manifolds of the pair.
    struct Trial {
        Matrix4 poseA, poseB;
        bool hit = false;
        std::vector<Manifold> f, n;  ///< By the FCL path, by the pair's own test.
    };
    Trial collideBoth(const CollisionShape &a, const CollisionShape &b, bool planeB) {
        Trial t;
        t.poseB = pose(Vector3(uniform(random), uniform(random), uniform(random)), orientation());
        t.poseA = place(a, b, t.poseB, planeB, t.hit);
        t.f = viaFcl(a, t.poseA, b, t.poseB);
        t.n = native(a, t.poseA, b, t.poseB);
        return t;
    }
};

// The least overlap over face axes and over edge-edge axes, by support points.
void leastOverlaps(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                   real &face, real &edge, real &secondBest) {
    std::vector<std::pair<real, bool>> all;  // overlap, is an edge axis
    auto add = [&](const Vector3 &axis, bool isEdge) {
        if (axis.norm() < 1e-6) return;
        const Vector3 n = axis.normalized();
        const real plus = (a.supportPoint(poseA, n, -1) - b.supportPoint(poseB, -n, -1)).dot(n);
        const real minus = (a.supportPoint(poseA, -n, -1) - b.supportPoint(poseB, n, -1)).dot(-n);
        all.push_back({std::min(plus, minus), isEdge});
    };
    for (int i = 0; i < 3; ++i) {
        add(poseA.linear().col(i), false);
        add(poseB.linear().col(i), false);
        for (int j = 0; j < 3; ++j) add(poseA.linear().col(i).cross(poseB.linear().col(j)), true);
    }
    std::sort(all.begin(), all.end());
    face = edge = 1e300;
    for (const auto &[overlap, isEdge] : all) (isEdge ? edge : face) = std::min(isEdge ? edge : face, overlap);
    secondBest = all[1].first;
}

TEST(BoxBox, AgreesWithTheFclPathOnRandomPoses) {
    // Boxes of random half extents in [0.2, 0.8] at random orientations. Both paths must
    // agree on hit or miss. Both take the least overlap over the 15 axes, except that this
    // one lets an edge axis win only 2% + 10 um below the best face (box_box.cpp) and the
    // FCL path tries only the edge pairs of the supporting faces: where the best edge and
    // face axes are more than 3% + 20 um apart (and no two axes tie), the normal and the
    // deepest point must be the same; otherwise the depth may exceed the FCL path's by at
    // most the bias. Most poses are of the first kind: this is checked too.
    RandomContacts r(11);
    int hits = 0, misses = 0, clear = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        auto halves = [&] { return Vector3(0.5 + 0.3 * r.uniform(r.random), 0.5 + 0.3 * r.uniform(r.random), 0.5 + 0.3 * r.uniform(r.random)); };
        const auto a = detail::compileShape(Shape::box(halves()));
        const auto b = detail::compileShape(Shape::box(halves()));
        const RandomContacts::Trial t = r.collideBoth(*a, *b, false);
        const std::vector<Manifold> &f = t.f, &n = t.n;
        ASSERT_EQ(f.size(), t.hit ? 1u : 0u);
        ASSERT_EQ(n.size(), f.size());
        if (!t.hit) {
            ++misses;
            continue;
        }
        ++hits;
        real face = 0, edge = 0, second = 0;
        leastOverlaps(*a, t.poseA, *b, t.poseB, face, edge, second);
        const real best = std::min(face, edge);
        const bool unambiguous = std::abs(edge - face) > 0.03 * face + 2e-5 && second - best > 1e-9;
        if (unambiguous) {
            ++clear;
            EXPECT_LT((n[0].normal - f[0].normal).norm(), 1e-6) << n[0].normal.transpose() << " vs " << f[0].normal.transpose();
            EXPECT_NEAR(deepestDepth(n[0]), deepestDepth(f[0]), 1e-9);
        } else {
            EXPECT_LE(deepestDepth(n[0]), deepestDepth(f[0]) / 0.98 + 1e-5 + 1e-9);
        }
    }
    EXPECT_GT(misses, 150);
    EXPECT_GT(clear, 9 * hits / 10);
}

// ---- boxes and hulls as polytopes ----

// A rock: an icosahedron of radius 0.3 whose corners are pushed in or out by up to 20 %
// (12 corners, 20 triangles, 30 edges), as in the benchmark's mixed piles.
Shape rock(std::mt19937 &random) {
    std::uniform_real_distribution<real> scale(0.8, 1.2);
    const real phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vector3> points;
    for (real s1 : {-1.0, 1.0})
        for (real s2 : {-1.0, 1.0})
            for (const Vector3 &p : {Vector3(0, s1, s2 * phi), Vector3(s1, s2 * phi, 0), Vector3(s2 * phi, 0, s1)})
                points.push_back(p.normalized() * 0.3 * scale(random));
    return Shape::convex(points);
}

TEST(Polytope, EdgesJoinTwoFacesAndLeaveOutCoplanarOnes) {
    // A box: 8 corners, 6 faces, 12 edges. A cube given as a hull may come in triangles;
    // its face diagonals join coplanar faces and are no edges: 12 again. Every edge's
    // corner lies on both its faces' planes, and its arc is along the edge (normal to both).
    for (const Shape &shape : {Shape::box(Vector3(0.3, 0.5, 0.7)), convexCube(0.5)}) {
        const auto compiled = detail::compileShape(shape);
        detail::BoxCorners room;
        const detail::Polytope p = detail::polytopeOf(*compiled, room);
        EXPECT_EQ(p.cornerCount, 8u);
        EXPECT_EQ(p.edgeCount, 12u);
        for (std::size_t k = 0; k < p.edgeCount; ++k) {
            const detail::PolytopeEdge &e = p.edges[k];
            const Vector3 &corner = p.corners[e.corner];
            for (int f : {e.face0, e.face1}) EXPECT_NEAR(p.normals[f].dot(corner), p.offsets[f], 1e-12);
            EXPECT_NEAR(e.arc.norm(), 1, 1e-12);
            EXPECT_NEAR(e.arc.dot(p.normals[e.face0]), 0, 1e-12);
            EXPECT_NEAR(e.arc.dot(p.normals[e.face1]), 0, 1e-12);
        }
        // The box holds a ball of its least half size about its centre; the cube one of 0.5.
        EXPECT_NEAR(p.innerRadius, shape.type == ShapeType::Box ? 0.3 : 0.5, 1e-12);
    }
    // The rock: Euler's V - E + F = 2 over its triangles (no two coplanar).
    std::mt19937 random(3);
    const auto compiled = detail::compileShape(rock(random));
    detail::BoxCorners room;
    const detail::Polytope p = detail::polytopeOf(*compiled, room);
    EXPECT_EQ(p.cornerCount, 12u);
    EXPECT_EQ(p.edgeCount, 30u);
    EXPECT_EQ(p.faceCount, 20u);
}

TEST(Polytope, HullResting1cmIntoABox) {
    // A convex cube of half size 0.4 at (0.1, 0.89, 0): its bottom at 0.49 is 0.01 into the
    // unit box's top, and its bottom square x in [-0.3, 0.5], z in [-0.4, 0.4] lies inside it.
    Expected e;
    e.normal = kDown;
    e.depth = 0.01;
    for (real x : {-0.3, 0.5})
        for (real z : {-0.4, 0.4}) e.points.push_back({Vector3(x, 0.49, z), Vector3(x, 0.5, z)});
    expectContact(convexCube(0.4), pose(Vector3(0.1, 0.89, 0)), kUnitBox, Matrix4::Identity(), e);
}

TEST(Polytope, HullEdgeAcrossHullEdge) { expectEdgeAcrossEdge(convexCube(0.5)); }

TEST(Polytope, PyramidApexIntoAFace) {
    // The pyramid upside down (apex at y = -0.75 in its frame) with its apex 3 cm into the
    // unit box's top: the box's face normal, 0.03 deep, one point under the apex.
    Expected e;
    e.normal = kDown;
    e.depth = 0.03;
    e.points = {{Vector3(0.1, 0.47, 0.2), Vector3(0.1, 0.5, 0.2)}};
    e.minPoints = e.maxPoints = 1;
    expectContact(pyramid(), pose(Vector3(0.1, 1.22, 0.2), rotation(kPi, Vector3::UnitX())), kUnitBox,
                  Matrix4::Identity(), e);
}

// The least overlap between two polytopes over every candidate axis: all face normals and
// the cross product of every edge pair (both ways), by support points.
real leastPolytopeOverlap(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB) {
    const auto overlap = [&](const Vector3 &n) {
        return (a.supportPoint(poseA, n, -1) - b.supportPoint(poseB, -n, -1)).dot(n);
    };
    detail::BoxCorners roomA, roomB;
    const detail::Polytope pa = detail::polytopeOf(a, roomA), pb = detail::polytopeOf(b, roomB);
    real least = 1e300;
    for (std::size_t f = 0; f < pa.faceCount; ++f) least = std::min(least, overlap(poseA.linear() * pa.normals[f]));
    for (std::size_t f = 0; f < pb.faceCount; ++f) least = std::min(least, overlap(-(poseB.linear() * pb.normals[f])));
    for (std::size_t i = 0; i < pa.edgeCount; ++i)
        for (std::size_t j = 0; j < pb.edgeCount; ++j) {
            const Vector3 axis = (poseA.linear() * pa.edges[i].arc).cross(poseB.linear() * pb.edges[j].arc);
            if (axis.norm() < 1e-9) continue;
            least = std::min({least, overlap(axis.normalized()), overlap(-axis.normalized())});
        }
    return least;
}

TEST(Polytope, TakesTheLeastOverlapOfAllAxesOnRandomPoses) {
    // Rocks against rocks and against boxes, overlapping by up to 0.35 m or apart: the
    // axis the test returns overlaps by what it reports, and that is the least over all
    // candidate axes (a face axis may win a tie within 1e-9 m). Apart, no axis overlaps.
    std::mt19937 random(5);
    std::uniform_real_distribution<real> uniform(-1, 1);
    const auto turn = [&] {
        return Quaternion(Eigen::Matrix<real, 4, 1>(uniform(random), uniform(random), uniform(random), uniform(random)).normalized());
    };
    int hits = 0, misses = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        const Vector3 half(0.3 + 0.1 * uniform(random), 0.3 + 0.1 * uniform(random), 0.3 + 0.1 * uniform(random));
        const auto a = detail::compileShape(trial % 2 ? Shape::box(half) : rock(random));
        const auto b = detail::compileShape(rock(random));
        const Matrix4 poseA = pose(Vector3(uniform(random), uniform(random), uniform(random)), turn());
        const Vector3 direction = Vector3(uniform(random), uniform(random), uniform(random)).normalized();
        const Matrix4 poseB = pose(poseA.translation() + (0.5 + 0.25 * uniform(random)) * direction, turn());
        Vector3 normal;
        real overlap = 0;
        detail::BoxCorners roomA, roomB;
        const bool touching = detail::polytopeAxis(detail::polytopeOf(*a, roomA), poseA, detail::polytopeOf(*b, roomB), poseB,
                                                   normal, overlap);
        const real least = leastPolytopeOverlap(*a, poseA, *b, poseB);
        if (!touching) {
            ++misses;
            EXPECT_LT(least, 0);
            continue;
        }
        ++hits;
        EXPECT_GE(least, 0);
        EXPECT_NEAR(normal.norm(), 1, 1e-12);
        EXPECT_NEAR((a->supportPoint(poseA, normal, -1) - b->supportPoint(poseB, -normal, -1)).dot(normal), overlap, 1e-9);
        EXPECT_GE(overlap, least - 1e-9);
        EXPECT_LE(overlap, least + 2e-9);
    }
    EXPECT_GT(hits, 500);
    EXPECT_GT(misses, 100);
}

TEST(Polytope, AgreesWithTheFclPathOnRandomPoses) {
    // FCL is the reference: both paths agree on hit or miss (A placed 0.5-50.5 mm into B
    // or 0.5-20.5 mm apart, as FCL finds them). The FCL path's normal is a candidate of
    // least overlap refined by GJK, so its depth bounds the least overlap from above, up
    // to the refinement's tolerance (1 um).
    RandomContacts r(13);
    std::mt19937 random(17);
    int hits = 0;
    for (int trial = 0; trial < 600; ++trial) {
        SCOPED_TRACE("trial " + std::to_string(trial));
        const auto a = detail::compileShape(trial % 3 == 0 ? Shape::box(Vector3(0.3, 0.2, 0.4)) : rock(random));
        const auto b = detail::compileShape(trial % 3 == 1 ? Shape::box(Vector3(0.25, 0.35, 0.3)) : rock(random));
        const RandomContacts::Trial t = r.collideBoth(*a, *b, false);
        ASSERT_EQ(t.f.size(), t.hit ? 1u : 0u);
        ASSERT_EQ(t.n.size(), t.f.size());
        if (!t.hit) continue;
        ++hits;
        const std::vector<Manifold> &f = t.f, &n = t.n;
        EXPECT_LE(deepestDepth(n[0]), deepestDepth(f[0]) + 1e-6);
        EXPECT_GT(deepestDepth(n[0]), 0);
    }
    EXPECT_GT(hits, 350);
}

TEST(NativePairs, SpheresAndPlanesAgreeWithTheFclPathOnRandomPoses) {
    // The closed-form sphere contacts and the plane's own hit test give the manifolds the
    // FCL path gives (its least-overlap normal is exact for these): same points.
    const std::vector<std::pair<Shape, Shape>> pairs = {
        {Shape::sphere(0.4), Shape::sphere(0.6)},
        {Shape::sphere(0.4), Shape::box(Vector3(0.5, 0.3, 0.7))},
        {Shape::box(Vector3(0.5, 0.3, 0.7)), Shape::sphere(0.4)},
        {Shape::box(Vector3(0.5, 0.3, 0.7)), Shape::plane(Vector3(0.1, 1, 0), 0.2)},
        {Shape::cylinder(0.3, 0.8), Shape::plane(Vector3::UnitY(), 0)},
        {Shape::capsule(0.3, 0.8), Shape::plane(Vector3::UnitY(), 0)},
        {pyramid(), Shape::plane(Vector3::UnitY(), 0)},
    };
    RandomContacts r(12);
    for (const auto &[shapeA, shapeB] : pairs) {
        const auto a = detail::compileShape(shapeA);
        const auto b = detail::compileShape(shapeB);
        int hits = 0;
        for (int trial = 0; trial < 200; ++trial) {
            SCOPED_TRACE(std::string(shapeTypeName(shapeA.type)) + " against " + shapeTypeName(shapeB.type) +
                         ", trial " + std::to_string(trial));
            const RandomContacts::Trial t = r.collideBoth(*a, *b, shapeB.type == ShapeType::Plane);
            const std::vector<Manifold> &f = t.f, &n = t.n;
            ASSERT_EQ(f.size(), t.hit ? 1u : 0u);
            ASSERT_EQ(n.size(), f.size());
            if (!t.hit) continue;
            ++hits;
            EXPECT_LT((n[0].normal - f[0].normal).norm(), 1e-9);
            ASSERT_EQ(n[0].count, f[0].count);
            for (int i = 0; i < n[0].count; ++i) {
                EXPECT_LT((n[0].points[i].pointA - f[0].points[i].pointA).norm(), 1e-9);
                EXPECT_LT((n[0].points[i].pointB - f[0].points[i].pointB).norm(), 1e-9);
                EXPECT_NEAR(n[0].points[i].depth, f[0].points[i].depth, 1e-9);
            }
        }
        EXPECT_GT(hits, 100);
    }
}

}  // namespace
}  // namespace cyclone::test
