// The contact solver's pass over one manifold (world/src/contact_solver.cpp): its rows are
// solved one after another, each against the velocities the rows before it left, as
// Gauss-Seidel does, although the bodies' velocities are read once and each impulse
// reaches the later rows through the manifold's couplings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "solver/contact_solver.h"
#include "cube_contact.h"
#include "solver/schedule.h"
#include "solver/velocity_pass.h"

namespace cyclone::test {
namespace {

using detail::SolverBody;
using detail::SolverManifold;
using detail::SolverManifolds;

// A cube falling at `speed` m/s onto the immovable world (cube_contact.h). Adds the cube's
// body and manifold.
void addFallingCube(real speed, std::vector<SolverBody> &bodies, SolverManifolds &manifolds) {
    manifolds.push_back(addCubeOn(0, Vector3(0, -speed, 0), bodies));
}

// One such cube at 1 m/s, solved alone.
struct FallingCube {
    std::vector<SolverBody> bodies{1};
    SolverManifolds manifolds;
    std::vector<detail::SolverGroup> groups{1};
    std::vector<detail::ManifoldBatch> wide;

    FallingCube() {
        addFallingCube(1, bodies, manifolds);
        groups[0].manifold[0] = 0;
        groups[0].size = 1;
    }

    void pass(bool reverse) {
        detail::loadBatches(bodies, manifolds, groups, false, wide);
        detail::solveVelocityBatches(bodies, wide, reverse);
        detail::storeBatches(wide, groups, manifolds);
    }
    Vector3 v() const { return detail::toVector3(bodies[1].v); }
    Vector3 w() const { return detail::toVector3(bodies[1].w); }
    real impulse(int i) const { return manifolds[0].points[i].normal.impulse; }

    // The impulses of points 0 and 1 and the cube's v_y and w_z; nothing else moves.
    void expect(real impulse0, real impulse1, real vy, real wz, real tolerance) const {
        EXPECT_NEAR(impulse(0), impulse0, tolerance);
        EXPECT_NEAR(impulse(1), impulse1, tolerance);
        EXPECT_NEAR(v().y(), vy, tolerance);
        EXPECT_NEAR(w().z(), wz, tolerance);
        EXPECT_NEAR(v().x(), 0, tolerance);
        EXPECT_NEAR(w().x(), 0, tolerance);
    }
};

// By hand. Each row's angular term is rB x n = (0, 0, +-0.5), so its effective mass is
// 1 / (1 + 0.5 * 6 * 0.5) = 0.4 kg, and an impulse on one point changes the other's normal
// velocity by 1 - 0.5 * 6 * 0.5 = -0.5 m/s per N s.
// The first point stops its -1 m/s: 0.4 N s. That leaves v_y = -0.6, w_z = +1.2 and the
// second point at -1 + (-0.5)(0.4) = -1.2 m/s, which takes 0.4 * 1.2 = 0.48 N s. Then
// v_y = -0.12 m/s and w_z = 1.2 - 6 * 0.5 * 0.48 = -0.24 rad/s: the second point is at
// rest and the first sinks at -0.12 - 0.24 * 0.5 = -0.24 m/s, as row-by-row Gauss-Seidel
// leaves them.
TEST(ContactSolverPass, EachRowSeesTheRowsBeforeIt) {
    FallingCube cube;
    cube.pass(false);
    cube.expect(0.4, 0.48, -0.12, -0.24, 1e-12);
}

// Backwards the same numbers fall to the other point, and the cube turns the other way.
TEST(ContactSolverPass, ReversePassMirrorsTheOrder) {
    FallingCube cube;
    cube.pass(true);
    cube.expect(0.48, 0.4, -0.12, 0.24, 1e-12);
}

// The solve order (as World sets it when a kept manifold's points come in another order)
// takes each point with its row and couplings: a forward pass in the order {1, 0} is the
// reverse pass in the stored order, its impulses landing on the same points; so is the
// scalar pass (solveUncarried), and with the order {1, 0} the reverse pass is the
// forward one.
TEST(ContactSolverPass, SolveOrderTakesThePointsWithTheirRowsAndCouplings) {
    for (const bool wide : {true, false}) {
        for (const bool reverse : {false, true}) {
            FallingCube cube;
            cube.manifolds[0].order[0] = 1;
            cube.manifolds[0].order[1] = 0;
            if (wide) cube.pass(reverse);
            else detail::solveUncarried(cube.bodies, cube.manifolds, {0}, reverse);
            SCOPED_TRACE(std::string(wide ? "wide" : "scalar") + (reverse ? ", reverse" : ""));
            if (reverse) cube.expect(0.4, 0.48, -0.12, -0.24, 1e-12);
            else cube.expect(0.48, 0.4, -0.12, 0.24, 1e-12);
        }
    }
}

// The couplings in a solve order are P C P^T: entry k, lane l is the coupling of the k-th
// point's row with the l-th point's (here c[i][j] = 10 i + j, friction rows 100 r + j). In
// the stored order they are C itself.
TEST(ContactSolverPass, CouplingsFollowTheSolveOrder) {
    SolverManifold m;
    detail::RowCouplings c;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) c.normal[i][j] = 10 * i + j;
    for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 4; ++j) c.friction[r][j] = 100 * r + j;
    const signed char stored[4] = {0, 1, 2, 3};
    const signed char order[4] = {2, 0, 3, 1};
    for (const signed char *o : {stored, order}) {
        std::copy(o, o + 4, m.order);
        const detail::CouplingOrder picked(m);
        detail::Lanes entry;
        for (int k = 0; k < 4; ++k) {
            picked.normal(c, k, entry);
            for (int l = 0; l < 4; ++l) EXPECT_EQ(entry[l], 10 * o[k] + o[l]) << k << ", " << l;
        }
        for (int r = 0; r < 3; ++r) {
            picked.friction(c, r, entry);
            for (int l = 0; l < 4; ++l) EXPECT_EQ(entry[l], 100 * r + o[l]) << r << ", " << l;
        }
    }
}

