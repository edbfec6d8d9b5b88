// The penetration pass (world/src/wide_pseudo.cpp): each point's target pseudo-velocity
// from its depth beyond what the manifold may keep, the rows solved one after another on
// the pseudo-velocities four manifolds at a time, and with shock propagation only the
// carried body moved.
#include <gtest/gtest.h>

#include <vector>

#include "contact_solver.h"
#include "solver_schedule.h"
#include "wide_pass.h"
#include "wide_pseudo.h"

namespace cyclone::test {
namespace {

using detail::SolverBody;
using detail::SolverManifold;

constexpr real kSlop = 0.005;
constexpr real kRate = 12;  // penetrationRecovery 0.2 at 60 Hz, per second

// A 1 kg unit cube (inertia 1/6 kg m^2 about each axis) resting on body `carrier` (0: the
// immovable world; else a 1 kg cube like it), frictionless, at two points of its lower
// face's edges: rB = (+0.5, -0.5, 0) and (-0.5, -0.5, 0), rA = (+-0.5, +0.5, 0), normal +y
// from A to the cube (B). The points' depths are `depth0` and `depth1`: their anchors are
// (0, depth, 0) on A and 0 on B, and the manifold's frame takes both along y from the
// same place. Adds the cube's body, its manifold and that frame.
void addCube(int carrier, real depth0, real depth1, std::vector<SolverBody> &bodies,
             std::vector<SolverManifold> &manifolds, std::vector<detail::DepthFrame> &frames) {
    SolverBody cube;
    cube.invMass = 1;
    cube.invInertia = Matrix3::Identity() * 6;
    SolverManifold m;
    m.a = carrier;
    m.b = static_cast<int>(bodies.size());
    m.count = 2;
    m.normal = Vector3::UnitY();
    detail::tangentBasis(m.normal, m.tangent[0], m.tangent[1]);
    detail::prepareDirections(m);
    const Vector3 points[2] = {Vector3(0.5, 0, 0), Vector3(-0.5, 0, 0)};
    const Vector3 centreA(0, -0.5, 0), centreB(0, 0.5, 0);
    const real depths[2] = {depth0, depth1};
    for (int i = 0; i < 2; ++i) {
        detail::prepareRows(bodies[carrier], cube, points[i] - centreA, points[i] - centreB, m, m.points[i]);
        m.points[i].localA = Vector3(0, depths[i], 0);
        m.points[i].localB = Vector3::Zero();
    }
    detail::prepareFrictionRows(bodies[carrier], cube, points, centreA, centreB, m);
    detail::prepareCouplings(bodies[carrier], cube, m);
    if (carrier != 0) m.support = detail::kASupportsB;
    bodies.push_back(cube);
    manifolds.push_back(m);
    frames.push_back({Vector3::UnitY(), Vector3::UnitY(), 0});
}

// The bodies, manifolds and frames of a scene, and one group of its manifolds.
struct Scene {
    std::vector<SolverBody> bodies{1};
    std::vector<SolverManifold> manifolds;
    std::vector<detail::DepthFrame> frames;
    std::vector<detail::SolverGroup> groups{1};
    std::vector<detail::WideManifold> wide;
    std::vector<detail::WidePseudo> pseudo;

