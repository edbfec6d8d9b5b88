// Triangle meshes in a World: both sides collide unless the mesh says otherwise, inner
// edges make no bumps, and a body that can reach a mesh within a step gets its contact
// in that step (speculative), while one passing by is not slowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "floor_crossing.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A contact rests a body on a surface up to the solver's slop (0.2 mm, settings.h) and
// the little gravity adds within a sub-step; 1 mm bounds both.
constexpr real kRestTolerance = 0.001;

// A 20 m x 20 m floor at y = 0 of 1 m squares, each split along one diagonal or the
// other in a checkerboard, so that a body crossing it meets edges at 0, 45 and 90
// degrees. Wound so that each triangle faces +y (`up`) or -y.
Shape gridFloor(bool up, MeshSides sides = MeshSides::Both) {
    constexpr int kCells = 20;
    std::vector<Vector3> vertices;
    for (int i = 0; i <= kCells; ++i)
        for (int j = 0; j <= kCells; ++j) vertices.emplace_back(i - kCells / 2, 0, j - kCells / 2);
    std::vector<std::array<int, 3>> triangles;
    const auto add = [&](int p, int q, int r) {
        // (p, q, r) with x along i and z along j: (q - p) x (r - p) faces -y when q is
        // along +x and r along +z, so the up-facing order swaps q and r.
        if (up) triangles.push_back({p, r, q});
        else triangles.push_back({p, q, r});
    };
    for (int i = 0; i < kCells; ++i) {
        for (int j = 0; j < kCells; ++j) {
            const int a = i * (kCells + 1) + j;  // (i, j)
            const int b = a + kCells + 1;        // (i + 1, j)
            const int c = a + 1;                 // (i, j + 1)
            const int d = b + 1;                 // (i + 1, j + 1)
            if ((i + j) % 2 == 0) {
                add(a, b, d);
                add(a, d, c);
            } else {
                add(a, b, c);
                add(b, d, c);
            }
        }
    }
    return Shape::mesh(vertices, triangles, sides);
}

BodyId addStaticBody(WorldFixture &f, const Shape &shape, real friction = 0.6) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = shape;
    s.material.friction = friction;
    return f.world.addBody(s);
}

BodyId addBody(WorldFixture &f, const Shape &shape, const Vector3 &position, const Vector3 &velocity = Vector3::Zero(),
               const Vector3 &rotation = Vector3::Zero(), real friction = 0.6) {
    BodySettings s;
    s.shape = shape;
    s.position = position;
    s.velocity = velocity;
    s.rotation = rotation;
    s.mass = 1;
    s.material.friction = friction;
    return f.world.addBody(s);
}

// The shapes the issue names, each with the height its centre rests at on a floor at
// y = 0: a box of half height 0.5, a sphere of radius 0.25, a capsule lying along z (its
// axis is local z, horizontal unturned) resting on its side at its radius 0.2.
struct Rested {
    const char *name;
    Shape shape;
    real restHeight;
};
std::vector<Rested> restingShapes() {
    return {{"box", Shape::box(Vector3(0.5, 0.5, 0.5)), 0.5},
            {"sphere", Shape::sphere(0.25), 0.25},
            {"capsule", Shape::capsule(0.2, 1.0), 0.2}};
}

TEST(MeshContact, DownWoundFloorHoldsABoxSphereAndCapsule) {
    // Both sides collide by default: dropped from 0.5 m above its rest height onto a floor
    // whose triangles all face down, each comes to rest on top at its rest height.
    for (const Rested &r : restingShapes()) {
        SCOPED_TRACE(r.name);
        WorldFixture f(noSleep());
        addStaticBody(f, gridFloor(false));
        const BodyId id = addBody(f, r.shape, Vector3(0.3, r.restHeight + 0.5, 0.2));
        f.simulate(2.0);
        EXPECT_NEAR(f.position(id).y(), r.restHeight, kRestTolerance);
    }
}

TEST(MeshContact, OneSidedMeshPushesOutToItsOpenSideOnly) {
    // MeshSides::Front on an up-facing floor: the solid lies below, so a ball dropped on it
    // rests on top; MeshSides::Back on the same floor puts the solid above, so the ball
    // falls through (pushed out downwards, never up through a triangle); so does Front on
    // a down-facing floor.
    struct Case {
        bool up;
        MeshSides sides;
        bool holds;
    };
    for (const Case &c : {Case{true, MeshSides::Front, true}, Case{true, MeshSides::Back, false},
                          Case{false, MeshSides::Front, false}, Case{false, MeshSides::Back, true}}) {
        SCOPED_TRACE(std::string(c.up ? "up" : "down") + (c.sides == MeshSides::Front ? " front" : " back"));
        WorldFixture f(noSleep());
        addStaticBody(f, gridFloor(c.up, c.sides));
        const BodyId ball = addBody(f, Shape::sphere(0.25), Vector3(0.3, 0.75, 0.2));
        f.simulate(2.0);
        if (c.holds) EXPECT_NEAR(f.position(ball).y(), 0.25, kRestTolerance);
        else EXPECT_LT(f.position(ball).y(), -1.0);
    }
}