// Loaded with the warm start, a group gives its bodies its accumulated impulses, as
// warmStart does: by hand, 0.3 and 0.2 N s on the two points lift the 1 kg cube by
// 0.5 m/s (-1 -> -0.5) and turn it by 6 * (0.5 * 0.3 - 0.5 * 0.2) = 0.3 rad/s about z
// (rB x n is (0, 0, +0.5) at the first point and (0, 0, -0.5) at the second). Loaded
// without it, the cube keeps its velocity. The world is never written.
TEST(ContactSolverPass, LoadingWithTheWarmStartGivesTheBodiesTheImpulses) {
    for (const bool warm : {true, false}) {
        FallingCube cube;
        cube.manifolds[0].points[0].normal.impulse = 0.3;
        cube.manifolds[0].points[1].normal.impulse = 0.2;
        detail::loadBatches(cube.bodies, cube.manifolds, cube.groups, warm, cube.wide);
        EXPECT_NEAR(cube.v().y(), warm ? -0.5 : -1, 1e-12) << warm;
        EXPECT_NEAR(cube.w().z(), warm ? 0.3 : 0, 1e-12) << warm;
        EXPECT_NEAR(cube.v().x(), 0, 1e-12) << warm;
        EXPECT_NEAR(cube.w().x(), 0, 1e-12) << warm;
        EXPECT_TRUE(detail::toVector3(cube.bodies[0].v).isZero(0)) << warm;
        EXPECT_TRUE(detail::toVector3(cube.bodies[0].w).isZero(0)) << warm;
        // The copy holds the impulses the passes start from.
        EXPECT_EQ(cube.wide[0].points[0].impulse[0], 0.3) << warm;
        EXPECT_EQ(cube.wide[0].points[1].impulse[0], 0.2) << warm;
    }
}

// Over many passes the two points share the cube's momentum equally and both come to
// rest: 0.5 N s each, v = 0, w = 0.
TEST(ContactSolverPass, PassesConvergeToTheRestingSolution) {
    FallingCube cube;
    for (int pass = 0; pass < 60; ++pass) cube.pass((pass & 1) != 0);
    cube.expect(0.5, 0.5, 0, 0, 1e-9);
}

