// Rolling and spinning resistance: angular rows between a manifold's two bodies that
// oppose their relative turning, rolling about the contact plane's tangents and spinning
// about the normal, each limited to a length (Material::rollingFriction,
// spinningFriction) times the manifold's normal impulse.
//
// Design note. Only manifolds that need them get rows, listed apart from the manifolds so
// that the batched velocity passes are unchanged and a scene without them pays nothing
// there: rolling rows for point and line contacts (one or two points; a face's three or
// more points already hold it from rolling), a spinning row where the patch has no twist
// row (a single point). The rows are solved one after another, after each velocity pass,
// on the calling thread, in the solve order of their manifolds: the same numbers for any
// thread count. Their limit is the normal impulse the manifold held when the sub-step
// began (its warm start), as the velocity passes keep the current one in their own copy.
#pragma once

#include <vector>

#include "solver/contact_solver.h"

namespace cyclone::detail {

/// The resistance rows of one manifold.
struct ResistanceRow {
    int slot = 0;  ///< The manifold's solver slot.
    int a = 0;     ///< Solver bodies (0 = the immovable world).
    int b = 0;
    Vector3 axis[3];            ///< tangent[0], tangent[1] (rolling), the normal (spinning).
    real mass[3] = {};          ///< Effective angular mass about each axis, kg m^2 (0: no row).
    Vector3 angA[3], angB[3];   ///< IA^-1 axis, IB^-1 axis.
    real rolling = 0;           ///< Rolling friction length, m (0: no rolling rows).
    real spinning = 0;          ///< Spinning friction length, m (0: no spinning row).
    real limit = 0;             ///< Normal impulse the limits scale, N s (per sub-step).
    Vector3 impulse = Vector3::Zero();  ///< Accumulated along the axes, N m s.
};

/// Whether manifold `m` may need rows: rolling friction on a contact of one or two points
/// (a face rests on its own), spinning friction where there is no twist row.
inline bool needsResistance(const SolverManifold &m, real rolling, real spinning) {
    return (rolling > 0 && m.count <= 2) || (spinning > 0 && m.twistRadius == 0);
}

/// Makes the rows of manifold `slot` (after its Jacobians) into `row`; false when it needs
/// none (`row` is then not to be solved). `rolling` and `spinning` are the pair's
/// lengths, m.
bool makeResistanceRows(const std::vector<SolverBody> &bodies, const SolverManifold &m, int slot, real rolling,
                        real spinning, ResistanceRow &row);
/// At a sub-step's start: the row's limit from its manifold's normal impulses, its
/// accumulated impulse cleared.
void beginResistance(const SolverManifolds &manifolds, ResistanceRow &row);
/// Solves one row: its impulses within their limits, its bodies' spins changed.
void solveResistanceRow(std::vector<SolverBody> &bodies, ResistanceRow &row);
/// One pass over the rows, in order.
void solveResistance(std::vector<SolverBody> &bodies, std::vector<ResistanceRow> &rows);

}  // namespace cyclone::detail
