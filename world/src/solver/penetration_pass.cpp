#include "solver/penetration_pass.h"

#include <cstddef>

#include "solver/batch_velocities.h"

namespace cyclone::detail {

namespace {

// Lanes are given back through a reference, as in simd/vector4.h.

// Lane k of `out` is field(*x[k]).
template <class T, class Field>
CYCLONE_INLINE void gather(const T *const x[kWideLanes], Field field, Lanes &out) {
    out = Lanes{field(*x[0]), field(*x[1]), field(*x[2]), field(*x[3])};
}

// Four reals at any address aligned as a real, read as lanes by one instruction (a
// copy through memory made two half-width stores that the full-width load could not
// forward from: slow).
using UnalignedLanes = double __attribute__((vector_size(4 * sizeof(double)), aligned(alignof(double)), may_alias));

// Lane k of `out` holds the four reals at x[k].
CYCLONE_INLINE void gatherFour(const real *const x[kWideLanes], Lanes out[kWideLanes]) {
    const Lanes r0 = *reinterpret_cast<const UnalignedLanes *>(x[0]);
    const Lanes r1 = *reinterpret_cast<const UnalignedLanes *>(x[1]);
    const Lanes r2 = *reinterpret_cast<const UnalignedLanes *>(x[2]);
    const Lanes r3 = *reinterpret_cast<const UnalignedLanes *>(x[3]);
    transpose(r0, r1, r2, r3, out);
}

// Per lane: out = the larger of a and 0.
CYCLONE_INLINE void positivePart(const Lanes &a, Lanes &out) {
    const Lanes zero{};
    out = a > zero ? a : zero;
}

// Sets the group's targets from the depths of its points at `frames` and clears its
// impulses. The slop is left alone only where the whole manifold is that deep: a tilt
// (one side deeper than the other) is corrected even when it is below the slop, or it
// would never be, and a stack would lean on it. Returns whether any point has a target.
CYCLONE_INLINE bool setTargets(const SolverGroup &group, const PseudoTargets &targets, PenetrationBatch &p) {
    // A frame's seven reals as two rows of four, normalA and normalB.x, then normalB
    // and the offset: two transposes.
    static_assert(sizeof(DepthFrame) == 7 * sizeof(real), "DepthFrame: seven reals in a row");
    static const DepthFrame none{Vector3::Zero(), Vector3::Zero(), 0};
    const real *first[kWideLanes], *second[kWideLanes];
    for (int k = 0; k < kWideLanes; ++k) {
        const DepthFrame &f = k < group.size ? targets.frames[group.manifold[k]] : none;
        first[k] = f.normalA.data();
        second[k] = f.normalB.data();
    }
    Lanes columns[kWideLanes];
    gatherFour(first, columns);
    const WideVector normalA = {columns[0], columns[1], columns[2]};
    gatherFour(second, columns);
    const WideVector normalB = {columns[0], columns[1], columns[2]};
    const Lanes offset = columns[3];
    Lanes depth[kMaxManifoldPoints];
    LaneMask held[kMaxManifoldPoints];  // lanes whose manifold has point i
    Lanes shallowest = Lanes{} + targets.slop;
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        Lanes a, b;
        dotLanes(p.localA[i], normalA, a);
        dotLanes(p.localB[i], normalB, b);
        depth[i] = a - b + offset;
        held[i] = Lanes{} + real(i) < p.count;
        shallowest = held[i] && depth[i] < shallowest ? depth[i] : shallowest;
    }
    Lanes allowed;
    positivePart(shallowest, allowed);
    const Lanes zero{};
    LaneMask any{};
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        Lanes beyond;
        positivePart(depth[i] - allowed, beyond);
        p.target[i] = held[i] ? targets.recoveryRate * beyond : zero;
        p.impulse[i] = zero;
        any |= p.target[i] > zero;
    }
    return anyLane(any);
}

