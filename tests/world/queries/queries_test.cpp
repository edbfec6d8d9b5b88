// Ray casts and overlap queries against hand-worked geometry, for every shape type.
#include <cmath>
#include <limits>

#include "world_fixture.h"

namespace cyclone::test {
namespace {


Quaternion about(const Vector3 &axis, double degrees) {
    return Quaternion(Eigen::AngleAxis<real>(degrees * kPi / 180, axis.normalized()));
}

BodyId add(World &world, const Shape &shape, const Vector3 &position, const Quaternion &q = Quaternion::Identity(),
           bool isStatic = true) {
    BodySettings s;
    s.shape = shape;
    s.position = position;
    s.orientation = q;
    s.motion = isStatic ? Motion::Static : Motion::Dynamic;
    return world.addBody(s);
}

void expectHit(const std::optional<RayHit> &hit, BodyId body, double distance, const Vector3 &point,
               const Vector3 &normal, double tolerance = 1e-12) {
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->body, body);
    EXPECT_NEAR(hit->distance, distance, tolerance);
    EXPECT_LT((hit->point - point).norm(), tolerance) << hit->point.transpose();
    EXPECT_LT((hit->normal - normal).norm(), tolerance) << hit->normal.transpose();
}

// --- Rays, one shape type at a time ---------------------------------------------------

TEST(RayCast, Box) {
    World world;
    const BodyId box = add(world, Shape::box(Vector3(1, 0.5, 2)), Vector3(3, 0, 0));
    // Face x = 3 - 1 = 2.
    expectHit(world.rayCast(Vector3::Zero(), Vector3::UnitX()), box, 2, Vector3(2, 0, 0), -Vector3::UnitX());
    // From above at (3.5, 4, 1.5): face y = 0.5, 3.5 m down.
    expectHit(world.rayCast(Vector3(3.5, 4, 1.5), -Vector3::UnitY()), box, 3.5, Vector3(3.5, 0.5, 1.5),
              Vector3::UnitY());
    // Just beside the box (z = 2.1 > 2): no hit.
    EXPECT_FALSE(world.rayCast(Vector3(0, 0, 2.1), Vector3::UnitX()));
}

TEST(RayCast, RotatedBox) {
    World world;
    // Turned 90 degrees about z, the box's x half extent 1 lies along y and y's 0.5
    // along x: the face facing the origin is at x = 3 - 0.5.
    const BodyId box = add(world, Shape::box(Vector3(1, 0.5, 2)), Vector3(3, 0, 0), about(Vector3::UnitZ(), 90));
    expectHit(world.rayCast(Vector3::Zero(), Vector3::UnitX()), box, 2.5, Vector3(2.5, 0, 0), -Vector3::UnitX());
    // Turned 45 degrees about z, a unit cube's local x axis is (1, 1, 0) / sqrt(2): a ray
    // along it from (0, -3, 0) through the centre (3, 0, 0), 3 sqrt(2) away, meets the
    // face -x 0.5 before the centre.
    World turned;
    const BodyId cube = add(turned, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(3, 0, 0), about(Vector3::UnitZ(), 45));
    const double s = std::sqrt(0.5);
    expectHit(turned.rayCast(Vector3(0, -3, 0), Vector3(1, 1, 0)), cube, 3 * std::sqrt(2.0) - 0.5,
              Vector3(3 - 0.5 * s, -0.5 * s, 0), Vector3(-s, -s, 0), 1e-12);
}

// Sphere of radius 0.5 at (0, 0, 5), ray along +z offset 0.3: it meets the sphere
// where z = 5 - sqrt(0.25 - 0.09) = 4.6, normal (0.3, 0, -0.4) / 0.5.
TEST(RayCast, Sphere) {
    World world;
    const BodyId ball = add(world, Shape::sphere(0.5), Vector3(0, 0, 5));
    expectHit(world.rayCast(Vector3(0.3, 0, 0), Vector3::UnitZ()), ball, 4.6, Vector3(0.3, 0, 4.6),
              Vector3(0.6, 0, -0.8));
    EXPECT_FALSE(world.rayCast(Vector3(0.6, 0, 0), Vector3::UnitZ()));
    EXPECT_FALSE(world.rayCast(Vector3(0, 0, 0), -Vector3::UnitZ()));  // behind the ray
}

// Capsule radius 0.5, cylindrical part 2 m along local z: side at 0.5 from the axis,
// ends reaching z = +-1.5.
TEST(RayCast, Capsule) {
    World world;
    const BodyId capsule = add(world, Shape::capsule(0.5, 2), Vector3::Zero());
    expectHit(world.rayCast(Vector3(0, 5, 0.7), -Vector3::UnitY()), capsule, 4.5, Vector3(0, 0.5, 0.7),
              Vector3::UnitY());
    expectHit(world.rayCast(Vector3(0, 0, 10), -Vector3::UnitZ()), capsule, 8.5, Vector3(0, 0, 1.5),
              Vector3::UnitZ());
    // Off the axis by 0.3 the end sphere (centre z = 1) is met at z = 1 + 0.4.
    expectHit(world.rayCast(Vector3(0.3, 0, 10), -Vector3::UnitZ()), capsule, 8.6, Vector3(0.3, 0, 1.4),
              Vector3(0.6, 0, 0.8));
    // Turned 90 degrees about y, the axis lies along x.
    World turned;
    const BodyId lying = add(turned, Shape::capsule(0.5, 2), Vector3::Zero(), about(Vector3::UnitY(), 90));
    expectHit(turned.rayCast(Vector3(10, 0, 0), -Vector3::UnitX()), lying, 8.5, Vector3(1.5, 0, 0), Vector3::UnitX());
}

// Cylinder radius 0.5, length 2 along local z: caps at z = +-1.
TEST(RayCast, Cylinder) {
    World world;
    const BodyId cylinder = add(world, Shape::cylinder(0.5, 2), Vector3::Zero());
    expectHit(world.rayCast(Vector3(0.3, 0, 10), -Vector3::UnitZ()), cylinder, 9, Vector3(0.3, 0, 1),
              Vector3::UnitZ());
    expectHit(world.rayCast(Vector3(0, 0.2, -4), Vector3::UnitZ()), cylinder, 3, Vector3(0, 0.2, -1),
              -Vector3::UnitZ());
    expectHit(world.rayCast(Vector3(0, 5, 0.9), -Vector3::UnitY()), cylinder, 4.5, Vector3(0, 0.5, 0.9),
              Vector3::UnitY());
    EXPECT_FALSE(world.rayCast(Vector3(0.6, 0, 10), -Vector3::UnitZ()));  // beside the cap
    EXPECT_FALSE(world.rayCast(Vector3(0, 5, 1.1), -Vector3::UnitY()));   // above the side
}

// The octahedron |x| + |y| + |z| <= 1: from (0.2, 0.1, 5) down -z the ray meets the
// face x + y + z = 1 at z = 0.7.
TEST(RayCast, Convex) {
    World world;
    const BodyId hull = add(world,
                            Shape::convex({Vector3(1, 0, 0), Vector3(-1, 0, 0), Vector3(0, 1, 0), Vector3(0, -1, 0),
                                           Vector3(0, 0, 1), Vector3(0, 0, -1)}),
                            Vector3(0, 0, 0));
    const Vector3 n = Vector3(1, 1, 1).normalized();
    expectHit(world.rayCast(Vector3(0.2, 0.1, 5), -Vector3::UnitZ()), hull, 4.3, Vector3(0.2, 0.1, 0.7), n);
    // From the other side, the face -x + y - z = 1 at z = -(1 - 0.4) for (-0.2, 0.2).
    expectHit(world.rayCast(Vector3(-0.2, 0.2, -5), Vector3::UnitZ()), hull, 4.4, Vector3(-0.2, 0.2, -0.6),
              Vector3(-1, 1, -1).normalized());
    EXPECT_FALSE(world.rayCast(Vector3(0.6, 0.6, 5), -Vector3::UnitZ()));  // |x| + |y| > 1
}

TEST(RayCast, Plane) {
    World world;
    const BodyId ground = add(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
    expectHit(world.rayCast(Vector3(1, 4, 2), -Vector3::UnitY()), ground, 4, Vector3(1, 0, 2), Vector3::UnitY());
    // Along (3, -4, 0) / 5 from 4 m up: 5 m to the ground, 3 m further along x.
    expectHit(world.rayCast(Vector3(1, 4, 2), Vector3(3, -4, 0)), ground, 5, Vector3(4, 0, 2), Vector3::UnitY());
    EXPECT_FALSE(world.rayCast(Vector3(1, 4, 2), Vector3::UnitX()));      // parallel
    EXPECT_FALSE(world.rayCast(Vector3(1, -1, 2), -Vector3::UnitY()));    // starts in the solid
    // The solid is normal.x <= offset as given (the scene format's contract): a normal
    // of length 2 with offset 1 is 2y <= 1, the ground y <= 0.5.
    World raised;
    const BodyId shelf = add(raised, Shape::plane(Vector3(0, 2, 0), 1), Vector3::Zero());
    expectHit(raised.rayCast(Vector3(0, 5, 0), -Vector3::UnitY()), shelf, 4.5, Vector3(0, 0.5, 0), Vector3::UnitY());
}

// Two triangles make the square [-1, 1]^2 at y = 0, normals up; a mesh is hit from
// either side, with the normal facing the ray.
TEST(RayCast, MeshFromBothSides) {
    World world;
    const BodyId floor = add(world,
                             Shape::mesh({Vector3(-1, 0, -1), Vector3(1, 0, -1), Vector3(1, 0, 1), Vector3(-1, 0, 1)},
                                         {{0, 2, 1}, {0, 3, 2}}),
                             Vector3::Zero());
    expectHit(world.rayCast(Vector3(0.25, 3, 0.5), -Vector3::UnitY()), floor, 3, Vector3(0.25, 0, 0.5),
              Vector3::UnitY());
    expectHit(world.rayCast(Vector3(0.25, -2, -0.5), Vector3::UnitY()), floor, 2, Vector3(0.25, 0, -0.5),
              -Vector3::UnitY());
    // On the diagonal shared by the two triangles.
    expectHit(world.rayCast(Vector3(0.5, 1, 0.5), -Vector3::UnitY()), floor, 1, Vector3(0.5, 0, 0.5),
              Vector3::UnitY());
    EXPECT_FALSE(world.rayCast(Vector3(1.5, 3, 0), -Vector3::UnitY()));
}

// A 40 x 40 grid of 3200 triangles on the slope y = 0.1 x, placed at (0, 1, 0): rays
// straight down from y = 10 meet it at y = 1 + 0.1 x, with normal (-0.1, 1, 0) / |.|.
// Exercises the walk through the mesh's bounding-volume tree.
TEST(RayCast, LargeMeshFollowsItsTree) {
    std::vector<Vector3> vertices;
    std::vector<std::array<int, 3>> triangles;
    const int n = 40;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double x = -20 + i, z = -20 + j;
            vertices.emplace_back(x, 0.1 * x, z);
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int v = i * (n + 1) + j;
            triangles.push_back({v, v + 1, v + n + 2});
            triangles.push_back({v, v + n + 2, v + n + 1});
        }
    World world;
    const BodyId slope = add(world, Shape::mesh(vertices, triangles), Vector3(0, 1, 0));
    const Vector3 normal = Vector3(-0.1, 1, 0).normalized();
    for (double x = -19.75; x < 20; x += 1.5)
        for (double z : {-19.9, -7.3, 0.0, 0.5, 13.1}) {
            const double y = 1 + 0.1 * x;
            expectHit(world.rayCast(Vector3(x, 10, z), -Vector3::UnitY()), slope, 10 - y, Vector3(x, y, z), normal,
                      1e-9);
        }
}

// --- What a ray considers ---------------------------------------------------------------

TEST(RayCast, ClosestOfManyAndFilters) {
    World world;
    const BodyId first =
        add(world, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(3, 0, 0), Quaternion::Identity(), false);
    const BodyId second = add(world, Shape::sphere(0.5), Vector3(6, 0, 0), Quaternion::Identity(), false);
    const BodyId wall = add(world, Shape::box(Vector3(0.5, 5, 5)), Vector3(9, 0, 0));
    const Vector3 o = Vector3::Zero();
    const Vector3 x = Vector3::UnitX();
    EXPECT_EQ(world.rayCast(o, x)->body, first);
    QueryFilter filter;
    filter.ignore = first;
    expectHit(world.rayCast(o, x, kInf, filter), second, 5.5, Vector3(5.5, 0, 0), -x);
    filter.accept = [&](BodyId id) { return id != second; };
    expectHit(world.rayCast(o, x, kInf, filter), wall, 8.5, Vector3(8.5, 0, 0), -x);
    QueryFilter dynamicOnly;
    dynamicOnly.staticBodies = false;
    EXPECT_EQ(world.rayCast(Vector3(7, 0, 0), x, kInf, dynamicOnly), std::nullopt);
    QueryFilter staticOnly;
    staticOnly.dynamicBodies = false;
    EXPECT_EQ(world.rayCast(o, x, kInf, staticOnly)->body, wall);
}

// A box face at x = 2.5, a sphere's near side at 5.5, a wall's face at 8.5 and a ground
// plane below the ray: every body the ray along +x meets, nearest first, each where the
// ray first meets it; the first hit is rayCast's.
TEST(RayCastAll, EveryBodyAlongTheRayNearestFirst) {
    World world;
    const BodyId box = add(world, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(3, 0, 0), Quaternion::Identity(), false);
    const BodyId ball = add(world, Shape::sphere(0.5), Vector3(6, 0, 0), Quaternion::Identity(), false);
    const BodyId wall = add(world, Shape::box(Vector3(0.5, 5, 5)), Vector3(9, 0, 0));
    add(world, Shape::plane(Vector3::UnitY(), -1), Vector3::Zero());
    const Vector3 o = Vector3::Zero();
    const Vector3 x = Vector3::UnitX();
    std::vector<RayHit> hits;
    ASSERT_EQ(world.rayCastAll(o, x, hits), 3u);
    const BodyId expected[3] = {box, ball, wall};
    const real distances[3] = {2.5, 5.5, 8.5};
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(hits[k].body, expected[k]);
        EXPECT_NEAR(hits[k].distance, distances[k], 1e-12);
        EXPECT_LT((hits[k].point - Vector3(distances[k], 0, 0)).norm(), 1e-12);
        EXPECT_LT((hits[k].normal + x).norm(), 1e-12);
    }
    EXPECT_EQ(world.rayCast(o, x)->body, hits[0].body);
    // Within 6 m: the box and the ball; the ball filtered out: the box and the wall.
    EXPECT_EQ(world.rayCastAll(o, x, hits, 6), 2u);
    EXPECT_EQ(hits[1].body, ball);
    QueryFilter filter;
    filter.ignore = ball;
    ASSERT_EQ(world.rayCastAll(o, x, hits, kInf, filter), 2u);
    EXPECT_EQ(hits[1].body, wall);
    // Straight down from above the box: its top at 1.5 m below, then the plane at 3 m.
    ASSERT_EQ(world.rayCastAll(Vector3(3, 2, 0), -Vector3::UnitY(), hits), 2u);
    EXPECT_NEAR(hits[0].distance, 1.5, 1e-12);
    EXPECT_NEAR(hits[1].distance, 3, 1e-12);
    // Nothing along -x: the list is emptied.
    EXPECT_EQ(world.rayCastAll(o, -x, hits), 0u);
    EXPECT_TRUE(hits.empty());
}

