// Small and large bodies: shapes placed to touch get their contact in the first step
// whatever rounding left between them, a pyramid of 5 cm boxes holds as one of unit
// boxes does, and a small body's sleep threshold follows its size.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A 5 cm box placed 1 nm above the ground, or above another box (a gap no position
// computed in doubles avoids: 0.025 + 0.05 is not 0.075). Within the touch margin (the
// slop, 0.2 mm) it is in contact from the first step and stays where it is; before, it
// had no contact in that step and fell into what it rests on for the whole step: at 4
// sub-steps of h = dt / 4, g h^2 (1 + 2 + 3 + 4) = 1.7 mm, a third of its height.
TEST(Scale, ShapesPlacedToTouchAreInContactFromTheFirstStep) {
    const double half = 0.025;
    const double gap = 1e-9;
    for (const bool onBox : {false, true}) {
        WorldFixture f(noSleep());
        f.ground();
        double base = 0;
        if (onBox) {
            f.box(Vector3(0, half, 0), Vector3::Constant(half), 1e-3);
            base = 2 * half;
        }
        const BodyId box = f.box(Vector3(0, base + half + gap, 0), Vector3::Constant(half), 1e-3);
        f.world.step(kDt);
        EXPECT_GT(f.world.stats().contacts, 0) << (onBox ? "on a box" : "on the ground");
        // It may close the gap and sink into the slop, no more (1e-5 m: a twentieth of
        // the slop, far below the 1.7 mm of a step's fall).
        EXPECT_NEAR(f.position(box).y(), base + half, 1e-5) << (onBox ? "on a box" : "on the ground");
    }
}

// Apart by twice the slop, the box is not touching: no contact in the first step (the
// margin is the slop, not more), and it falls until its speculative contact stops it.
TEST(Scale, ShapesApartByMoreThanTheSlopHaveNoContactAtRest) {
    WorldFixture f(noSleep());
    f.ground();
    const real gap = 2 * f.world.settings().penetrationSlop;
    f.box(Vector3(0, 0.025 + gap, 0), Vector3::Constant(0.025), 1e-3);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().contacts, 0);
}

struct PyramidDrift {
    double top = 0;      // the top box's displacement after the run, m
    double deepest = 0;  // the deepest contact of any step, m
};

// The benchmark's pyramid (bench/scenes.cpp) of `levels` levels of boxes of `edge`, 1.05
// edges apart and touching vertically (positions computed in doubles, so apart or
// overlapping by rounding), each box edge^3 kg; 10 s at 60 Hz at the default settings,
// sleep off. bench/scale.cpp (cyclone-scale) prints the same for any size.
PyramidDrift pyramidDrift(double edge, int levels) {
    WorldFixture f(noSleep());
    f.ground();
    BodyId top{};
    for (int layer = 0; layer < levels; ++layer) {
        const int count = levels - layer;
        for (int i = 0; i < count; ++i)
            top = f.box(Vector3((i - (count - 1) / 2.0) * 1.05 * edge, (0.5 + layer) * edge, 0),
                        Vector3::Constant(edge / 2), edge * edge * edge);
    }
    const Vector3 start = f.position(top);
    PyramidDrift d;
    for (int i = 0; i < 600; ++i) {
        f.world.step(kDt);
        d.deepest = std::max(d.deepest, static_cast<double>(f.world.stats().maxPenetration));
    }
    d.top = (f.position(top) - start).norm();
    return d;
}

// The target: the 10-level pyramid of 5 cm boxes moves its top box at most 1 % of
// an edge (0.5 mm) in 10 s. Why 1 % is the right bound: a level that misses its first
// contact falls a step into the one below, 1.7 mm (above), and the 10 levels sank 2.6 mm
// (5 % of an edge) that way before the touch margin; the bound is a third of one such
// fall, so any missed contact fails it. What nothing rules out is the sideways residue of
// the order in which points are solved, which grows with the step and not with the
// boxes (0.03-0.05 mm at every size from 1 cm to 10 m: docs/solver.md, "Small bodies:
// the touch margin and the sleep threshold"), a tenth of the bound here. Contacts never go deeper than that fall either.
TEST(Scale, APyramidOfFiveCentimetreBoxesHolds) {
    const double edge = 0.05;
    const PyramidDrift d = pyramidDrift(edge, 10);
    EXPECT_LE(d.top, 0.01 * edge);
    EXPECT_LE(d.deepest, 0.01 * edge);
}

// The same pyramid of 10 m boxes: 1 % of an edge would be 10 cm, so it is held to the
// stability suite's absolute bound for a stack's sideways drift, 1 mm (stability_test.cpp),
// and the deepest contact to a slop plus one sub-step of gravity, g h^2 (h = dt / 4).
TEST(Scale, APyramidOfTenMetreBoxesHolds) {
    const PyramidDrift d = pyramidDrift(10, 10);
    EXPECT_LE(d.top, 0.001);
    const double h = kDt / 4;
    EXPECT_LE(d.deepest, WorldSettings().penetrationSlop + kG * h * h);
}

// A 5 cm box resting on the ground (woken at rest: sleep average twice its threshold,
// halving each second) sleeps after about a second, as a unit box does.
TEST(Scale, AFiveCentimetreBoxAtRestSleeps) {
    WorldFixture f;
    f.ground();
    const BodyId box = f.box(Vector3(0, 0.025, 0), Vector3::Constant(0.025), 1.25e-4);
    f.simulate(2);
    EXPECT_FALSE(f.awake(box));
}

// A 5 cm box sliding without friction at 5 cm/s, an edge per second: v.v = 0.0025 is a
// quarter of the world's threshold (0.01), under which it slept within sleepDelay. Its
// own threshold is 0.01 (R / 0.25 m)^2 with R = 0.025 sqrt(3) = 0.0433 m, 3.0e-4, which
// v.v exceeds 8 times: it stays awake, and slides its 25 cm in 5 s.
TEST(Scale, AFiveCentimetreBoxSlidingAnEdgeASecondStaysAwake) {
    WorldFixture f;
    f.ground(0);
    const BodyId box = f.box(Vector3(0, 0.025, 0), Vector3::Constant(0.025), 1.25e-4, 0);
    f.world.setVelocity(box, Vector3(0.05, 0, 0));
    f.simulate(5);
    EXPECT_TRUE(f.awake(box));
    EXPECT_NEAR(f.position(box).x(), 0.25, 0.001);
}

}  // namespace
}  // namespace cyclone::test