// Four cubes in one group, one per lane, falling at 1, 2, 0.5 and 3 m/s. The pass is
// linear in the speed while no impulse is clamped, so each cube gets the one-cube numbers
// above times its speed: a lane that read or wrote another's rows or bodies would not.
TEST(ContactSolverPass, EachLaneOfAGroupIsSolvedOnItsOwn) {
    const real speeds[4] = {1, 2, 0.5, 3};
    std::vector<SolverBody> bodies(1);
    SolverManifolds manifolds;
    std::vector<detail::SolverGroup> groups(1);
    for (int k = 0; k < 4; ++k) {
        addFallingCube(speeds[k], bodies, manifolds);
        groups[0].manifold[k] = 3 - k;  // lanes in another order than the manifolds
    }
    groups[0].size = 4;
    std::vector<detail::ManifoldBatch> wide;
    detail::loadBatches(bodies, manifolds, groups, false, wide);
    detail::solveVelocityBatches(bodies, wide, false);
    detail::storeBatches(wide, groups, manifolds);
    for (int k = 0; k < 4; ++k) {
        const real s = speeds[k];
        EXPECT_NEAR(manifolds[k].points[0].normal.impulse, 0.4 * s, 1e-12) << "cube " << k;
        EXPECT_NEAR(manifolds[k].points[1].normal.impulse, 0.48 * s, 1e-12) << "cube " << k;
        EXPECT_NEAR(detail::toVector3(bodies[k + 1].v).y(), -0.12 * s, 1e-12) << "cube " << k;
        EXPECT_NEAR(detail::toVector3(bodies[k + 1].w).z(), -0.24 * s, 1e-12) << "cube " << k;
    }
    EXPECT_EQ(detail::toVector3(bodies[0].v), Vector3::Zero());  // the world is never written
}

// Whether two solver bodies hold the same bits, field by field (not the padding, which
// a copy need not keep).
bool sameBits(const SolverBody &x, const SolverBody &y) {
    const auto same = [](const auto &p, const auto &q) { return std::memcmp(&p, &q, sizeof p) == 0; };
    return same(x.v, y.v) && same(x.w, y.w) && same(x.pv, y.pv) && same(x.pw, y.pw) && same(x.invMass, y.invMass) &&
           same(x.invInertia, y.invInertia);
}

// The same for two batches: the lanes' bodies and size, then everything from the first
// Lanes field on (Lanes only, so no padding between them).
bool sameBits(const detail::ManifoldBatch &x, const detail::ManifoldBatch &y) {
    const auto from = [](const detail::ManifoldBatch &m) { return reinterpret_cast<const char *>(&m.invMassA); };
    const auto start = reinterpret_cast<const char *>(&x);
    const std::size_t lanes = sizeof(detail::ManifoldBatch) - static_cast<std::size_t>(from(x) - start);
    return std::memcmp(x.a, y.a, sizeof x.a) == 0 && std::memcmp(x.b, y.b, sizeof x.b) == 0 && x.size == y.size &&
           std::memcmp(from(x), from(y), lanes) == 0;
}

// A later sub-step copies again only what changes within a step (reloadBatches,
// velocity_pass.h). After a sub-step's passes, with every impulse, target and velocity
// changed, and with `isolate` one body isolated (immovable: inverse mass and inertia
// zero), the batches and the bodies the reload leaves are those a full copy leaves, bit
// for bit.
void expectReloadGivesWhatAFullLoadGives(bool isolate) {
    // Six cubes in a column on the world, each manifold's A the cube below (0: the world).
    std::vector<SolverBody> bodies(1);
    SolverManifolds manifolds;
    for (int k = 0; k < 6; ++k) manifolds.push_back(addCubeOn(k, Vector3(0.1 * k, -1 - k, 0.2), bodies));
    std::vector<detail::SolverGroup> groups(2);
    const int lanes[2][4] = {{3, 0, 5, 1}, {4, 2, 0, 0}};
    for (int g = 0; g < 2; ++g) {
        groups[g].size = g == 0 ? 4 : 2;
        for (int k = 0; k < groups[g].size; ++k) groups[g].manifold[k] = lanes[g][k];
    }
    std::vector<detail::ManifoldBatch> wide;
    detail::loadBatches(bodies, manifolds, groups, true, wide);
    detail::solveVelocityBatches(bodies, wide, false);
    detail::storeBatches(wide, groups, manifolds);

    // What the sub-steps in between change.
    for (int k = 0; k < 6; ++k) {
        SolverManifold &m = manifolds[static_cast<std::size_t>(k)];
        for (int i = 0; i < m.count; ++i) {
            m.points[i].normal.impulse += 0.05 * (k + 1);
            m.points[i].velocityBias = 0.01 * (k + i + 1);
        }
        m.frictionRow[0].impulse = 0.001 * (k + 1);
        m.frictionRow[1].impulse = -0.002 * (k + 1);
        m.twist.impulse = 0.003 * (k + 1);
    }
    for (std::size_t b = 1; b < bodies.size(); ++b) {
        detail::setLanes(bodies[b].v, Vector3(0.2, -0.5 * static_cast<real>(b), 0.1));
        detail::setLanes(bodies[b].w, Vector3(0.01 * static_cast<real>(b), 0, -0.02));
    }
    if (isolate) bodies[3] = SolverBody();

    std::vector<SolverBody> fullBodies = bodies;
    std::vector<detail::ManifoldBatch> full;
    detail::loadBatches(fullBodies, manifolds, groups, true, full);
    detail::reloadBatches(bodies, manifolds, groups, true, wide);
    ASSERT_EQ(full.size(), wide.size());
    for (std::size_t g = 0; g < wide.size(); ++g)
        EXPECT_TRUE(sameBits(wide[g], full[g])) << "group " << g;
    for (std::size_t b = 0; b < bodies.size(); ++b)
        EXPECT_TRUE(sameBits(bodies[b], fullBodies[b])) << "body " << b;
    // The warm start moved the bodies: the comparison is not of two untouched copies.
    EXPECT_NE(detail::toVector3(bodies[6].v), Vector3(0.2, -3, 0.1));
}