// The normal rows' effective masses, and their couplings (as ManifoldBatch::
// normalCoupling), through the bodies the carrier pass moves: the carried one where a
// lane has a carrier, else both. Worked out from the rows (SolverRow::carriedMass and
// RowCouplings of the carried side give the same but for rounding): the sweep's chain
// does not wait on them, and loading them cost more.
CYCLONE_INLINE void carriedRows(const ManifoldBatch &m, const PenetrationBatch &p, Lanes mass[kMaxManifoldPoints],
                                  Lanes coupling[kMaxManifoldPoints][kMaxManifoldPoints]) {
    const Lanes invMasses = m.invMassA * p.moveA + m.invMassB * p.moveB;
    const Lanes zero{};
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        WideVector angA, angB;  // IA^-1 (rA x n), IB^-1 (rB x n) of point i
        multiply(m.invInertiaA, m.points[i].row.rAxd, angA);
        multiply(m.invInertiaB, m.points[i].row.rBxd, angB);
        for (int j = 0; j < kMaxManifoldPoints; ++j) {
            const WideRow &at = m.points[j].row;
            Lanes a, b;
            dotLanes(at.rAxd, angA, a);
            dotLanes(at.rBxd, angB, b);
            coupling[i][j] = invMasses + (a * p.moveA + b * p.moveB);
        }
        const Lanes k = coupling[i][i];
        mass[i] = k > zero ? 1 / k : zero;
        coupling[i][i] = zero;
    }
}

// One group's normal rows on the pseudo-velocities, in solve order, each towards its
// target; a point with neither a target nor an impulse is left alone. As WideSweep
// (velocity_pass.cpp) does for the velocities: the normal velocities are read at the start
// and tracked through the couplings, and the impulses reach the bodies at the end.
template <bool kCarried>
CYCLONE_INLINE void solveGroup(std::vector<SolverBody> &bodies, const ManifoldBatch &m, PenetrationBatch &p) {
    WideVelocities<true> vel(bodies, m);
    const WideVector dv = {vel.vb.x - vel.va.x, vel.vb.y - vel.va.y, vel.vb.z - vel.va.z};
    const Lanes linear = m.normal.x * dv.x + m.normal.y * dv.y + m.normal.z * dv.z;
    Lanes vn[kMaxManifoldPoints];
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        const WideRow &row = m.points[i].row;
        vn[i] = linear + (row.rBxd.x * vel.wb.x - row.rAxd.x * vel.wa.x) +
                (row.rBxd.y * vel.wb.y - row.rAxd.y * vel.wa.y) + (row.rBxd.z * vel.wb.z - row.rAxd.z * vel.wa.z);
    }
    const Lanes zero{};
    Lanes carriedMass[kMaxManifoldPoints], carriedCoupling[kMaxManifoldPoints][kMaxManifoldPoints];
    if (kCarried) carriedRows(m, p, carriedMass, carriedCoupling);
    Lanes change[kMaxManifoldPoints];
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        const Lanes &mass = kCarried ? carriedMass[i] : m.points[i].mass;
        const Lanes *coupling = kCarried ? carriedCoupling[i] : m.normalCoupling[i];
        const LaneMask active = (p.target[i] > zero) | (p.impulse[i] != zero);
        const Lanes candidate = p.impulse[i] - mass * (vn[i] - p.target[i]);
        Lanes pushed;
        positivePart(candidate, pushed);
        const Lanes updated = active ? pushed : p.impulse[i];
        change[i] = updated - p.impulse[i];
        p.impulse[i] = updated;
        for (int j = 0; j < kMaxManifoldPoints; ++j) vn[j] += change[i] * coupling[j];
    }
    const Lanes total = (change[0] + change[1]) + (change[2] + change[3]);
    WideVector impulseA = {total * m.normal.x, total * m.normal.y, total * m.normal.z};
    WideVector impulseB = impulseA;
    // Each side's angular impulse, sum of impulse times (r x n), turned by its inverse
    // inertia once.
    WideVector leverA{}, leverB{};
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        addScaled(leverA, change[i], m.points[i].row.rAxd);
        addScaled(leverB, change[i], m.points[i].row.rBxd);
    }
    WideVector angularA, angularB;
    multiply(m.invInertiaA, leverA, angularA);
    multiply(m.invInertiaB, leverB, angularB);
    Lanes invMassA = m.invMassA, invMassB = m.invMassB;
    if (kCarried) {
        // A side that does not move gets nothing.
        invMassA *= p.moveA;
        invMassB *= p.moveB;
        angularA = {angularA.x * p.moveA, angularA.y * p.moveA, angularA.z * p.moveA};
        angularB = {angularB.x * p.moveB, angularB.y * p.moveB, angularB.z * p.moveB};
    }
    subtractScaled(vel.va, invMassA, impulseA);
    addScaled(vel.vb, invMassB, impulseB);
    vel.wa = {vel.wa.x - angularA.x, vel.wa.y - angularA.y, vel.wa.z - angularA.z};
    vel.wb = {vel.wb.x + angularB.x, vel.wb.y + angularB.y, vel.wb.z + angularB.z};
    vel.store(bodies, m);
}

