// Continuous collision: fast bodies with BodySettings::ccd do not pass through thin
// things, whatever the pair of shapes, and bodies without it cost nothing.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

WorldSettings flying() {
    WorldSettings settings;
    settings.gravity = Vector3::Zero();
    settings.sleep = false;
    return settings;
}

// Hull of a cube of half size `half`.
Shape hullCube(real half) {
    std::vector<Vector3> points;
    for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? half : -half, i & 2 ? half : -half, i & 4 ? half : -half);
    return Shape::convex(points);
}

// Obstacles whose near side is at x = -0.05 m on the shots' path: walls 0.1 m thick
// across x = 0, 4 m x 4 m (a mesh: the near face only), a 1 m ball, and rods 0.1 m thick.
std::vector<std::pair<std::string, Shape>> walls() {
    std::vector<Vector3> slab;
    for (int i = 0; i < 8; ++i) slab.emplace_back(i & 1 ? 0.05 : -0.05, i & 2 ? 2 : -2, i & 4 ? 2 : -2);
    const std::vector<Vector3> face{{-0.05, -2, -2}, {-0.05, 2, -2}, {-0.05, 2, 2}, {-0.05, -2, 2}};
    return {{"box", Shape::box(Vector3(0.05, 2, 2))},
            {"convex", Shape::convex(slab)},
            {"mesh", Shape::mesh(face, {{0, 2, 1}, {0, 3, 2}})},
            {"sphere", Shape::sphere(1)},
            {"capsule", Shape::capsule(0.05, 4)},
            {"cylinder", Shape::cylinder(0.05, 4)}};
}

// Fast movers, each about 0.1 m across.
std::vector<std::pair<std::string, Shape>> movers() {
    return {{"sphere", Shape::sphere(0.05)},
            {"box", Shape::box(Vector3(0.05, 0.05, 0.05))},
            {"capsule", Shape::capsule(0.05, 0.1)},
            {"cylinder", Shape::cylinder(0.05, 0.1)},
            {"convex", hullCube(0.05)}};
}

struct Shot {
    real finalX;
    real finalVelocityX;
    int hits;
    int sweeps;
    bool entered;  // the centre was inside the obstacle after some step
};

BodySettings staticBody(const Shape &shape) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = shape;
    return s;
}

// A mover starting 2 m before the obstacle at `speed` along +x, turning at 3 rad/s, for 0.5 s
// at 60 Hz (3.3 m per step at 200 m/s: the wall is inside one step's motion).
Shot shoot(const Shape &mover, const BodySettings &wall, bool ccd, real speed = 200,
           const std::function<bool(const Vector3 &)> &inside = nullptr) {
    WorldFixture f(flying());
    f.world.addBody(wall);
    BodySettings s;
    s.shape = mover;
    s.position = Vector3(-2, 0.3, 0.01);
    s.velocity = Vector3(speed, 0, 0);
    s.rotation = Vector3(0, 3, 1);
    s.ccd = ccd;
    const BodyId id = f.world.addBody(s);
    Shot shot{0, 0, 0, 0, false};
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        shot.hits += f.world.stats().ccdHits;
        shot.sweeps += f.world.stats().ccdSweeps;
        if (inside && inside(f.position(id))) shot.entered = true;
    }
    shot.finalX = f.position(id).x();
    shot.finalVelocityX = f.world.body(id).getVelocity().x();
    return shot;
}

// Without ccd a mesh wall stops it as a solid wall does (below): at 3.3 m per step the
// wall's triangles lie within the step's reach and give a speculative contact that holds
// the ball on the near side, its centre its radius before the face at x = -0.05, less
// the 2 mm of tolerance the solid wall's test allows.
TEST(ContinuousCollision, WithoutItSpeculativeContactsStopAFastBodyAtAMesh) {
    const std::vector<Vector3> face{{-0.05, -2, -2}, {-0.05, 2, -2}, {-0.05, 2, 2}, {-0.05, -2, 2}};
    const Shot shot = shoot(Shape::sphere(0.05), staticBody(Shape::mesh(face, {{0, 2, 1}, {0, 3, 2}})), false);
    EXPECT_LT(shot.finalX, -0.1 + 0.002);
    EXPECT_LT(shot.finalVelocityX, 0.01);
    EXPECT_EQ(shot.sweeps, 0);
}

