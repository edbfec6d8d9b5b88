// Hostile input, round three (issue 61): a step too short for the step's divisions, a
// frame too long for the stepper's sums, shapes that reach beyond the coordinate range
// through a compound's child or a query, and callbacks that change the World while it
// is being read. Each is refused with InvalidArgument naming the function, the field and
// the value, and the World is left as it was.
#include <gtest/gtest.h>

#include <cfloat>
#include <string>
#include <vector>

#include "cyclone/world/game_loop.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

template <class Call>
void expectLimitRefused(Call call, const std::string &function, const std::string &field, const std::string &shown) {
    try {
        call();
        FAIL() << "no throw for " << field;
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), function) << e.what();
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(e.problem().find(shown), std::string::npos) << e.what();
    }
}

// dt = 5e-324 (the smallest double) made eleven ragdoll bodies non-finite in the first
// step: 1 / 5e-324 is no double. Below kMinStep = 1e-6 s the step is refused and nothing
// moves; kMinStep itself is taken, and a box falling for one such step moves by
// g dt^2 = 9.81e-12 m at most (it moves, it stays finite).
TEST(HostileLimits, AStepShorterThanTheShortestIsRefused) {
    WorldFixture f(noSleep());
    f.ground();
    const BodyId box = f.box(Vector3(0, 2, 0));
    for (real dt : {real(5e-324), real(1e-310), real(1e-7), real(0)}) {
        expectLimitRefused([&] { f.world.step(dt); }, "World::step", "dt", "in [1e-06, 1] s");
    }
    EXPECT_EQ(f.position(box), Vector3(0, 2, 0));
    f.world.step(kMinStep);
    const real y = f.position(box).y();
    EXPECT_LT(y, 2);
    EXPECT_GT(y, 2 - 2 * kG * kMinStep * kMinStep);
}

TEST(HostileLimits, AStepperStepShorterThanTheShortestIsRefused) {
    WorldFixture f;
    FixedStepSettings s;
    s.stepSeconds = 5e-324;
    expectLimitRefused([&] { FixedStepper stepper(f.world, s); }, "FixedStepper::FixedStepper", "stepSeconds",
                       "got 5e-324");
    FixedStepper stepper(f.world);
    expectLimitRefused([&] { stepper.setSettings(s); }, "FixedStepper::setSettings", "stepSeconds", "[1e-06, 1]");
    EXPECT_EQ(stepper.settings().stepSeconds, real(1) / 60);
}

// advance(DBL_MAX) twice: each frame drops all but five steps of it, and the dropped
// time summed to 2 DBL_MAX = inf. A frame beyond kMaxFrameSeconds = 1e9 s is refused (and
// changes nothing); two frames of 1e9 s drop 2e9 s less ten steps, a finite sum.
TEST(HostileLimits, TheStepperSumsStayFinite) {
    WorldFixture f;
    FixedStepper stepper(f.world);
    expectLimitRefused([&] { stepper.advance(DBL_MAX); }, "FixedStepper::advance", "frameSeconds", "[0, 1e9] s");
    EXPECT_EQ(stepper.droppedSeconds(), 0);
    EXPECT_EQ(stepper.advance(kMaxFrameSeconds), 5);
    EXPECT_EQ(stepper.advance(kMaxFrameSeconds), 5);
    // 2e9 s less the 10 steps of 1/60 s run, less what is left in the accumulator (under a step).
    EXPECT_NEAR(stepper.droppedSeconds(), 2e9 - 10.0 / 60, 1.0 / 60 + 1e-6);
    EXPECT_LT(stepper.accumulatedSeconds(), 1.0 / 60);
}

CompoundChild sphereChild(const Vector3 &position) {
    CompoundChild child;
    child.shape = Shape::sphere(1);
    child.position = position;
    return child;
}

// A compound whose frame is at 9e11 m with a child 9e11 m further out: the frame and the
// shape's size are each within 1e12 m, but the child's far side is at
// 9e11 + 9e11 + 1 = 1.8e12 m (its centre of mass, halfway, at 1.35e12 m, is itself
// beyond). Refused at the position, naming where the shape reaches.
TEST(HostileLimits, ACompoundChildBeyondTheRangeIsRefused) {
    WorldFixture f;
    BodySettings s;
    s.shape = Shape::compound({sphereChild(Vector3::Zero()), sphereChild(Vector3(9e11, 0, 0))});
    s.position = Vector3(9e11, 0, 0);
    expectLimitRefused([&] { f.world.addBody(s); }, "World::addBody", "position", "every point must be within 1e12 m");
    // A child 1e300 m from the frame is refused at that child.
    s.shape = Shape::compound({sphereChild(Vector3::Zero()), sphereChild(Vector3(1e300, 0, 0))});
    s.position = Vector3::Zero();
    expectLimitRefused([&] { f.world.addBody(s); }, "World::addBody", "shape.children[1].position", "1e+300");
    EXPECT_EQ(f.world.bodyCount(), 0u);
    // The same two children 1e6 m apart, at the origin: within the range, accepted.
    s.shape = Shape::compound({sphereChild(Vector3::Zero()), sphereChild(Vector3(1e6, 0, 0))});
    EXPECT_NO_THROW(f.world.addBody(s));
}