TEST(MeshContact, TwoSidedMeshStopsABodyFromBelowToo) {
    // Without gravity a ball rising at 3 m/s from below meets the floor's underside and
    // stays below it (restitution 0), its centre no higher than its radius under it;
    // one-sided with the solid below (Front on an up-facing floor), it is pushed out
    // upwards instead and ends above.
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    for (MeshSides sides : {MeshSides::Both, MeshSides::Front}) {
        WorldFixture f(settings);
        addStaticBody(f, gridFloor(true, sides));
        const BodyId ball = addBody(f, Shape::sphere(0.25), Vector3(0.3, -1, 0.2), Vector3(0, 3, 0));
        f.simulate(1.0);
        if (sides == MeshSides::Both) EXPECT_LE(f.position(ball).y(), -0.25 + kRestTolerance);
        else EXPECT_GT(f.position(ball).y(), 0.25 - kRestTolerance);
    }
}

using Track = FloorTrack;  // floor_crossing.h

const Shape kPlaneFloor = Shape::plane(Vector3::UnitY(), 0);

TEST(MeshContact, SphereRollsAcrossAMeshFloorWithoutBumps) {
    // A ball rolling at 1.08 m/s across the floor diagonally crosses a dozen inner edges
    // and vertices in 6 s. On a flat floor its centre stays at its radius and it never
    // moves up or down: the bounds are 1 mm and 0.01 m/s (the speed from the
    // first quarter second on, the start being the same on a plane: see below).
    const Track track = crossFloor(gridFloor(true), Shape::sphere(0.25), Quaternion::Identity(), 0.25,
                                   Vector3(1.0, 0, 0.4), true, 0.6, 6.0);
    EXPECT_LE(heightError(track, 0.25), 0.001);
    EXPECT_LE(verticalSpeed(track, 15), 0.01);
    // It did cross the floor: 1.08 m/s for 6 s, less what rolling resistance takes.
    EXPECT_GT(track.travelled, 5);
}

TEST(MeshContact, FastBallRollsOnAMeshFloorAsOnAPlane) {
    // At 4.27 m/s, over 30 inner edges, a flat mesh must add nothing to what a plane
    // does: the same heights and vertical speeds, step by step, as on the plane it lies
    // in, within 0.1 mm and 1 mm/s. On both the ball keeps its height as at 1.08 m/s
    // (solver/round_depths.h; the bounds are derived in round_depths_test.cpp: the slop
    // plus a sub-step's fall g h^2, and the 0.01 m/s), from the first step.
    const Vector3 v(4, 0, 1.5);
    const Track mesh = crossFloor(gridFloor(true), Shape::sphere(0.25), Quaternion::Identity(), 0.25, v, true, 0.6, 3.0);
    const Track plane = crossFloor(kPlaneFloor, Shape::sphere(0.25), Quaternion::Identity(), 0.25, v, true, 0.6, 3.0);
    const real heightBound = 0.0002 + kG * (kDt / 4) * (kDt / 4);
    EXPECT_LE(heightError(mesh, 0.25), heightBound);
    EXPECT_LE(verticalSpeed(mesh), 0.01);
    EXPECT_LE(heightError(plane, 0.25), heightBound);
    EXPECT_LE(verticalSpeed(plane), 0.01);
    ASSERT_EQ(mesh.height.size(), plane.height.size());
    for (std::size_t i = 0; i < mesh.height.size(); ++i) {
        SCOPED_TRACE("step " + std::to_string(i));
        EXPECT_NEAR(mesh.height[i], plane.height[i], 1e-4);
        EXPECT_NEAR(mesh.verticalSpeed[i], plane.verticalSpeed[i], 1e-3);
    }
}