// Without ccd a solid wall stops it all the same: its box grown by the step's reach
// finds the wall and the speculative contact holds it on the near side.
TEST(ContinuousCollision, WithoutItSpeculativeContactsStopAFastBody) {
    const Shot shot = shoot(Shape::sphere(0.05), staticBody(Shape::box(Vector3(0.05, 2, 2))), false);
    EXPECT_LT(shot.finalX, -0.1 + 0.002);
    EXPECT_LT(shot.finalVelocityX, 0.01);
    EXPECT_EQ(shot.sweeps, 0);
}

// Every mover against every obstacle, head on: its centre never enters the obstacle (for a
// flat wall: never reaches the near face at x = -0.05 m). Against flat walls it stays on
// the near side, its centre at least its inner radius (5 cm) before the face, less 2 mm
// of contact tolerance and slop, and the contact of the step after the hit stops it
// (restitution 0), rather than the sweep holding it in front; round obstacles may send
// it off sideways.
TEST(ContinuousCollision, NoShapeTunnelsThroughAnyObstacle) {
    for (const auto &[wallName, wall] : walls()) {
        BodySettings w;
        w.motion = Motion::Static;
        w.shape = wall;
        // Capsules and cylinders lie along z: turn them across the path (along y).
        const bool rod = wall.type == ShapeType::Capsule || wall.type == ShapeType::Cylinder;
        if (rod) w.orientation = Quaternion(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitX()));
        if (wall.type == ShapeType::Sphere) w.position = Vector3(0.95, 0.3, 0.01);
        const bool flat = !rod && wall.type != ShapeType::Sphere;
        const auto inside = [&](const Vector3 &p) {
            if (wall.type == ShapeType::Sphere) return (p - w.position).norm() < 1;
            if (rod) return std::hypot(p.x(), p.z()) < 0.05 && std::abs(p.y()) < 2;
            return p.x() > -0.05 && std::abs(p.y()) < 2 && std::abs(p.z()) < 2;
        };
        for (const auto &[moverName, mover] : movers()) {
            const Shot shot = shoot(mover, w, true, 200, inside);
            EXPECT_FALSE(shot.entered) << moverName << " into " << wallName;
            // Speculative contacts stop the movers before a sweep finds anything, at a
            // mesh (its triangles within the step's reach) as at a solid obstacle.
            if (wall.type == ShapeType::Mesh) {
                EXPECT_EQ(shot.hits, 0) << moverName << " against " << wallName;
            }
            if (!flat) continue;
            EXPECT_LT(shot.finalX, -0.1 + 0.002) << moverName << " against " << wallName;
            EXPECT_LT(shot.finalVelocityX, 0.01) << moverName << " against " << wallName;
        }
    }
}

// Shots at walls tilted up to 0.3 rad, from random points, directions within 0.07 rad of
// the normal, speeds of 150-250 m/s and spins up to 35 rad/s: no centre ever reaches the
// wall's near face (checked after every step, in the wall's frame).
TEST(ContinuousCollision, RandomShotsNeverTunnel) {
    unsigned seed = 2024;
    auto uniform = [&seed]() {
        seed = seed * 1103515245u + 12345u;
        return real((seed >> 8) & 0xffff) / 0xffff * 2 - 1;
    };
    int shots = 0;
    for (const auto &[wallName, wall] : walls()) {
        if (wall.type != ShapeType::Box && wall.type != ShapeType::Convex) continue;
        for (const auto &[moverName, mover] : movers()) {
            for (int i = 0; i < 20; ++i, ++shots) {
                WorldFixture f(flying());
                BodySettings w;
                w.motion = Motion::Static;
                w.shape = wall;
                w.orientation = Quaternion(Eigen::AngleAxis<real>(
                    0.3 * uniform(), Vector3(uniform(), uniform(), uniform()).normalized()));
                const BodyId wallId = f.world.addBody(w);
                BodySettings s;
                s.shape = mover;
                s.position = Vector3(-2, 0.5 * uniform(), 0.5 * uniform());
                s.orientation = Quaternion(uniform(), uniform(), uniform(), uniform());
                s.velocity = Vector3(200 + 50 * uniform(), 10 * uniform(), 10 * uniform());
                s.rotation = 20 * Vector3(uniform(), uniform(), uniform());
                s.ccd = true;
                const BodyId id = f.world.addBody(s);
                for (int step = 0; step < 20; ++step) {
                    f.world.step(kDt);
                    const Vector3 local = f.world.body(wallId).getPointInLocalSpace(f.position(id));
                    const bool facing = std::abs(local.y()) < 2 && std::abs(local.z()) < 2;
                    ASSERT_FALSE(facing && local.x() > -0.05)
                        << moverName << " into " << wallName << ", shot " << i << ", step " << step;
                }
            }
        }
    }
    EXPECT_EQ(shots, 200);
}