// Whether any point of the group has a target or an impulse.
CYCLONE_INLINE bool pushes(const PenetrationBatch &p) {
    const Lanes zero{};
    LaneMask any{};
    for (int i = 0; i < kMaxManifoldPoints; ++i) any |= (p.target[i] > zero) | (p.impulse[i] != zero);
    return anyLane(any);
}

}  // namespace

CYCLONE_SIMD_CLONES
void loadPseudo(const SolverManifold *const m[kWideLanes], PenetrationBatch &out) {
    static const SolverPoint zeroPoint{};
    gather(m, [](const SolverManifold &x) { return real(x.count); }, out.count);
    // A point's localA and localB are six reals in a row, and a real follows them: two
    // rows of four, localA and localB.x, then localB and the next, transposed.
    static_assert(offsetof(SolverPoint, localB) == offsetof(SolverPoint, localA) + 3 * sizeof(real) &&
                      offsetof(SolverPoint, depth) == offsetof(SolverPoint, localB) + 3 * sizeof(real),
                  "SolverPoint: localA, localB and depth in a row");
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        const real *first[kWideLanes], *second[kWideLanes];
        for (int k = 0; k < kWideLanes; ++k) {
            const SolverPoint &p = i < m[k]->count ? m[k]->points[m[k]->order[i]] : zeroPoint;
            first[k] = p.localA.data();
            second[k] = p.localB.data();
        }
        Lanes columns[kWideLanes];
        gatherFour(first, columns);
        out.localA[i] = {columns[0], columns[1], columns[2]};
        gatherFour(second, columns);
        out.localB[i] = {columns[0], columns[1], columns[2]};
    }
    // Per lane: the carried side alone, or both.
    gather(m, [](const SolverManifold &x) { return real(x.carrier == Carrier::A ? 0 : 1); }, out.moveA);
    gather(m, [](const SolverManifold &x) { return real(x.carrier == Carrier::B ? 0 : 1); }, out.moveB);
}

CYCLONE_SIMD_CLONES
bool solvePenetrationBatches(std::vector<SolverBody> &bodies, const std::vector<ManifoldBatch> &wide,
                     std::vector<PenetrationBatch> &pseudo, const std::vector<SolverGroup> &groups, bool carried,
                     const PseudoTargets *targets) {
    bool anyTarget = false;
    for (std::size_t g = 0; g < wide.size(); ++g) {
        PenetrationBatch &p = pseudo[g];
        if (targets ? !setTargets(groups[g], *targets, p) : !pushes(p)) continue;
        anyTarget = true;
        if (carried) solveGroup<true>(bodies, wide[g], p);
        else solveGroup<false>(bodies, wide[g], p);
    }
    return anyTarget;
}

}  // namespace cyclone::detail