// setPosition checks the shape's far side too: a unit box (half diagonal sqrt(3)/2 =
// 0.87 m) may go to 1e12 - 1 m, not to 1e12 - 0.5 m.
TEST(HostileLimits, SetPositionKeepsTheWholeShapeInRange) {
    WorldFixture f;
    const BodyId box = f.box(Vector3::Zero());
    EXPECT_NO_THROW(f.world.setPosition(box, Vector3(kMaxCoordinate - 1, 0, 0)));
    expectLimitRefused([&] { f.world.setPosition(box, Vector3(0, kMaxCoordinate - 0.5, 0)); }, "World::setPosition",
                       "position", "every point must be within 1e12 m");
    EXPECT_EQ(f.position(box), Vector3(kMaxCoordinate - 1, 0, 0));
}

// overlap() and shapeCast() said their shape is "validated as for addBody" and took a
// sphere of radius 1e300. Refused at the shape; a shape placed so that its far side, or
// its end after the cast, leaves the range is refused at the position or the translation.
TEST(HostileLimits, QueryShapesBeyondTheRangeAreRefused) {
    WorldFixture f;
    f.box(Vector3::Zero());
    std::vector<BodyId> out;
    const Quaternion q = Quaternion::Identity();
    expectLimitRefused([&] { f.world.overlap(Shape::sphere(1e300), Vector3::Zero(), q, out); }, "World::overlap", "shape",
                       "1e+300");
    expectLimitRefused([&] { f.world.shapeCast(Shape::sphere(1e300), Vector3::Zero(), q, Vector3(1, 0, 0)); },
                       "World::shapeCast", "shape", "1e+300");
    expectLimitRefused([&] { f.world.overlap(Shape::sphere(2), Vector3(kMaxCoordinate - 1, 0, 0), q, out); },
                       "World::overlap", "position", "every point must be within 1e12 m");
    expectLimitRefused([&] { f.world.shapeCast(Shape::sphere(1), Vector3::Zero(), q, Vector3(0, 0, kMaxCoordinate)); },
                       "World::shapeCast", "translation", "every point must be within 1e12 m");
    // Within the range the queries answer: the unit box at the origin is found.
    EXPECT_EQ(f.world.overlap(Shape::sphere(1), Vector3::Zero(), q, out), 1u);
    EXPECT_TRUE(f.world.shapeCast(Shape::sphere(0.5), Vector3(-5, 0, 0), q, Vector3(10, 0, 0)).has_value());
}

// A DebugDraw that removes a body from its line(): the walk went on over the removed
// body's shape and the pairs it freed (a use after free under ASan, a segfault in
// Release). Now debugDraw throws at "draw" as soon as that line() returns.
struct RemovingDraw : DebugDraw {
    World *world = nullptr;
    std::vector<BodyId> victims;
    int lines = 0;
    void line(const Vector3 &, const Vector3 &, const DebugColor &) override {
        ++lines;
        for (BodyId id : victims)
            if (world->contains(id)) world->removeBody(id);
    }
};

struct SteppingDraw : DebugDraw {
    World *world = nullptr;
    void line(const Vector3 &, const Vector3 &, const DebugColor &) override { world->step(kDt); }
};

struct CountingDraw : DebugDraw {
    const World *world = nullptr;
    int lines = 0;
    void line(const Vector3 &, const Vector3 &, const DebugColor &) override {
        lines += world->bodyCount() > 0;
    }
};

TEST(HostileLimits, ADebugDrawThatChangesTheWorldIsRefused) {
    WorldFixture f;
    f.ground();
    std::vector<BodyId> boxes;
    for (int i = 0; i < 6; ++i) boxes.push_back(f.box(Vector3(0, 0.5 + i, 0)));  // a stack: contacts to draw
    f.world.step(kDt);
    DebugDrawOptions options;
    options.contacts = true;
    options.boundingBoxes = true;
    RemovingDraw removing;
    removing.world = &f.world;
    removing.victims = boxes;
    expectLimitRefused([&] { f.world.debugDraw(removing, options); }, "World::debugDraw", "draw", "must only read");
    EXPECT_EQ(removing.lines, 1);  // refused after the first line, before the walk went on
    EXPECT_EQ(f.world.bodyCount(), 1u);  // what it did stays done: only the ground is left
    for (int i = 0; i < 3; ++i) f.box(Vector3(0, 0.5 + i, 0));
    f.world.step(kDt);
    SteppingDraw stepping;
    stepping.world = &f.world;
    expectLimitRefused([&] { f.world.debugDraw(stepping, options); }, "World::debugDraw", "draw", "must only read");
    // A draw that only reads draws everything: the ground plane's 7 lines, 12 per box for
    // each of its shape and its bounding box, and at least one contact's 4 lines.
    CountingDraw counting;
    counting.world = &f.world;
    EXPECT_NO_THROW(f.world.debugDraw(counting, options));
    EXPECT_GE(counting.lines, 7 + 3 * 24 + 4);
}

// The query filter's check covers every changing call, not only those that move the
// broadphase: a filter that steps the World (with every body asleep, so that nothing
// moves) or sets a velocity is refused.
TEST(HostileLimits, AQueryFilterThatCallsAChangingMemberIsRefused) {
    WorldFixture f;
    const BodyId box = f.box(Vector3(0, 0, 0));
    QueryFilter filter;
    filter.accept = [&](BodyId id) {
        f.world.setVelocity(id, Vector3(0, 0, 0));
        return true;
    };
    expectLimitRefused([&] { f.world.rayCast(Vector3(0, 0, -5), Vector3(0, 0, 1), 100, filter); }, "World query",
                       "filter.accept", "must only read");
    EXPECT_TRUE(f.world.contains(box));
}

}  // namespace
}  // namespace cyclone::test
