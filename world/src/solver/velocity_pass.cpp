#include "solver/velocity_pass.h"

#include "solver/patch_friction.h"
#include "solver/penetration_pass.h"
#include "solver/batch_velocities.h"

namespace cyclone::detail {

static_assert(kWidePatchPoints == kMaxManifoldPoints, "patch_friction.h couples every point of a patch");

namespace {

// Four manifolds' rows side by side.
CYCLONE_INLINE void loadRow(const SolverRow &r0, const SolverRow &r1, const SolverRow &r2, const SolverRow &r3,
                            WideRow &out) {
    transposeIn(r0.rAxd, r1.rAxd, r2.rAxd, r3.rAxd, out.rAxd);
    transposeIn(r0.rBxd, r1.rBxd, r2.rBxd, r3.rBxd, out.rBxd);
}

// The inverse inertias of the bodies `index` of four lanes, as WideSymmetric holds them.
CYCLONE_INLINE void loadInertia(const std::vector<SolverBody> &bodies, const int index[kWideLanes],
                                WideSymmetric &out) {
    const real *m[kWideLanes];  // column by column (Eigen's default)
    for (int k = 0; k < kWideLanes; ++k) m[k] = bodies[index[k]].invInertia.data();
    const auto entry = [&](int e, Lanes &lanes) __attribute__((always_inline)) {
        lanes = Lanes{m[0][e], m[1][e], m[2][e], m[3][e]};
    };
    entry(0, out.xx), entry(1, out.yx), entry(2, out.zx), entry(4, out.yy), entry(5, out.zy), entry(8, out.zz);
}

// Per lane: out = d . (vb - va) + rBxd . wb - rAxd . wa, summed x + y + z as sum3 does.
CYCLONE_INLINE void relative(const WideVector &d, const WideVector &va, const WideVector &vb, const WideRow &row,
                             const WideVector &wa, const WideVector &wb, Lanes &out) {
    const Lanes x = d.x * (vb.x - va.x) + row.rBxd.x * wb.x - row.rAxd.x * wa.x;
    const Lanes y = d.y * (vb.y - va.y) + row.rBxd.y * wb.y - row.rAxd.y * wa.y;
    const Lanes z = d.z * (vb.z - va.z) + row.rBxd.z * wb.z - row.rAxd.z * wa.z;
    out = x + y + z;
}

// Gives the bodies of a wide manifold impulses along its rows: normal[i] along point i's
// normal row, tangent0 and tangent1 along the friction rows, twist about the normal.
CYCLONE_INLINE void giveImpulses(WideVelocities<> &vel, const ManifoldBatch &m, const Lanes normal[kMaxManifoldPoints],
                                 const Lanes &tangent0, const Lanes &tangent1, const Lanes &twist) {
    const Lanes total = (normal[0] + normal[1]) + (normal[2] + normal[3]);
    const WideVector linear = {total * m.normal.x + tangent0 * m.tangent[0].x + tangent1 * m.tangent[1].x,
                               total * m.normal.y + tangent0 * m.tangent[0].y + tangent1 * m.tangent[1].y,
                               total * m.normal.z + tangent0 * m.tangent[0].z + tangent1 * m.tangent[1].z};
    subtractScaled(vel.va, m.invMassA, linear);
    addScaled(vel.vb, m.invMassB, linear);
    // Each side's angular impulse, sum of impulse times (r x d), turned by its inverse
    // inertia once (the twist row's r x d is the normal).
    WideVector leverA = {twist * m.normal.x, twist * m.normal.y, twist * m.normal.z};
    WideVector leverB = leverA;
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        addScaled(leverA, normal[i], m.points[i].row.rAxd);
        addScaled(leverB, normal[i], m.points[i].row.rBxd);
    }
    for (int r = 0; r < 2; ++r) {
        addScaled(leverA, r == 0 ? tangent0 : tangent1, m.friction[r].rAxd);
        addScaled(leverB, r == 0 ? tangent0 : tangent1, m.friction[r].rBxd);
    }
    WideVector turnA, turnB;
    multiply(m.invInertiaA, leverA, turnA);
    multiply(m.invInertiaB, leverB, turnB);
    vel.wa = {vel.wa.x - turnA.x, vel.wa.y - turnA.y, vel.wa.z - turnA.z};
    vel.wb = {vel.wb.x + turnB.x, vel.wb.y + turnB.y, vel.wb.z + turnB.z};
}

// One pass over a wide manifold's rows, as ManifoldSweep (contact_solver.cpp) makes it for
// one manifold: the friction rows' and the points' relative velocities are read from the
// bodies at the start, each impulse then reaches the points after it through the
// couplings, and all impulses reach the bodies together at the end.
struct WideSweep {
    WideVelocities<> &vel;
    ManifoldBatch &m;
    Lanes vn[kMaxManifoldPoints];  // relative normal velocity at each point, m/s
    Lanes v0, v1, v2;              // along tangent 0 and 1, m/s, and about the normal, rad/s
    Lanes change[kMaxManifoldPoints];
    Lanes change0, change1, change2;  // the friction rows'

