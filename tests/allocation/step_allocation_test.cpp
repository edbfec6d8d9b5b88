// A World step in steady state allocates nothing: after warm-up steps have grown every
// reused vector, further steps of a scene at rest (or in a steady motion) call operator
// new zero times.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "counting_allocator.h"
#include "cyclone/world.h"

namespace cyclone::test {
namespace {

constexpr real kDt = 1.0 / 60.0;
constexpr real kPi = 3.14159265358979323846;

// A unit cube as a convex hull (its narrowphase goes through libccd's MPR).
Shape hullCube() {
    std::vector<Vector3> corners;
    for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    return Shape::convex(corners);
}

BodyId addGround(World &world) {
    BodySettings s;
    s.motion = Motion::Static;
    s.shape = Shape::plane(Vector3::UnitY(), 0);
    return world.addBody(s);
}

BodyId addBody(World &world, const Shape &shape, const Vector3 &position,
               const Quaternion &orientation = Quaternion::Identity()) {
    BodySettings s;
    s.shape = shape;
    s.position = position;
    s.orientation = orientation;
    return world.addBody(s);
}

// What the counted steps did, so that a test can show they did real work.
struct Counted {
    long allocations = 0;
    long pairsTested = 0;
    long contacts = 0;
    long contactBegins = 0;
    long contactEnds = 0;
    long springs = 0;
    long ccdSweeps = 0;
};

// Steps `warmUp` times, then counts the allocations of `steps` more.
Counted countSteps(World &world, int warmUp, int steps, const std::function<void()> &beforeStep = {}) {
    for (int i = 0; i < warmUp; ++i) {
        if (beforeStep) beforeStep();
        world.step(kDt);
    }
    Counted c;
    for (int i = 0; i < steps; ++i) {
        if (beforeStep) beforeStep();
        const long before = allocationCount();
        world.step(kDt);
        c.allocations += allocationCount() - before;
        const StepStats &stats = world.stats();
        c.pairsTested += stats.pairsTested;
        c.contacts += stats.contacts;
        c.springs += stats.springs;
        c.ccdSweeps += stats.ccdSweeps;
        c.contactBegins += static_cast<long>(world.events().contactBegins.size());
        c.contactEnds += static_cast<long>(world.events().contactEnds.size());
    }
    return c;
}

// A pyramid of base 5 (15 cubes, 1.05 m apart, resting on each other), sleep off.
// Boxes (their own separating-axis test) and the same cubes as convex hulls (libccd's
// MPR); with manifold reuse off every counted step runs the narrowphase on every pair,
// with the default reuse it refreshes the kept manifolds instead.
TEST(StepAllocation, RestingPyramidAllocatesNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    for (const real reuse : {real(0), WorldSettings().debug.manifoldReuseTolerance}) {
        for (const Shape &cube : {Shape::box(Vector3::Constant(0.5)), hullCube()}) {
            const std::string what = std::string(shapeTypeName(cube.type)) + ", reuse " + std::to_string(reuse);
            WorldSettings settings;
            settings.sleep = false;
            settings.debug.manifoldReuseTolerance = reuse;
            World world(settings);
            addGround(world);
            for (int level = 0; level < 5; ++level)
                for (int i = 0; i < 5 - level; ++i)
                    addBody(world, cube, Vector3((i - 0.5 * (4 - level)) * 1.05, 0.5 + level, 0));
            const Counted c = countSteps(world, 120, 120);
            EXPECT_EQ(c.allocations, 0) << what;
            // 5 cubes on the ground and 10 cubes on two each: 25 contacts of 4 points at rest.
            EXPECT_EQ(world.stats().contacts, 100) << what;
            if (reuse == 0) {
                EXPECT_GT(c.pairsTested, 0) << "the counted steps must run the narrowphase";
            }
        }
    }
}

// Spheres, capsules, cylinders and hulls at rest on the ground and on a static box.
TEST(StepAllocation, RestingMixedShapesAllocateNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    WorldSettings settings;
    settings.sleep = false;
    World world(settings);
    addGround(world);
    BodySettings table;
    table.motion = Motion::Static;
    table.shape = Shape::box(Vector3(3, 0.5, 3));
    table.position = Vector3(0, 0.5, 10);
    world.addBody(table);
    // Capsules and cylinders have their axis along local z: the capsule lies along x,
    // the cylinder stands along y.
    const Quaternion alongX(Eigen::AngleAxis<real>(kPi / 2, Vector3::UnitY()));
    const Quaternion upright(Eigen::AngleAxis<real>(-kPi / 2, Vector3::UnitX()));
    for (int k = 0; k < 2; ++k) {
        const real base = k == 0 ? 0 : 1;  // on the ground, then on the table
        const real z = k == 0 ? 0 : 10;
        addBody(world, Shape::sphere(0.4), Vector3(-3, base + 0.4, z));
        addBody(world, Shape::capsule(0.25, 1), Vector3(-1.5, base + 0.25, z), alongX);
        addBody(world, Shape::cylinder(0.4, 1), Vector3(0, base + 0.5, z), upright);
        addBody(world, hullCube(), Vector3(1.5, base + 0.5, z));
    }
    const Counted c = countSteps(world, 180, 120);
    EXPECT_EQ(c.allocations, 0);
    EXPECT_GT(c.contacts, 0);
}

// 100 boxes asleep in stacks and one sphere bouncing on the ground: its contact begins
// and ends (a pair created and removed, events recorded) without allocating.
TEST(StepAllocation, BouncingSphereAmongSleepingBoxesAllocatesNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    World world;
    addGround(world);
    for (int stack = 0; stack < 10; ++stack) {
        for (int level = 0; level < 10; ++level) {
            BodySettings box;
            box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            box.position = Vector3(stack * 2.0, 0.5 + level, 0);
            box.awake = false;
            world.addBody(box);
        }
    }
    BodySettings ball;
    ball.shape = Shape::sphere(0.5);
    ball.position = Vector3(-20, 3, 0);
    ball.material.restitution = 1;
    ball.canSleep = false;
    world.addBody(ball);
    const Counted c = countSteps(world, 240, 240);
    EXPECT_EQ(c.allocations, 0);
    EXPECT_GT(c.contactBegins, 0) << "the ball must bounce during the counted steps";
    EXPECT_GT(c.contactEnds, 0);
    EXPECT_EQ(world.stats().awakeBodies, 1);
}

// Springs (a chain hanging from a world anchor), a ccd body sliding on the ground, and
// a body pushed by a user force every step.
TEST(StepAllocation, SpringsCcdAndForcesAllocateNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    WorldSettings settings;
    settings.sleep = false;
    World world(settings);
    addGround(world);
    BodyId previous;
    for (int i = 0; i < 4; ++i) {
        const BodyId link = addBody(world, Shape::sphere(0.2), Vector3(5, 9 - i, 0));
        SpringSettings spring;
        spring.a = link;
        if (i == 0) {
            spring.bPoint = Vector3(5, 10, 0);
        } else {
            spring.b = previous;
        }
        spring.stiffness = 200;
        spring.damping = 2;
        world.addSpring(spring);
        previous = link;
    }
    BodySettings fast;
    fast.shape = Shape::sphere(0.1);
    fast.position = Vector3(-5, 0.1, 0);
    fast.velocity = Vector3(0, 0, 30);
    fast.ccd = true;
    fast.material.friction = 0;
    world.addBody(fast);
    const BodyId pushed = addBody(world, hullCube(), Vector3(0, 0.5, -5));
    const Counted c = countSteps(world, 60, 60, [&] { world.addForce(pushed, Vector3(0, 0, 1)); });
    EXPECT_EQ(c.allocations, 0);
    EXPECT_EQ(c.springs, 4 * 60);
    EXPECT_EQ(c.ccdSweeps, 60) << "the fast body must be swept every counted step";
}

// The level features in steady motion: a crate riding a conveyor, a body locked to its
// plane resting on a one-way ledge, a contact listener seeing every manifold, and the
// contact impulses reported every step.
TEST(StepAllocation, ConveyorsLedgesLocksAndAListenerAllocateNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    struct Counting final : ContactListener {
        long calls = 0;
        void preSolve(PreSolveContact &) override { ++calls; }
    } listener;
    WorldSettings settings;
    settings.sleep = false;
    World world(settings);
    addGround(world);
    BodySettings belt;
    belt.motion = Motion::Static;
    belt.shape = Shape::box(Vector3(50, 0.25, 1));
    belt.position = Vector3(0, 0.25, 5);
    belt.surfaceVelocity = Vector3(1, 0, 0);
    world.addBody(belt);
    addBody(world, Shape::box(Vector3(0.3, 0.3, 0.3)), Vector3(0, 0.8, 5));
    BodySettings ledge;
    ledge.motion = Motion::Static;
    ledge.shape = Shape::box(Vector3(1, 0.1, 1));
    ledge.position = Vector3(0, 2, -5);
    ledge.oneWay = Vector3(0, 1, 0);
    world.addBody(ledge);
    BodySettings player;
    player.shape = Shape::box(Vector3(0.3, 0.3, 0.3));
    player.position = Vector3(0, 2.4, -5);
    player.lockedAxes.z = player.lockedAxes.rx = player.lockedAxes.ry = true;
    world.addBody(player);
    world.setContactListener(&listener);
    const Counted c = countSteps(world, 60, 60);
    EXPECT_EQ(c.allocations, 0);
    EXPECT_GT(listener.calls, 60) << "the listener must see the counted steps' manifolds";
    EXPECT_EQ(world.events().contactImpulses.size(), 2u) << "the crate on the belt, the player on the ledge";
}

}  // namespace
}  // namespace cyclone::test
