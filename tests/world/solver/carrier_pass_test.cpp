// The carrier pass's runs (world/src/carrier_pass.h): each carried body swept against its
// carriers held immovable, four runs at a time, one per lane.
#include <gtest/gtest.h>

#include <vector>

#include "solver/contact_solver.h"
#include "solver/carrier_pass.h"

namespace cyclone::test {
namespace {

using detail::SolverBody;
using detail::SolverManifold;
using detail::SolverManifolds;

// A 1 kg unit cube (inertia 1/6 kg m^2 about each axis) whose centre is 1 m above its
// carrier's, resting on it, frictionless, at two points of its lower face's edges:
// (+-0.5, 0.5, 0) from the carrier's centre. With `cubeIsA` the manifold lists the cube
// first and its normal points down, from the cube to the carrier; otherwise up, from the
// carrier to the cube. Adds the manifold and returns its index.
int addResting(std::vector<SolverBody> &bodies, SolverManifolds &manifolds, int cube, int carrier,
               const Vector3 &carrierCentre, bool cubeIsA) {
    SolverManifold m;
    m.a = cubeIsA ? cube : carrier;
    m.b = cubeIsA ? carrier : cube;
    m.carrier = cubeIsA ? detail::Carrier::B : detail::Carrier::A;
    m.count = 2;
    m.normal = cubeIsA ? Vector3(0, -1, 0) : Vector3::UnitY();
    detail::tangentBasis(m.normal, m.tangent[0], m.tangent[1]);
    detail::prepareDirections(m);
    const Vector3 cubeCentre = carrierCentre + Vector3(0, 1, 0);
    const Vector3 points[2] = {carrierCentre + Vector3(0.5, 0.5, 0), carrierCentre + Vector3(-0.5, 0.5, 0)};
    const Vector3 &centreA = cubeIsA ? cubeCentre : carrierCentre;
    const Vector3 &centreB = cubeIsA ? carrierCentre : cubeCentre;
    const SolverBody &a = bodies[m.a];
    const SolverBody &b = bodies[m.b];
    for (int i = 0; i < 2; ++i) detail::prepareRows(a, b, points[i] - centreA, points[i] - centreB, m, m.points[i]);
    detail::prepareFrictionRows(a, b, points, carrierCentre + Vector3(0, 0.5, 0), centreA, centreB, m);
    detail::prepareCouplings(a, b, m);
    detail::prepareCarriedMasses(bodies, m);
    manifolds.push_back(m);
    return static_cast<int>(manifolds.size()) - 1;
}

// A body of 1 kg and inertia 1/6 kg m^2 moving at v.
int addBody(std::vector<SolverBody> &bodies, const Vector3 &v) {
    SolverBody body;
    detail::setLanes(body.v, v);
    body.invMass = 1;
    body.invInertia = Matrix3::Identity() * 6;
    bodies.push_back(body);
    return static_cast<int>(bodies.size()) - 1;
}

// Each manifold its own run, all on one level.
detail::CarrierRuns oneRunEach(int count) {
    detail::CarrierRuns runs;
    for (int r = 0; r <= count; ++r) runs.start.push_back(r);
    for (int r = 0; r < count; ++r) runs.manifolds.push_back(r);
    runs.levelStart = {0, count};
    return runs;
}

// The pass stops a run once a sweep changes the body's velocity by less than
// kCarrierTolerance; the error left is of that order.
constexpr real kLeft = 10 * detail::kCarrierTolerance;

// Falling at 1 m/s onto the immovable world: the two points stop the cube and its turning,
// which takes 1 N s in all, and by symmetry half of it at each. The world is a static
// carrier, so the impulses are the true problem's and are kept.
TEST(SupportPass, StopsACubeOnTheWorldAndKeepsItsImpulses) {
    for (bool cubeIsA : {false, true}) {
        std::vector<SolverBody> bodies(1);
        SolverManifolds manifolds;
        const int cube = addBody(bodies, Vector3(0, -1, 0));
        addResting(bodies, manifolds, cube, 0, Vector3(0, -0.5, 0), cubeIsA);
        const detail::CarrierRuns runs = oneRunEach(1);
        detail::CarrierPassScratch scratch;
        const int run = 0;
        detail::solveCarriedRuns(bodies, manifolds, runs, &run, 1, false, scratch);
        const Vector3 v = detail::toVector3(bodies[cube].v);
        const Vector3 w = detail::toVector3(bodies[cube].w);
        EXPECT_NEAR(v.y(), 0, kLeft) << "cube is A: " << cubeIsA;
        EXPECT_NEAR(w.z(), 0, kLeft) << "cube is A: " << cubeIsA;
        EXPECT_EQ(v.x(), 0);
        EXPECT_EQ(w.x(), 0);
        EXPECT_NEAR(manifolds[0].points[0].normal.impulse, 0.5, kLeft);
        EXPECT_NEAR(manifolds[0].points[1].normal.impulse, 0.5, kLeft);
        EXPECT_EQ(detail::toVector3(bodies[0].v), Vector3::Zero());  // the world is never written
    }
}

// On a carrier rising at 0.5 m/s, a cube at rest is brought to the carrier's velocity at
// the contacts: 0.5 m/s up, not turning. The carrier is held immovable, so it keeps its
// velocity; it moves, so the run's impulses are dropped and the manifold keeps those the
// velocity passes left.
TEST(SupportPass, CarriesACubeWithAMovingCarrierAndDropsItsImpulses) {
    for (bool cubeIsA : {false, true}) {
        std::vector<SolverBody> bodies(1);
        SolverManifolds manifolds;
        const int carrier = addBody(bodies, Vector3(0, 0.5, 0));
        const int cube = addBody(bodies, Vector3::Zero());
        const int m = addResting(bodies, manifolds, cube, carrier, Vector3::Zero(), cubeIsA);
        manifolds[m].points[0].normal.impulse = 0.3;
        manifolds[m].points[1].normal.impulse = 0.2;
        const detail::CarrierRuns runs = oneRunEach(1);
        detail::CarrierPassScratch scratch;
        const int run = 0;
        detail::solveCarriedRuns(bodies, manifolds, runs, &run, 1, false, scratch);
        EXPECT_NEAR(detail::toVector3(bodies[cube].v).y(), 0.5, kLeft) << "cube is A: " << cubeIsA;
        EXPECT_NEAR(detail::toVector3(bodies[cube].w).z(), 0, kLeft) << "cube is A: " << cubeIsA;
        EXPECT_EQ(detail::toVector3(bodies[carrier].v), Vector3(0, 0.5, 0));
        EXPECT_EQ(detail::toVector3(bodies[carrier].w), Vector3::Zero());
        EXPECT_EQ(manifolds[m].points[0].normal.impulse, 0.3);
        EXPECT_EQ(manifolds[m].points[1].normal.impulse, 0.2);
    }
}

// Five cubes falling at different speeds need different numbers of sweeps to settle:
// solved four and then one at a time, or each alone, every cube must end with the same
// velocities and impulses to the last bit. A lane that went on taking impulses after its
// own run had stopped, or that read another lane's rows, would differ.
TEST(SupportPass, EachRunOfAGroupIsSolvedAsIfAlone) {
    const real speeds[] = {1, 2, 0.5, 3, 1.5};
    const auto build = [&](std::vector<SolverBody> &bodies, SolverManifolds &manifolds) {
        bodies.assign(1, SolverBody());
        manifolds.clear();
        for (int k = 0; k < 5; ++k) {
            const int cube = addBody(bodies, Vector3(0, -speeds[k], 0));
            addResting(bodies, manifolds, cube, 0, Vector3(3.0 * k, -0.5, 0), k % 2 == 1);
        }
    };
    const detail::CarrierRuns runs = oneRunEach(5);
    detail::CarrierPassScratch scratch;
    std::vector<SolverBody> together, alone;
    SolverManifolds togetherManifolds, aloneManifolds;
    build(together, togetherManifolds);
    build(alone, aloneManifolds);
    const int all[] = {0, 1, 2, 3, 4};
    detail::solveCarriedRuns(together, togetherManifolds, runs, all, 4, true, scratch);
    detail::solveCarriedRuns(together, togetherManifolds, runs, all + 4, 1, true, scratch);
    for (int r = 0; r < 5; ++r) detail::solveCarriedRuns(alone, aloneManifolds, runs, &all[r], 1, true, scratch);
    for (int k = 0; k < 5; ++k) {
        const int body = k + 1;
        EXPECT_EQ(detail::toVector3(together[body].v), detail::toVector3(alone[body].v)) << "cube " << k;
        EXPECT_EQ(detail::toVector3(together[body].w), detail::toVector3(alone[body].w)) << "cube " << k;
        for (int i = 0; i < 2; ++i)
            EXPECT_EQ(togetherManifolds[k].points[i].normal.impulse, aloneManifolds[k].points[i].normal.impulse)
                << "cube " << k << ", point " << i;
        // And each one settled: stopped, with its own momentum in the two points.
        EXPECT_NEAR(detail::toVector3(alone[body].v).y(), 0, kLeft * speeds[k]) << "cube " << k;
        EXPECT_NEAR(aloneManifolds[k].points[0].normal.impulse + aloneManifolds[k].points[1].normal.impulse,
                    speeds[k], kLeft * speeds[k])
            << "cube " << k;
    }
}

// A 1 kg body (inertia 1/6 kg m^2 about each axis) lies across two immovable carriers,
// four corners on each (x from -1 to -0.2 m and from 0.2 to 1 m, z = +-0.5 m, its centre
// 0.5 m above them), friction 0.5, falling at 0.1 m/s. One corner asks to separate at
// 1 cm/s: no velocity meets all eight corners and the friction at once. Sweeps that
// alternated their direction ended in a cycle of two states here, each sweep moving the
// body by the same amount, and only a test of the states two sweeps apart stopped them
// short of the cap. Sweeps in one direction (either) settle: the run stops by its
// one-sweep test, before the cap, with the body no longer falling.
TEST(SupportPass, SweepsInOneDirectionSettleWhereNoVelocityMeetsEveryCorner) {
    std::vector<SolverBody> bodies(1);
    const int body = addBody(bodies, Vector3(0, -0.1, 0));
    SolverManifolds manifolds;
    const Vector3 centre(0, 0.5, 0);
    for (const real x : {-0.6, 0.6}) {
        SolverManifold m;
        m.a = 0;
        m.b = body;
        m.carrier = detail::Carrier::A;
        m.count = 4;
        m.normal = Vector3::UnitY();
        detail::tangentBasis(m.normal, m.tangent[0], m.tangent[1]);
        detail::prepareDirections(m);
        const Vector3 points[4] = {Vector3(x + 0.4, 0, 0.5), Vector3(x - 0.4, 0, 0.5), Vector3(x - 0.4, 0, -0.5),
                                   Vector3(x + 0.4, 0, -0.5)};
        for (int i = 0; i < 4; ++i)
            detail::prepareRows(bodies[0], bodies[body], points[i], points[i] - centre, m, m.points[i]);
        detail::prepareFrictionRows(bodies[0], bodies[body], points, Vector3(x, 0, 0), Vector3::Zero(), centre, m);
        detail::prepareCouplings(bodies[0], bodies[body], m);
        m.friction = 0.5;
        detail::prepareCarriedMasses(bodies, m);
        manifolds.push_back(m);
    }
    manifolds[1].points[0].velocityBias = 0.01;
    detail::CarrierRuns runs;
    runs.start = {0, 2};
    runs.manifolds = {0, 1};
    runs.levelStart = {0, 1};
    const int run = 0;
    for (const bool reverse : {false, true}) {
        std::vector<SolverBody> fresh = bodies;
        SolverManifolds freshManifolds = manifolds;
        detail::CarrierPassScratch scratch;
        detail::solveCarriedRuns(fresh, freshManifolds, runs, &run, 1, reverse, scratch);
        EXPECT_LT(scratch.sweeps, detail::kCarrierSweeps) << "reverse " << reverse;
        // It was stopped: it no longer falls at 0.1 m/s, within the separating corner's 1 cm/s.
        EXPECT_GT(detail::toVector3(fresh[body].v).y(), -0.01) << "reverse " << reverse;
    }
}

}  // namespace
}  // namespace cyclone::test
