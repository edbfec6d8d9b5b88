#include "solver/rolling_resistance.h"

#include <algorithm>
#include <cmath>

namespace cyclone::detail {

bool makeResistanceRows(const std::vector<SolverBody> &bodies, const SolverManifold &m, int slot, real rolling,
                        real spinning, ResistanceRow &row) {
    if (!needsResistance(m, rolling, spinning)) return false;
    const bool rolls = rolling > 0 && m.count <= 2;
    const bool spins = spinning > 0 && m.twistRadius == 0;
    const SolverBody &a = bodies[m.a];
    const SolverBody &b = bodies[m.b];
    row = ResistanceRow();
    row.slot = slot;
    row.a = m.a;
    row.b = m.b;
    row.axis[0] = m.tangent[0];
    row.axis[1] = m.tangent[1];
    row.axis[2] = m.normal;
    row.rolling = rolls ? rolling : 0;
    row.spinning = spins ? spinning : 0;
    for (int k = 0; k < 3; ++k) {
        const bool used = k < 2 ? rolls : spins;
        row.angA[k] = a.invInertia * row.axis[k];
        row.angB[k] = b.invInertia * row.axis[k];
        const real k11 = row.axis[k].dot(row.angA[k] + row.angB[k]);
        row.mass[k] = used && k11 > 0 ? 1 / k11 : 0;
    }
    return row.mass[0] > 0 || row.mass[1] > 0 || row.mass[2] > 0;
}

void beginResistance(const SolverManifolds &manifolds, ResistanceRow &row) {
    const SolverManifold &m = manifolds[row.slot];
    real normal = 0;
    for (int i = 0; i < m.count; ++i) normal += m.points[i].normal.impulse;
    row.limit = std::max(normal, real(0));
    row.impulse.setZero();
}

void solveResistanceRow(std::vector<SolverBody> &bodies, ResistanceRow &row) {
    if (row.limit == 0) return;
    SolverBody &a = bodies[row.a];
    SolverBody &b = bodies[row.b];
    Vector3 wa = toVector3(a.w);
    Vector3 wb = toVector3(b.w);
    const Vector3 old = row.impulse;
    Vector3 next = old;
    // Rolling: the two tangents' impulses together within a disc, as a patch's
    // tangent friction is limited within a cone.
    if (row.rolling > 0) {
        for (int k = 0; k < 2; ++k) next[k] -= row.mass[k] * row.axis[k].dot(wb - wa);
        // The squares decide (std::hypot is a slow library call); the length of a
        // clamped impulse is taken as before.
        const real limit = row.rolling * row.limit;
        if (next[0] * next[0] + next[1] * next[1] > limit * limit) {
            const real length = std::hypot(next[0], next[1]);
            if (length > limit) {
                next[0] *= limit / length;
                next[1] *= limit / length;
            }
        }
    }
    if (row.spinning > 0) {
        const real limit = row.spinning * row.limit;
        next[2] = std::clamp(next[2] - row.mass[2] * row.axis[2].dot(wb - wa), -limit, limit);
    }
    const Vector3 change = next - old;
    row.impulse = next;
    for (int k = 0; k < 3; ++k) {
        wa -= change[k] * row.angA[k];
        wb += change[k] * row.angB[k];
    }
    // The immovable world (entry 0) keeps zero velocities (its inverse inertia is zero):
    // it is not written, so that two threads may read it at once (threads/ordered_shares.h).
    if (row.a != 0) setLanes(a.w, wa);
    if (row.b != 0) setLanes(b.w, wb);
}

void solveResistance(std::vector<SolverBody> &bodies, std::vector<ResistanceRow> &rows) {
    for (ResistanceRow &row : rows) solveResistanceRow(bodies, row);
}

}  // namespace cyclone::detail