    void group(std::initializer_list<int> members) {
        for (int k : members) groups[0].manifold[groups[0].size++] = k;
    }
    // One penetration pass, the first of a sub-step. Returns whether a point had a target.
    bool pass(bool support) {
        detail::loadWide(bodies, manifolds, groups, false, wide, {&pseudo, support});
        const detail::PseudoTargets targets{frames.data(), kSlop, kRate};
        return detail::solveWidePseudo(bodies, wide, pseudo, groups, support, &targets);
    }
    Vector3 pv(int body) const { return detail::toVector3(bodies[body].pv); }
    Vector3 pw(int body) const { return detail::toVector3(bodies[body].pw); }
};

// By hand, for a cube on the world with depths 0.02 and 0.01 m. The manifold may keep the
// slop only where all of it is that deep: allowed = min(0.005, 0.02, 0.01) = 0.005 m, so the
// targets are 12 * 0.015 = 0.18 and 12 * 0.005 = 0.06 m/s. Each row's effective mass is
// 1 / (1 + 0.5 * 6 * 0.5) = 0.4 kg and an impulse on one point changes the other's normal
// velocity by 1 - 0.5 * 6 * 0.5 = -0.5 m/s per N s. The first point takes 0.4 * 0.18 =
// 0.072 N s, which leaves the second at -0.036 m/s; it takes 0.4 * (0.06 + 0.036) = 0.0384
// N s. The cube: pv_y = 0.072 + 0.0384 = 0.1104 m/s, pw_z = 6 * 0.5 * (0.072 - 0.0384) =
// 0.1008 rad/s (rB x n is (0, 0, +-0.5)).
TEST(PseudoPass, TargetsComeFromTheDepthBeyondWhatTheManifoldMayKeep) {
    Scene s;
    addCube(0, 0.02, 0.01, s.bodies, s.manifolds, s.frames);
    s.group({0});
    EXPECT_TRUE(s.pass(false));
    EXPECT_NEAR(s.pv(1).y(), 0.1104, 1e-12);
    EXPECT_NEAR(s.pw(1).z(), 0.1008, 1e-12);
    EXPECT_NEAR(s.pv(1).x(), 0, 1e-15);
    EXPECT_NEAR(s.pw(1).x(), 0, 1e-15);
    EXPECT_EQ(s.pv(0), Vector3::Zero());  // the world is never written
}

// Both points 3 mm deep, within the slop: nothing to push, and the pass says so.
TEST(PseudoPass, ALevelContactWithinTheSlopIsLeftAlone) {
    Scene s;
    addCube(0, 0.003, 0.003, s.bodies, s.manifolds, s.frames);
    s.group({0});
    EXPECT_FALSE(s.pass(false));
    EXPECT_EQ(s.pv(1), Vector3::Zero());
    EXPECT_EQ(s.pw(1), Vector3::Zero());
}

// A tilt within the slop is corrected: depths 4 and 3 mm keep 3 mm, so only the first
// point has a target, 12 * 0.001 = 0.012 m/s. It takes 0.4 * 0.012 = 0.0048 N s, which
// leaves the second point at -0.0024 m/s: that one has no target and no impulse, so it
// does not pull back. pv_y = 0.0048 m/s, pw_z = 3 * 0.0048 = 0.0144 rad/s.
TEST(PseudoPass, ATiltWithinTheSlopIsCorrected) {
    Scene s;
    addCube(0, 0.004, 0.003, s.bodies, s.manifolds, s.frames);
    s.group({0});
    EXPECT_TRUE(s.pass(false));
    EXPECT_NEAR(s.pv(1).y(), 0.0048, 1e-12);
    EXPECT_NEAR(s.pw(1).z(), 0.0144, 1e-12);
}

// A cube carried by another cube, depths as in the first test. With shock propagation
// the carrier stays where it is and the carried cube moves as it did on the immovable
// world: the same numbers. Without, both move: the carrier down.
TEST(PseudoPass, WithShockPropagationOnlyTheCarriedBodyMoves) {
    Scene s;
    addCube(0, 0, 0, s.bodies, s.manifolds, s.frames);  // body 1, on the world, not penetrating
    addCube(1, 0.02, 0.01, s.bodies, s.manifolds, s.frames);  // body 2 on body 1
    s.group({1});
    EXPECT_TRUE(s.pass(true));
    EXPECT_EQ(s.pv(1), Vector3::Zero());
    EXPECT_EQ(s.pw(1), Vector3::Zero());
    EXPECT_NEAR(s.pv(2).y(), 0.1104, 1e-12);
    EXPECT_NEAR(s.pw(2).z(), 0.1008, 1e-12);

    Scene both;
    addCube(0, 0, 0, both.bodies, both.manifolds, both.frames);
    addCube(1, 0.02, 0.01, both.bodies, both.manifolds, both.frames);
    both.group({1});
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
    Scene s;
    for (real k : scales) addCube(0, kSlop + 0.015 * k, kSlop + 0.005 * k, s.bodies, s.manifolds, s.frames);
    s.group({3, 2, 1, 0});  // lanes in another order than the manifolds
    EXPECT_TRUE(s.pass(false));
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(s.pv(k + 1).y(), 0.1104 * scales[k], 1e-12) << "cube " << k;
        EXPECT_NEAR(s.pw(k + 1).z(), 0.1008 * scales[k], 1e-12) << "cube " << k;
    }
}

}  // namespace
}  // namespace cyclone::test