TEST(ContactSolverPass, ReloadingForALaterSubStepGivesWhatAFullLoadGives) {
    expectReloadGivesWhatAFullLoadGives(false);
}

TEST(ContactSolverPass, ReloadingAfterABodyWasIsolatedGivesWhatAFullLoadGives) {
    expectReloadGivesWhatAFullLoadGives(true);
}

}  // namespace
}  // namespace cyclone::test

namespace cyclone::test {
namespace {

// A rod's manifold on a face whose normal is (0, 1, 0) tilted 0.3 rad about z: two points
// touching 3 mm and 1 mm deep at one end, two speculative ones 0.4 m apart at the other
// (the rod turning down onto the face). All four are moved along the normal into the plane
// through the deeper one (its midpoint's height along n is 0), and friction acts at the
// centre of the touching pair: the origin.
TEST(FrictionCentre, TheCentreOfThePointsNearTheDeepestInItsPlane) {
    const Vector3 n(-std::sin(0.3), std::cos(0.3), 0);
    const Vector3 t(std::cos(0.3), std::sin(0.3), 0);  // across the face, along the rod
    const Vector3 z = Vector3::UnitZ();
    Vector3 points[4] = {0.1 * z, -0.001 * n - 0.1 * z, 0.7 * t + 0.2 * n + 0.1 * z, 0.7 * t + 0.2 * n - 0.1 * z};
    const real depths[4] = {0.003, 0.001, -0.4, -0.4};
    EXPECT_NEAR(detail::frictionCentre(depths, 4, n, points).norm(), 0, 1e-15);
    EXPECT_NEAR((points[0] - 0.1 * z).norm(), 0, 1e-15);
    EXPECT_NEAR((points[1] + 0.1 * z).norm(), 0, 1e-15);  // lifted 1 mm along n
    EXPECT_NEAR((points[2] - (0.7 * t + 0.1 * z)).norm(), 0, 1e-15);  // lowered 0.2 m along n
    EXPECT_NEAR((points[3] - (0.7 * t - 0.1 * z)).norm(), 0, 1e-15);
}

// Points apart by no more than kFrictionBand beyond the deepest take part in the centre; a
// point just beyond it does not. An empty manifold's centre is the origin.
TEST(FrictionCentre, TheBandIsMeasuredFromTheDeepest) {
    const Vector3 n = Vector3::UnitY();
    Vector3 points[3] = {Vector3(0, 0, 0), Vector3(1, 0.01, 0), Vector3(0, 0.02, 1)};
    const real band = detail::kFrictionBand;
    const real depths[3] = {-0.005, -0.005 - band, -0.005 - band - 1e-6};
    EXPECT_NEAR((detail::frictionCentre(depths, 3, n, points) - Vector3(0.5, 0, 0)).norm(), 0, 1e-15);
    EXPECT_NEAR((points[2] - Vector3(0, 0, 1)).norm(), 0, 1e-15);
    EXPECT_EQ(detail::frictionCentre(depths, 0, n, points), Vector3::Zero());
}

}  // namespace
}  // namespace cyclone::test