    CYCLONE_INLINE WideSweep(WideVelocities<> &v, ManifoldBatch &manifold) : vel(v), m(manifold) {
        const WideVector dv = {vel.vb.x - vel.va.x, vel.vb.y - vel.va.y, vel.vb.z - vel.va.z};
        const WideVector dw = {vel.wb.x - vel.wa.x, vel.wb.y - vel.wa.y, vel.wb.z - vel.wa.z};
        const Lanes linear = m.normal.x * dv.x + m.normal.y * dv.y + m.normal.z * dv.z;
        for (int i = 0; i < kMaxManifoldPoints; ++i) {
            const WideRow &row = m.points[i].row;
            vn[i] = linear + (row.rBxd.x * vel.wb.x - row.rAxd.x * vel.wa.x) +
                    (row.rBxd.y * vel.wb.y - row.rAxd.y * vel.wa.y) + (row.rBxd.z * vel.wb.z - row.rAxd.z * vel.wa.z);
        }
        relative(m.tangent[0], vel.va, vel.vb, m.friction[0], vel.wa, vel.wb, v0);
        relative(m.tangent[1], vel.va, vel.vb, m.friction[1], vel.wa, vel.wb, v1);
        v0 -= m.frictionTarget[0];
        v1 -= m.frictionTarget[1];
        v2 = m.normal.x * dw.x + m.normal.y * dw.y + m.normal.z * dw.z;
    }

    // Adds `impulse` times a row's couplings to the points' normal velocities.
    CYCLONE_INLINE void couple(const Lanes coupling[kMaxManifoldPoints], const Lanes &impulse) {
        for (int j = 0; j < kMaxManifoldPoints; ++j) vn[j] += impulse * coupling[j];
    }

    // The patch's friction (patch_friction.h).
    CYCLONE_INLINE void friction() {
        const Lanes zero{};
        const LaneMask rubs = m.coefficient > zero;  // lanes with friction rows
        Lanes load = m.points[0].impulse;
        for (int i = 1; i < kMaxManifoldPoints; ++i) load += m.points[i].impulse;
        WideFrictionRows rows{m.frictionImpulse[0], m.frictionImpulse[1], m.twistImpulse};
        solveWideFriction(v0, v1, v2, m.frictionInverse, load, m.coefficient, m.twistRadius, rubs, m.frictionCoupling, vn, rows);
        change0 = rows.change0, change1 = rows.change1, change2 = rows.change2;
    }

    // Point i's normal row towards its bias.
    CYCLONE_INLINE void normal(int i) {
        WidePoint &p = m.points[i];
        const Lanes candidate = p.impulse - p.mass * (vn[i] - p.bias);
        const Lanes zero{};
        const Lanes updated = candidate > zero ? candidate : zero;
        change[i] = updated - p.impulse;
        p.impulse = updated;
        couple(m.normalCoupling[i], change[i]);
    }