TEST(RayCastAll, RefusesBadInput) {
    World world;
    std::vector<RayHit> hits;
    EXPECT_THROW(world.rayCastAll(Vector3::Zero(), Vector3::Zero(), hits), InvalidArgument);
    EXPECT_THROW(world.rayCastAll(Vector3(kInf, 0, 0), Vector3::UnitX(), hits), InvalidArgument);
    EXPECT_THROW(world.rayCastAll(Vector3::Zero(), Vector3::UnitX(), hits, 0), InvalidArgument);
    try {
        world.rayCastAll(Vector3::Zero(), Vector3::UnitX(), hits, -1);
        FAIL();
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::rayCastAll");
        EXPECT_EQ(e.field(), "maxDistance");
    }
}

TEST(RayCast, MaxDistanceIsInclusive) {
    World world;
    const BodyId box = add(world, Shape::box(Vector3(1, 1, 1)), Vector3(3, 0, 0));
    EXPECT_FALSE(world.rayCast(Vector3::Zero(), Vector3::UnitX(), 1.99));
    expectHit(world.rayCast(Vector3::Zero(), Vector3::UnitX(), 2), box, 2, Vector3(2, 0, 0), -Vector3::UnitX());
}

// A ray that starts inside a solid leaves it: the next body is hit instead. A ray that
// starts on a face and goes in hits it at distance 0.
TEST(RayCast, StartingInsideIgnoresThatBody) {
    World world;
    add(world, Shape::box(Vector3(1, 1, 1)), Vector3::Zero());
    const BodyId next = add(world, Shape::sphere(1), Vector3(5, 0, 0));
    expectHit(world.rayCast(Vector3::Zero(), Vector3::UnitX()), next, 4, Vector3(4, 0, 0), -Vector3::UnitX());
    const BodyId face = add(world, Shape::box(Vector3(1, 1, 1)), Vector3(0, 10, 0));
    expectHit(world.rayCast(Vector3(0, 11, 0), -Vector3::UnitY()), face, 0, Vector3(0, 11, 0), Vector3::UnitY());
}

