// A solver manifold for the solver's unit tests, worked out by hand in them: a cube on
// two points of an edge each side.
#pragma once

#include <vector>

#include "solver/contact_solver.h"

namespace cyclone::test {

/// Adds a 1 kg unit cube (inertia 1/6 kg m^2 about each axis) moving at `velocity` to
/// `bodies`, and returns its manifold with body `carrier` (0: the immovable world): two
/// points of its lower face's edges, (+0.5, 0, 0) and (-0.5, 0, 0), with the cube's centre
/// at (0, 0.5, 0) and the carrier's at (0, -0.5, 0), so rB = (+-0.5, -0.5, 0) and rA =
/// (+-0.5, 0.5, 0); normal +y from the carrier (A) to the cube (B); frictionless. Each
/// row's effective mass against the world is 1 / (1 + 0.5 * 6 * 0.5) = 0.4 kg (rB x n is
/// (0, 0, +-0.5)), and an impulse on one point changes the other's normal velocity by
/// 1 - 0.5 * 6 * 0.5 = -0.5 m/s per N s.
inline detail::SolverManifold addCubeOn(int carrier, const Vector3 &velocity, std::vector<detail::SolverBody> &bodies) {
    detail::SolverBody cube;
    detail::setLanes(cube.v, velocity);
    cube.invMass = 1;
    cube.invInertia = Matrix3::Identity() * 6;
    detail::SolverManifold m;
    m.a = carrier;
    m.b = static_cast<int>(bodies.size());
    m.count = 2;
    m.normal = Vector3::UnitY();
    detail::tangentBasis(m.normal, m.tangent[0], m.tangent[1]);
    detail::prepareDirections(m);
    const Vector3 points[2] = {Vector3(0.5, 0, 0), Vector3(-0.5, 0, 0)};
    const Vector3 centreA(0, -0.5, 0), centreB(0, 0.5, 0);
    for (int i = 0; i < 2; ++i) detail::prepareRows(bodies[carrier], cube, points[i] - centreA, points[i] - centreB, m, m.points[i]);
    detail::prepareFrictionRows(bodies[carrier], cube, points, Vector3::Zero(), centreA, centreB, m);
    detail::prepareCouplings(bodies[carrier], cube, m);
    bodies.push_back(cube);
    return m;
}

}  // namespace cyclone::test