    // Gives the bodies the sweep's impulses.
    CYCLONE_INLINE void finish() { giveImpulses(vel, m, change, change0, change1, change2); }
};

// A group's manifolds, padded with an empty one (lanes past the group's size, and points
// past a manifold's count, read zeros).
CYCLONE_INLINE void groupManifolds(const SolverManifolds &manifolds, const SolverGroup &group,
                                   const SolverManifold *m[kWideLanes]) {
    static const SolverManifold empty{};
    for (int k = 0; k < kWideLanes; ++k) m[k] = k < group.size ? &manifolds[group.manifold[k]] : &empty;
}

// Each lane's `field` of its manifold.
template <class Field>
CYCLONE_INLINE void gatherLanes(const SolverManifold *const m[kWideLanes], const Field &field, Lanes &out) {
    out = Lanes{field(*m[0]), field(*m[1]), field(*m[2]), field(*m[3])};
}

// Each lane's i-th point in its manifold's solve order (a zero point past its count).
CYCLONE_INLINE void pointsInOrder(const SolverManifold *const m[kWideLanes], int i, const SolverPoint *p[kWideLanes]) {
    static const SolverPoint zeroPoint{};
    for (int k = 0; k < kWideLanes; ++k) p[k] = i < m[k]->count ? &m[k]->points[m[k]->order[i]] : &zeroPoint;
}

// What changes between the sub-steps of a step: the accumulated impulses, the targets,
// and the bodies' inverse masses and inertias (a body isolated in a sub-step is
// immovable from then on).
CYCLONE_INLINE void loadChanging(const std::vector<SolverBody> &bodies, const SolverManifold *const m[kWideLanes],
                                 ManifoldBatch &w) {
    w.invMassA = Lanes{bodies[w.a[0]].invMass, bodies[w.a[1]].invMass, bodies[w.a[2]].invMass, bodies[w.a[3]].invMass};
    w.invMassB = Lanes{bodies[w.b[0]].invMass, bodies[w.b[1]].invMass, bodies[w.b[2]].invMass, bodies[w.b[3]].invMass};
    loadInertia(bodies, w.a, w.invInertiaA);
    loadInertia(bodies, w.b, w.invInertiaB);
    // Lane point i is the i-th in the manifold's solve order.
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        const SolverPoint *p[kWideLanes];
        pointsInOrder(m, i, p);
        w.points[i].impulse = Lanes{p[0]->normal.impulse, p[1]->normal.impulse, p[2]->normal.impulse, p[3]->normal.impulse};
        w.points[i].bias = Lanes{p[0]->velocityBias, p[1]->velocityBias, p[2]->velocityBias, p[3]->velocityBias};
    }
    for (int r = 0; r < 2; ++r)
        gatherLanes(m, [r](const SolverManifold &x) { return x.frictionRow[r].impulse; }, w.frictionImpulse[r]);
    gatherLanes(m, [](const SolverManifold &x) { return x.twist.impulse; }, w.twistImpulse);
}

// The warm start of one group: its bodies take its accumulated impulses.
CYCLONE_INLINE void warmStartGroup(std::vector<SolverBody> &bodies, const ManifoldBatch &w) {
    WideVelocities<> vel(bodies, w);
    const Lanes normal[kMaxManifoldPoints] = {w.points[0].impulse, w.points[1].impulse, w.points[2].impulse,
                                              w.points[3].impulse};
    giveImpulses(vel, w, normal, w.frictionImpulse[0], w.frictionImpulse[1], w.twistImpulse);
    vel.store(bodies, w);
}

}  // namespace