TEST(RayCast, SleepingBodiesAreHit) {
    World world;
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = Vector3(0, 0, 4);
    s.awake = false;
    const BodyId sleeper = world.addBody(s);
    expectHit(world.rayCast(Vector3::Zero(), Vector3::UnitZ()), sleeper, 3.5, Vector3(0, 0, 3.5), -Vector3::UnitZ());
    EXPECT_FALSE(world.body(sleeper).getAwake());  // a query wakes nothing
}

// 2500 boxes in a 50 x 50 grid 3 m apart, static, awake and asleep (in the three
// trees): a ray down onto each meets that box's top.
TEST(RayCast, EveryBodyOfALargeWorld) {
    World world;
    std::vector<BodyId> ids;
    for (int i = 0; i < 50; ++i)
        for (int j = 0; j < 50; ++j) {
            BodySettings s;
            s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            s.position = Vector3(3 * i, 0, 3 * j);
            s.motion = j % 3 == 0 ? Motion::Static : Motion::Dynamic;
            s.awake = j % 3 == 1;
            ids.push_back(world.addBody(s));
        }
    world.step(kDt);  // the awake ones fall a little
    for (int i = 0; i < 50; ++i)
        for (int j = 0; j < 50; ++j) {
            const Vector3 top = world.body(ids[i * 50 + j]).getPosition() + Vector3(0.2, 0.5, -0.1);
            expectHit(world.rayCast(top + Vector3(0, 9.5, 0), -Vector3::UnitY()), ids[i * 50 + j], 9.5, top,
                      Vector3::UnitY(), 1e-9);
        }
}