TEST(MeshContact, CapsuleRollsAcrossAMeshFloorOnItsSide) {
    // A capsule lying across its path (its axis, local z, along up x v) rolls at 4.27 m/s
    // over some 30 inner edges and beside as many vertices: height and vertical speed as
    // for the ball, from the first step. Before a face contact beside its triangle gave no
    // point (mesh_contacts.cpp, clipContact) it jumped 8 cm at 1.2 m/s.
    const Vector3 v(4, 0, 1.5);
    const Quaternion acrossPath = Quaternion::FromTwoVectors(Vector3::UnitZ(), Vector3::UnitY().cross(v).normalized());
    const Track track = crossFloor(gridFloor(true), Shape::capsule(0.25, 1.0), acrossPath, 0.25, v, true, 0.6, 3.0);
    EXPECT_LE(heightError(track, 0.25), 0.0002 + kG * (kDt / 4) * (kDt / 4));
    EXPECT_LE(verticalSpeed(track), 0.01);
    EXPECT_GT(track.travelled, 12) << "it rolled on: 4.27 m/s for 3 s, less rolling resistance";
}

TEST(MeshContact, BoxAndCapsuleSlideAcrossAMeshFloorWithoutBumps) {
    // Sliding at 4 m/s with friction 0.1 they stop after v^2 / (2 mu g) = 8.1 m, crossing
    // some 20 inner edges; height and vertical speed as for the ball. The capsule lies
    // along its path (turned about y so that its axis, local z, is along v), so it slides
    // rather than rolls.
    const Vector3 v(3.6, 0, 1.7);
    const Quaternion alongPath(Eigen::AngleAxis<real>(std::atan2(v.x(), v.z()), Vector3::UnitY()));
    for (const Rested &r : restingShapes()) {
        if (r.shape.type == ShapeType::Sphere) continue;
        SCOPED_TRACE(r.name);
        const Quaternion q = r.shape.type == ShapeType::Capsule ? alongPath : Quaternion::Identity();
        const Track track = crossFloor(gridFloor(true), r.shape, q, r.restHeight, v, false, 0.1, 3.0);
        EXPECT_LE(heightError(track, r.restHeight), 0.001);
        EXPECT_LE(verticalSpeed(track, 15), 0.01);
        EXPECT_GT(track.travelled, 7);
    }
}

TEST(MeshContact, SphereDroppedOntoAMeshStopsAtItsSurface) {
    // As onto a plane (speculative_contact_test.cpp): from 5 m it meets the floor at
    // 9.9 m/s, 16.5 cm per step; the contact acts in the step of the impact, so it never
    // gets more than 5 mm into the floor.
    WorldFixture f(noSleep());
    addStaticBody(f, gridFloor(true));
    const real radius = 0.25;
    const BodyId ball = addBody(f, Shape::sphere(radius), Vector3(0.3, 5 + radius, 0.2));
    real deepest = 0;
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        deepest = std::max(deepest, radius - f.position(ball).y());
    }
    EXPECT_LE(deepest, 0.005);
    EXPECT_NEAR(f.position(ball).y(), radius, kRestTolerance);
}

TEST(MeshContact, BallPassingCloseToAMeshIsNotSlowed) {
    // Without gravity a ball flies level at 10 m/s 1 cm above the floor, then 1 cm past
    // the end of a wall: both are within its step's reach (16.7 cm), neither closes on it
    // along the normal of its nearest feature within the step, or meets it when swept,
    // so it has no contact and keeps its velocity to the bit.
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    const real radius = 0.25;
    {
        WorldFixture f(settings);
        addStaticBody(f, gridFloor(true));
        const BodyId ball = addBody(f, Shape::sphere(radius), Vector3(-8, radius + 0.01, 0.3), Vector3(10, 0, 0));
        int contacts = 0;
        for (int i = 0; i < 90; ++i) {
            f.world.step(kDt);
            contacts += f.world.stats().contacts;
        }
        EXPECT_EQ(contacts, 0);
        EXPECT_EQ(f.world.body(ball).getVelocity(), Vector3(10, 0, 0));
    }
    {
        // A wall in the plane x = 0 over z in [-2, 0]: the ball's path along x at
        // z = radius + 0.01 passes its end edge at z = 0 with 1 cm to spare.
        WorldFixture f(settings);
        addStaticBody(f, Shape::mesh({Vector3(0, -2, -2), Vector3(0, 2, -2), Vector3(0, 2, 0), Vector3(0, -2, 0)},
                                 {{0, 2, 1}, {0, 3, 2}}));
        const BodyId ball = addBody(f, Shape::sphere(radius), Vector3(-3, 0.3, radius + 0.01), Vector3(10, 0, 0));
        int contacts = 0;
        for (int i = 0; i < 60; ++i) {
            f.world.step(kDt);
            contacts += f.world.stats().contacts;
        }
        EXPECT_EQ(contacts, 0);
        EXPECT_EQ(f.world.body(ball).getVelocity(), Vector3(10, 0, 0));
    }
}

}  // namespace
}  // namespace cyclone::test
