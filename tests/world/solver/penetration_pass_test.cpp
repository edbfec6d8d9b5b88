// The penetration pass (world/src/penetration_pass.cpp): each point's target pseudo-velocity
// from its depth beyond what the manifold may keep, the rows solved one after another on
// the pseudo-velocities four manifolds at a time, and with the carrier pass only the
// carried body moved.
#include <gtest/gtest.h>

#include <vector>

#include "solver/contact_solver.h"
#include "cube_contact.h"
#include "solver/schedule.h"
#include "solver/velocity_pass.h"
#include "solver/penetration_pass.h"

namespace cyclone::test {
namespace {

using detail::SolverBody;
using detail::SolverManifold;
using detail::SolverManifolds;

constexpr real kSlop = 0.005;
constexpr real kRate = 12;  // penetrationRecovery 0.2 at 60 Hz, per second

// The bodies, manifolds and frames of a scene, and one group of its manifolds.
struct PenetrationScene {
    std::vector<SolverBody> bodies{1};
    SolverManifolds manifolds;
    std::vector<detail::DepthFrame> frames;
    std::vector<detail::SolverGroup> groups{1};
    std::vector<detail::ManifoldBatch> wide;
    std::vector<detail::PenetrationBatch> pseudo;

    // A cube at rest on body `carrier` (cube_contact.h), its points `depth0` and `depth1`
    // deep: their anchors are (0, depth, 0) on A and 0 on B, and the manifold's frame takes
    // both along y from the same place. A moving carrier carries it.
    void addCube(int carrier, real depth0, real depth1) {
        SolverManifold m = addCubeOn(carrier, Vector3::Zero(), bodies);
        const real depths[2] = {depth0, depth1};
        for (int i = 0; i < 2; ++i) {
            m.points[i].localA = Vector3(0, depths[i], 0);
            m.points[i].localB = Vector3::Zero();
        }
        if (carrier != 0) m.carrier = detail::Carrier::A;
        manifolds.push_back(m);
        frames.push_back({Vector3::UnitY(), Vector3::UnitY(), 0});
    }
    void group(std::initializer_list<int> members) {
        for (int k : members) groups[0].manifold[groups[0].size++] = k;
    }
    // One penetration pass, the first of a sub-step. Returns whether a point had a target.
    bool pass(bool carried) {
        detail::loadBatches(bodies, manifolds, groups, false, wide, &pseudo);
        const detail::PseudoTargets targets{frames.data(), kSlop, kRate};
        return detail::solvePenetrationBatches(bodies, wide, pseudo, groups, carried, &targets);
    }
    Vector3 pv(int body) const { return detail::toVector3(bodies[body].pv); }
    Vector3 pw(int body) const { return detail::toVector3(bodies[body].pw); }
};

// A cube on the world, points `depth0` and `depth1` deep, alone in its group.
PenetrationScene cubeOnWorld(real depth0, real depth1) {
    PenetrationScene s;
    s.addCube(0, depth0, depth1);
    s.group({0});
    return s;
}

// A cube (body 2) carried by another (body 1, on the world), its points 0.02 and 0.01 m
// deep as in the first test below, its manifold alone in its group.
PenetrationScene carriedCube() {
    PenetrationScene s;
    s.addCube(0, 0, 0);
    s.addCube(1, 0.02, 0.01);
    s.group({1});
    return s;
}

// By hand, for a cube on the world with depths 0.02 and 0.01 m. The manifold may keep the
// slop only where all of it is that deep: allowed = min(0.005, 0.02, 0.01) = 0.005 m, so the
// targets are 12 * 0.015 = 0.18 and 12 * 0.005 = 0.06 m/s. With the rows' masses (0.4 kg)
// and coupling (-0.5 m/s per N s) of cube_contact.h, the first point takes 0.4 * 0.18 =
// 0.072 N s, which leaves the second at -0.036 m/s; it takes 0.4 * (0.06 + 0.036) = 0.0384
// N s. The cube: pv_y = 0.072 + 0.0384 = 0.1104 m/s, pw_z = 6 * 0.5 * (0.072 - 0.0384) =
// 0.1008 rad/s (rB x n is (0, 0, +-0.5)).
TEST(PseudoPass, TargetsComeFromTheDepthBeyondWhatTheManifoldMayKeep) {
    PenetrationScene s = cubeOnWorld(0.02, 0.01);
    EXPECT_TRUE(s.pass(false));
    EXPECT_NEAR(s.pv(1).y(), 0.1104, 1e-12);
    EXPECT_NEAR(s.pw(1).z(), 0.1008, 1e-12);
    EXPECT_NEAR(s.pv(1).x(), 0, 1e-15);
    EXPECT_NEAR(s.pw(1).x(), 0, 1e-15);
    EXPECT_EQ(s.pv(0), Vector3::Zero());  // the world is never written
}

// Both points 3 mm deep, within the slop: nothing to push, and the pass says so.
TEST(PseudoPass, ALevelContactWithinTheSlopIsLeftAlone) {
    PenetrationScene s = cubeOnWorld(0.003, 0.003);
    EXPECT_FALSE(s.pass(false));
    EXPECT_EQ(s.pv(1), Vector3::Zero());
    EXPECT_EQ(s.pw(1), Vector3::Zero());
}

// A tilt within the slop is corrected: depths 4 and 3 mm keep 3 mm, so only the first
// point has a target, 12 * 0.001 = 0.012 m/s. It takes 0.4 * 0.012 = 0.0048 N s, which
// leaves the second point at -0.0024 m/s: that one has no target and no impulse, so it
// does not pull back. pv_y = 0.0048 m/s, pw_z = 3 * 0.0048 = 0.0144 rad/s.
TEST(PseudoPass, ATiltWithinTheSlopIsCorrected) {
    PenetrationScene s = cubeOnWorld(0.004, 0.003);
    EXPECT_TRUE(s.pass(false));
    EXPECT_NEAR(s.pv(1).y(), 0.0048, 1e-12);
    EXPECT_NEAR(s.pw(1).z(), 0.0144, 1e-12);
}

// A cube carried by another cube, depths as in the first test. With the carrier pass
// the carrier stays where it is and the carried cube moves as it did on the immovable
// world: the same numbers. Without, both move: the carrier down.
TEST(PseudoPass, WithShockPropagationOnlyTheCarriedBodyMoves) {
    PenetrationScene s = carriedCube();
    EXPECT_TRUE(s.pass(true));
    EXPECT_EQ(s.pv(1), Vector3::Zero());
    EXPECT_EQ(s.pw(1), Vector3::Zero());
    EXPECT_NEAR(s.pv(2).y(), 0.1104, 1e-12);
    EXPECT_NEAR(s.pw(2).z(), 0.1008, 1e-12);

    PenetrationScene both = carriedCube();
    EXPECT_TRUE(both.pass(false));
    EXPECT_LT(both.pv(1).y(), 0);
    EXPECT_GT(both.pv(2).y(), 0);
    EXPECT_LT(both.pv(2).y(), 0.1104);  // the push is shared with the carrier
}

// Four cubes on the world in one group, one per lane, depths 0.005 + 0.015 s and 0.005 +
// 0.005 s for s = 1, 2, 0.5, 3: the targets, and so the whole pass, scale with s, and
// each cube gets the first test's numbers times s. A lane that read another's anchors,
// rows or bodies would not.
TEST(PseudoPass, EachLaneOfAGroupIsSolvedOnItsOwn) {
    const real scales[4] = {1, 2, 0.5, 3};
    PenetrationScene s;
    for (real k : scales) s.addCube(0, kSlop + 0.015 * k, kSlop + 0.005 * k);
    s.group({3, 2, 1, 0});  // lanes in another order than the manifolds
    EXPECT_TRUE(s.pass(false));
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(s.pv(k + 1).y(), 0.1104 * scales[k], 1e-12) << "cube " << k;
        EXPECT_NEAR(s.pw(k + 1).z(), 0.1008 * scales[k], 1e-12) << "cube " << k;
    }
}

}  // namespace
}  // namespace cyclone::test
