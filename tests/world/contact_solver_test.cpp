// The contact solver's pass over one manifold (world/src/contact_solver.cpp): its rows are
// solved one after another, each against the velocities the rows before it left, as
// Gauss-Seidel does, although the bodies' velocities are read once and each impulse
// reaches the later rows through the manifold's couplings.
#include <gtest/gtest.h>

#include <vector>

#include "contact_solver.h"
#include "solver_schedule.h"

namespace cyclone::test {
namespace {

using detail::SolverBody;
using detail::SolverManifold;

// A 1 kg unit cube (inertia 1/6 kg m^2 about each axis) falling at 1 m/s onto the
// immovable world, frictionless, touching it at two points of its lower face's edges:
// rB = (+0.5, -0.5, 0) and (-0.5, -0.5, 0), normal +y from the world (A) to the cube (B).
struct FallingCube {
    std::vector<SolverBody> bodies{2};
    std::vector<SolverManifold> manifolds{1};
    std::vector<detail::SolverGroup> groups{1};

    FallingCube() {
        SolverBody &cube = bodies[1];
        detail::setLanes(cube.v, Vector3(0, -1, 0));
        cube.invMass = 1;
        cube.invInertia = Matrix3::Identity() * 6;
        SolverManifold &m = manifolds[0];
        m.a = 0;
        m.b = 1;
        m.count = 2;
        m.normal = Vector3::UnitY();
        detail::tangentBasis(m.normal, m.tangent[0], m.tangent[1]);
        detail::prepareDirections(m);
        const Vector3 points[2] = {Vector3(0.5, 0, 0), Vector3(-0.5, 0, 0)};
        const Vector3 centre(0, 0.5, 0);
        for (int i = 0; i < 2; ++i)
            detail::prepareRows(bodies[0], cube, points[i], points[i] - centre, m, m.points[i]);
        detail::prepareFrictionRows(bodies[0], cube, points, Vector3::Zero(), centre, m);
        detail::prepareCouplings(bodies[0], cube, m);
        groups[0].manifold[0] = 0;
        groups[0].size = 1;
    }

    void pass(bool reverse) { detail::solveVelocities(bodies, manifolds, groups, reverse); }
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

// Renumbering the points (as World does when a kept manifold's points come in another
// order) carries their rows and couplings along: a forward pass over the renumbered
// manifold is the reverse pass over the original one.
TEST(ContactSolverPass, RenumberedPointsKeepTheirRowsAndCouplings) {
    FallingCube cube;
    const int from[2] = {1, 0};
    detail::renumberPointRows(cube.manifolds[0], from);
    cube.pass(false);
    cube.expect(0.4, 0.48, -0.12, 0.24, 1e-12);  // point 0 was point 1
}

// Over many passes the two points share the cube's momentum equally and both come to
// rest: 0.5 N s each, v = 0, w = 0.
TEST(ContactSolverPass, PassesConvergeToTheRestingSolution) {
    FallingCube cube;
    for (int pass = 0; pass < 60; ++pass) cube.pass((pass & 1) != 0);
    cube.expect(0.5, 0.5, 0, 0, 1e-9);
}

}  // namespace
}  // namespace cyclone::test