CYCLONE_SIMD_CLONES
void loadBatches(std::vector<SolverBody> &bodies, const SolverManifolds &manifolds,
              const std::vector<SolverGroup> &groups, bool warmStart, std::vector<ManifoldBatch> &wide,
              std::vector<PenetrationBatch> *pseudo) {
    // The number of groups moves a little from step to step (the order of a layer's
    // contacts, equal in height but for rounding, changes how they group): room for an
    // eighth more, so that a steady scene does not allocate when it rises past what an
    // earlier step needed (std::vector's first resize takes exactly the size asked). Every
    // batch is written below, so the old room is let go before the new is taken, not
    // copied into it: a batch is 3.5 KB.
    if (wide.capacity() < groups.size()) {
        std::vector<ManifoldBatch>().swap(wide);
        wide.reserve(groups.size() + groups.size() / 8 + 4);
    }
    wide.resize(groups.size());
    if (pseudo) {
        if (pseudo->capacity() < groups.size()) {
            std::vector<PenetrationBatch>().swap(*pseudo);
            pseudo->reserve(wide.capacity());
        }
        pseudo->resize(groups.size());
    }
    for (std::size_t g = 0; g < groups.size(); ++g) {
        ManifoldBatch &w = wide[g];
        const SolverManifold *m[kWideLanes];
        groupManifolds(manifolds, groups[g], m);
        w.size = groups[g].size;
        for (int k = 0; k < kWideLanes; ++k) {
            w.a[k] = m[k]->a;
            w.b[k] = m[k]->b;
        }
        const auto vectors = [&](auto field, WideVector &out) __attribute__((always_inline)) {
            transposeIn(field(*m[0]), field(*m[1]), field(*m[2]), field(*m[3]), out);
        };
        loadChanging(bodies, m, w);
        for (int d = 0; d < 3; ++d)
            vectors([d](const SolverManifold &x) -> const Lanes & { return x.direction[d]; }, d == 0 ? w.normal : w.tangent[d - 1]);
        // Lane point i is the i-th in the manifold's solve order.
        const CouplingOrder order[kWideLanes] = {CouplingOrder(*m[0]), CouplingOrder(*m[1]), CouplingOrder(*m[2]),
                                                 CouplingOrder(*m[3])};
        Lanes entry[kWideLanes];
        for (int i = 0; i < kMaxManifoldPoints; ++i) {
            const SolverPoint *p[kWideLanes];
            pointsInOrder(m, i, p);
            loadRow(p[0]->normal, p[1]->normal, p[2]->normal, p[3]->normal, w.points[i].row);
            w.points[i].mass = Lanes{p[0]->normal.mass, p[1]->normal.mass, p[2]->normal.mass, p[3]->normal.mass};
            for (int k = 0; k < kWideLanes; ++k) order[k].normal(m[k]->couplings, i, entry[k]);
            transpose(entry[0], entry[1], entry[2], entry[3], w.normalCoupling[i]);
        }
        for (int r = 0; r < 2; ++r) {
            loadRow(m[0]->frictionRow[r], m[1]->frictionRow[r], m[2]->frictionRow[r], m[3]->frictionRow[r], w.friction[r]);
            gatherLanes(m, [r](const SolverManifold &x) { return x.frictionRow[r].target; }, w.frictionTarget[r]);
        }
        for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < kWideLanes; ++k) order[k].friction(m[k]->couplings, r, entry[k]);
            transpose(entry[0], entry[1], entry[2], entry[3], w.frictionCoupling[r]);
        }
        for (int e = 0; e < 6; ++e)
            gatherLanes(m, [e](const SolverManifold &x) { return x.frictionInverse[e]; }, w.frictionInverse[e]);
        gatherLanes(m, [](const SolverManifold &x) { return x.friction; }, w.coefficient);
        gatherLanes(m, [](const SolverManifold &x) { return x.twistRadius; }, w.twistRadius);
        if (pseudo) loadPseudo(m, (*pseudo)[g]);
        // The warm start, while the group's rows are still in the cache.
        if (warmStart) warmStartGroup(bodies, w);
    }
}

CYCLONE_SIMD_CLONES
void reloadBatches(std::vector<SolverBody> &bodies, const SolverManifolds &manifolds,
                   const std::vector<SolverGroup> &groups, bool warmStart, std::vector<ManifoldBatch> &wide) {
    for (std::size_t g = 0; g < groups.size(); ++g) {
        ManifoldBatch &w = wide[g];
        const SolverManifold *m[kWideLanes];
        groupManifolds(manifolds, groups[g], m);
        loadChanging(bodies, m, w);
        if (warmStart) warmStartGroup(bodies, w);
    }
}

CYCLONE_SIMD_CLONES
void solveVelocityBatches(std::vector<SolverBody> &bodies, std::vector<ManifoldBatch> &wide, bool reverse) {
    for (ManifoldBatch &m : wide) {
        WideVelocities<> vel(bodies, m);
        WideSweep sweep(vel, m);
        sweepRows(sweep, kMaxManifoldPoints, reverse);
        vel.store(bodies, m);
    }
}

void storeBatches(const std::vector<ManifoldBatch> &wide, const std::vector<SolverGroup> &groups,
               SolverManifolds &manifolds) {
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const ManifoldBatch &w = wide[g];
        for (int k = 0; k < w.size; ++k) {
            SolverManifold &m = manifolds[groups[g].manifold[k]];
            for (int i = 0; i < m.count; ++i) m.points[m.order[i]].normal.impulse = w.points[i].impulse[k];
            m.frictionRow[0].impulse = w.frictionImpulse[0][k];
            m.frictionRow[1].impulse = w.frictionImpulse[1][k];
            m.twist.impulse = w.twistImpulse[k];
        }
    }
}

}  // namespace cyclone::detail