TEST(RayCast, RefusesBadInput) {
    World world;
    add(world, Shape::box(Vector3(1, 1, 1)), Vector3(3, 0, 0));
    auto expectRefused = [&](const Vector3 &o, const Vector3 &d, double max, const std::string &field) {
        try {
            world.rayCast(o, d, max);
            FAIL() << "accepted a bad " << field;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "World::rayCast");
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    expectRefused(Vector3(kNaN, 0, 0), Vector3::UnitX(), 1, "origin");
    expectRefused(Vector3(2e30, 0, 0), Vector3::UnitX(), 1, "origin");
    expectRefused(Vector3::Zero(), Vector3::Zero(), 1, "direction");
    expectRefused(Vector3::Zero(), Vector3(0, kInf, 0), 1, "direction");
    expectRefused(Vector3::Zero(), Vector3::UnitX(), 0, "maxDistance");
    expectRefused(Vector3::Zero(), Vector3::UnitX(), -1, "maxDistance");
    expectRefused(Vector3::Zero(), Vector3::UnitX(), kNaN, "maxDistance");
}

// --- Overlap ----------------------------------------------------------------------------

// Three unit boxes at x = 0, 2, 4, y = 1 (faces at x = +-0.5 from their centres), over
// the ground plane y = 0.
struct Row {
    World world;
    BodyId ground, box0, box1, box2;
    Row() {
        ground = add(world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero());
        box0 = add(world, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(0, 1, 0), Quaternion::Identity(), false);
        box1 = add(world, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(2, 1, 0), Quaternion::Identity(), false);
        box2 = add(world, Shape::box(Vector3(0.5, 0.5, 0.5)), Vector3(4, 1, 0), Quaternion::Identity(), false);
    }
    std::vector<BodyId> overlap(const Shape &shape, const Vector3 &p, const Quaternion &q = Quaternion::Identity(),
                                const QueryFilter &filter = QueryFilter()) {
        std::vector<BodyId> out{BodyId{99, 99}};  // cleared by the query
        const std::size_t n = world.overlap(shape, p, q, out, filter);
        EXPECT_EQ(n, out.size());
        return out;
    }
};

TEST(Overlap, SphereBetweenTwoBoxes) {
    Row r;
    // Centre (1, 1, 0): 0.5 m from the faces of box0 and box1, 2.5 m from box2's, 1 m
    // above the ground.
    EXPECT_EQ(r.overlap(Shape::sphere(0.6), Vector3(1, 1, 0)), (std::vector<BodyId>{r.box0, r.box1}));
    EXPECT_TRUE(r.overlap(Shape::sphere(0.4), Vector3(1, 1, 0)).empty());
    EXPECT_EQ(r.overlap(Shape::sphere(1.1), Vector3(1, 1, 0)), (std::vector<BodyId>{r.ground, r.box0, r.box1}));
}

// A thin bar (half 2 x 0.05 x 0.05) at (1, 1, 0) spans x in [-1, 3]: boxes 0 and 1.
// Turned 90 degrees about y it spans z instead and fits in the gap x in (0.5, 1.5).
TEST(Overlap, OrientedBar) {
    Row r;
    const Shape bar = Shape::box(Vector3(2, 0.05, 0.05));
    EXPECT_EQ(r.overlap(bar, Vector3(1, 1, 0)), (std::vector<BodyId>{r.box0, r.box1}));
    EXPECT_TRUE(r.overlap(bar, Vector3(1, 1, 0), about(Vector3::UnitY(), 90)).empty());
    // (0,0,0,0) means identity, as for bodies.
    EXPECT_EQ(r.overlap(bar, Vector3(1, 1, 0), Quaternion(0, 0, 0, 0)), (std::vector<BodyId>{r.box0, r.box1}));
}

// A post (half 0.1 x 2 x 0.1) at (4, 0, 0) reaches y in [-2, 2]: box2 and the ground.
TEST(Overlap, FiltersAndShapes) {
    Row r;
    const Shape post = Shape::box(Vector3(0.1, 2, 0.1));
    EXPECT_EQ(r.overlap(post, Vector3(4, 0, 0)), (std::vector<BodyId>{r.ground, r.box2}));
    QueryFilter dynamicOnly;
    dynamicOnly.staticBodies = false;
    EXPECT_EQ(r.overlap(post, Vector3(4, 0, 0), Quaternion::Identity(), dynamicOnly), std::vector<BodyId>{r.box2});
    QueryFilter ignore;
    ignore.ignore = r.ground;
    EXPECT_EQ(r.overlap(post, Vector3(4, 0, 0), Quaternion::Identity(), ignore), std::vector<BodyId>{r.box2});
    // A capsule lying along x (turned about y) from x = 1 - 1.1 to 1 + 1.1 at y = 1.
    EXPECT_EQ(r.overlap(Shape::capsule(0.1, 2), Vector3(1, 1, 0), about(Vector3::UnitY(), 90)),
              (std::vector<BodyId>{r.box0, r.box1}));
    // A cylinder standing on end (turned about x) under box1, whose bottom is at y = 0.5:
    // 0.2 long it spans y in [0.2, 0.4] and touches nothing; 0.5 long, y in [0.05, 0.55].
    EXPECT_EQ(r.overlap(Shape::cylinder(0.3, 0.2), Vector3(2, 0.3, 0), about(Vector3::UnitX(), 90)).size(), 0u);
    EXPECT_EQ(r.overlap(Shape::cylinder(0.3, 0.5), Vector3(2, 0.3, 0), about(Vector3::UnitX(), 90)),
              std::vector<BodyId>{r.box1});
}

TEST(Overlap, RefusesBadInput) {
    Row r;
    std::vector<BodyId> out{r.box0};
    auto expectRefused = [&](const Shape &shape, const Vector3 &p, const Quaternion &q, const std::string &field) {
        try {
            r.world.overlap(shape, p, q, out);
            FAIL() << "accepted a bad " << field;
        } catch (const InvalidArgument &e) {
            EXPECT_EQ(e.function(), "World::overlap");
            EXPECT_EQ(e.field(), field) << e.what();
        }
        EXPECT_EQ(out, std::vector<BodyId>{r.box0});  // untouched
    };
    expectRefused(Shape::sphere(-1), Vector3::Zero(), Quaternion::Identity(), "shape.radius");
    expectRefused(Shape::plane(Vector3::UnitY(), 0), Vector3::Zero(), Quaternion::Identity(), "shape.type");
    expectRefused(Shape::sphere(1), Vector3(0, kNaN, 0), Quaternion::Identity(), "position");
    expectRefused(Shape::sphere(1), Vector3::Zero(), Quaternion(kNaN, 0, 0, 0), "orientation");
}

}  // namespace
}  // namespace cyclone::test