// A ground plane: the time of impact is where the lowest point reaches the surface, so a
// sphere falling at 200 m/s stops on it instead of 3 m below.
TEST(ContinuousCollision, PlanesStopFastBodiesAtTheSurface) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.ground();
    BodySettings s;
    s.shape = Shape::sphere(0.05);
    s.position = Vector3(0, 2, 0);
    s.velocity = Vector3(0, -200, 0);
    s.ccd = true;
    const BodyId ball = f.world.addBody(s);
    real lowest = 2;
    for (int i = 0; i < 30; ++i) {
        f.world.step(kDt);
        lowest = std::min(lowest, f.position(ball).y());
    }
    // The radius, less the 0.2 mm slop and what the split impulse leaves in one step.
    EXPECT_GT(lowest, 0.05 - 0.005);
}

// A thin dynamic plate is hit, not jumped: the ball pushes it.
TEST(ContinuousCollision, DynamicTargetsAreHit) {
    WorldFixture f(flying());
    const BodyId plate = f.box(Vector3::Zero(), Vector3(0.05, 1, 1), 1);
    BodySettings s;
    s.shape = Shape::sphere(0.05);
    s.position = Vector3(-2, 0, 0);
    s.velocity = Vector3(200, 0, 0);
    s.mass = 1;
    s.ccd = true;
    const BodyId ball = f.world.addBody(s);
    f.simulate(0.1);
    EXPECT_LT(f.position(ball).x(), f.position(plate).x());
    EXPECT_GT(f.world.body(plate).getVelocity().x(), 10);
}

// A ccd body sliding fast on the floor it rests on is not held back: a pair already in
// contact at the step's start is the solver's, not the sweep's.
TEST(ContinuousCollision, RestingContactsDoNotStopSliding) {
    WorldSettings settings;
    settings.sleep = false;
    WorldFixture f(settings);
    f.staticBox(Vector3(0, -0.5, 0), Vector3(200, 0.5, 2), Quaternion::Identity(), 0);
    BodySettings s;
    s.shape = Shape::box(Vector3(0.05, 0.05, 0.05));
    s.position = Vector3(-100, 0.05, 0);
    s.material.friction = 0;
    s.ccd = true;
    const BodyId box = f.world.addBody(s);
    f.simulate(0.2);
    f.world.setVelocity(box, Vector3(50, 0, 0));
    const real start = f.position(box).x();
    f.simulate(1);
    EXPECT_NEAR(f.position(box).x() - start, 50, 0.1);
    EXPECT_GT(f.world.stats().ccdSweeps, 0);
}

// No sweep for bodies without ccd, nor for ccd bodies that move less than their inner
// radius in a step (they cannot pass through anything).
TEST(ContinuousCollision, OnlyFastCcdBodiesAreSwept) {
    // The shot also turns at 3.2 rad/s: 0.26 cm per step at the sphere's 5 cm radius.
    const Shot slow = shoot(Shape::sphere(0.05), staticBody(Shape::box(Vector3(0.05, 2, 2))), true, 2.5);  // 4.2 + 0.3 cm
    EXPECT_EQ(slow.sweeps, 0);
    const Shot fast = shoot(Shape::sphere(0.05), staticBody(Shape::box(Vector3(0.05, 2, 2))), true, 3.5);  // 5.8 + 0.3 cm
    EXPECT_GT(fast.sweeps, 0);
}

}  // namespace
}  // namespace cyclone::test
