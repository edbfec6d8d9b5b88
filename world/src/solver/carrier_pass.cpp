#include "solver/carrier_pass.h"

#include <algorithm>

#include "solver/patch_friction.h"

namespace cyclone::detail {
namespace {

// The lanes of a group: run k's manifolds are runs.manifolds[first[k] .. first[k] + size[k]).
struct RunLanes {
    int count = 0;
    int first[kWideLanes] = {};
    int size[kWideLanes] = {};
    int body[kWideLanes] = {};  ///< The carried bodies (0 in idle lanes).
    int slots = 0;              ///< The longest run's size.
};

CYCLONE_INLINE bool carriesB(const SolverManifold &m) { return m.carrier == Carrier::A; }

// Per lane: a . b summed as dot3 sums one vector, (x + y) + z of the rounded products. The
// barriers keep the compiler from fusing a product into a sum (FMA), which would round
// it otherwise: every operation is then a plain rounded one, and a sign taken into the
// terms comes out of the sum exactly (a sign flip commutes with rounding).
CYCLONE_INLINE void exactDot(const WideVector &a, const WideVector &b, Lanes &out) {
    const Lanes x = __builtin_assoc_barrier(a.x * b.x);
    const Lanes y = __builtin_assoc_barrier(a.y * b.y);
    const Lanes z = __builtin_assoc_barrier(a.z * b.z);
    out = (x + y) + z;
}

RunLanes laneRuns(const SolverManifolds &manifolds, const CarrierRuns &runs, const int *run,
                  int count) {
    RunLanes lanes;
    lanes.count = count;
    for (int k = 0; k < count; ++k) {
        lanes.first[k] = runs.start[run[k]];
        lanes.size[k] = runs.start[run[k] + 1] - lanes.first[k];
        const SolverManifold &lead = manifolds[runs.manifolds[lanes.first[k]]];
        lanes.body[k] = carriesB(lead) ? lead.b : lead.a;
        lanes.slots = std::max(lanes.slots, lanes.size[k]);
    }
    return lanes;
}

// One contact slot of each lane, as its carried body takes it: the manifolds, their
// carriers, and which side of each row is the carried body's.
struct CarriedLanes {
    const SolverManifold *m[kWideLanes];
    Lanes sign;  // +1 where the carried body is B, -1 where it is A
    Lanes SolverRow::*rxd[kWideLanes];  // the carried body's terms of a row
    Lanes SolverRow::*ang[kWideLanes];
    Lanes SolverRow::*carrierRxd[kWideLanes];  // the carrier's
    WideVector carrierV, carrierW;               // the carriers' velocities

    CYCLONE_INLINE CarriedLanes(const std::vector<SolverBody> &bodies, const SolverManifolds &manifolds,
                                const CarrierRuns &runs, const RunLanes &lanes, int slot) {
        static const SolverManifold none{};
        const SolverBody *carrier[kWideLanes];
        for (int k = 0; k < kWideLanes; ++k) {
            const bool has = k < lanes.count && slot < lanes.size[k];
            m[k] = has ? &manifolds[runs.manifolds[lanes.first[k] + slot]] : &none;
            const bool b = carriesB(*m[k]);
            carrier[k] = &bodies[b ? m[k]->a : m[k]->b];
            sign[k] = b ? 1 : -1;
            rxd[k] = b ? &SolverRow::rBxd : &SolverRow::rAxd;
            ang[k] = b ? &SolverRow::angB : &SolverRow::angA;
            carrierRxd[k] = b ? &SolverRow::rAxd : &SolverRow::rBxd;
        }
        transposeIn(carrier[0]->v, carrier[1]->v, carrier[2]->v, carrier[3]->v, carrierV);
        transposeIn(carrier[0]->w, carrier[1]->w, carrier[2]->w, carrier[3]->w, carrierW);
    }

    // A vector of each lane, signed as the carried body takes it.
    template <typename Field>
    CYCLONE_INLINE void vectors(Field field, WideVector &out) const {
        transposeIn(field(0), field(1), field(2), field(3), out);
        out.x *= sign, out.y *= sign, out.z *= sign;
    }
    template <typename Field>
    static CYCLONE_INLINE void lanesOf(Field field, Lanes &out) {
        out = Lanes{field(0), field(1), field(2), field(3)};
    }
    // A row as the carried body takes it, and the carrier's share of its relative velocity
    // along d (`direction`, already negated where the carried body is A): minus the
    // carrier's own terms where the carried body is B. The carrier's lever terms are
    // negated with d, so the share is -(d . v + (r x d) . w) of the signed terms in every
    // lane: the sign times that of the unsigned terms, exactly (exactDot).
    template <typename Row>
    CYCLONE_INLINE void loadRow(Row row, const WideVector &direction, WideCarriedRow &out, Lanes &share) const {
        vectors([&](int k) -> const Lanes & { return row(k).*rxd[k]; }, out.rxd);
        vectors([&](int k) -> const Lanes & { return row(k).*ang[k]; }, out.ang);
        WideVector lever;
        vectors([&](int k) -> const Lanes & { return row(k).*carrierRxd[k]; }, lever);
        Lanes linear, angular;
        exactDot(direction, carrierV, linear);
        exactDot(lever, carrierW, angular);
        share = -(linear + angular);
    }
};

// The normal rows of the lanes' points into c: lane point i is the i-th in the
// manifold's solve order. With `patchCentre`, every point's carrier share along the
// normal is that of the patch's centre (loadContact).
CYCLONE_INLINE void loadPoints(const CarriedLanes &l, const CouplingOrder *order, bool patchCentre,
                               WideCarriedContact &c) {
    static const SolverPoint zeroPoint{};
    Lanes entry[kWideLanes];
    for (int i = 0; i < kMaxManifoldPoints; ++i) {
        const SolverPoint *p[kWideLanes];
        for (int k = 0; k < kWideLanes; ++k) p[k] = i < l.m[k]->count ? &l.m[k]->points[l.m[k]->order[i]] : &zeroPoint;
        const auto row = [&](int k) -> const SolverRow & { return p[k]->normal; };
        l.loadRow(row, c.normal, c.points[i], c.carrier[i]);
        l.lanesOf([&](int k) { return row(k).carriedMass; }, c.mass[i]);
        l.lanesOf([&](int k) { return row(k).impulse; }, c.impulse[i]);
        l.lanesOf([&](int k) { return p[k]->velocityBias; }, c.bias[i]);
        for (int k = 0; k < kWideLanes; ++k) order[k].normal(l.m[k]->carriedCouplings, i, entry[k]);
        transpose(entry[0], entry[1], entry[2], entry[3], c.normalCoupling[i]);
    }
    if (!patchCentre) return;
    for (int k = 0; k < kWideLanes; ++k) {
        const int count = l.m[k]->count;
        if (count == 0) continue;
        real sum = 0;
        for (int i = 0; i < count; ++i) sum += c.carrier[i][k];
        for (int i = 0; i < count; ++i) c.carrier[i][k] = sum / count;
    }
}

// The friction rows, the twist row and the patch's friction terms of the lanes into c.
CYCLONE_INLINE void loadFriction(const CarriedLanes &l, const CouplingOrder *order, WideCarriedContact &c) {
    for (int r = 0; r < 2; ++r) {
        const auto row = [&](int k) -> const SolverRow & { return l.m[k]->frictionRow[r]; };
        l.loadRow(row, c.tangent[r], c.friction[r], c.frictionCarrier[r]);
        l.lanesOf([&](int k) { return row(k).impulse; }, c.frictionImpulse[r]);
        // The relative velocity is B's less A's in every lane (loadRow): its target too.
        Lanes target;
        l.lanesOf([&](int k) { return row(k).target; }, target);
        c.frictionCarrier[r] -= target;
    }
    // The twist row's lever terms are the normal itself, on either side.
    l.vectors([&](int k) -> const Lanes & { return l.m[k]->twist.*l.ang[k]; }, c.twist);
    exactDot(c.normal, l.carrierW, c.frictionCarrier[2]);
    c.frictionCarrier[2] = -c.frictionCarrier[2];
    l.lanesOf([&](int k) { return l.m[k]->twist.impulse; }, c.twistImpulse);
    Lanes entry[kWideLanes];
    for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < kWideLanes; ++k) order[k].friction(l.m[k]->carriedCouplings, r, entry[k]);
        transpose(entry[0], entry[1], entry[2], entry[3], c.frictionCoupling[r]);
    }
    for (int e = 0; e < 6; ++e) l.lanesOf([&](int k) { return l.m[k]->carriedFrictionInverse[e]; }, c.frictionInverse[e]);
    l.lanesOf([&](int k) { return l.m[k]->friction; }, c.coefficient);
    l.lanesOf([&](int k) { return l.m[k]->twistRadius; }, c.twistRadius);
}

// Copies each lane's contact `slot` into c, as its carried body takes it. With
// `patchCentre`, every point's carrier share along the normal is that of the patch's
// centre (the mean of the points'): the carrier taken as moving with its patch, its turn
// across the patch left out. A box on two carriers whose tops move apart vertically must
// turn to rest on both; taken with its carriers' turns, that turn reaches the next level
// as a difference of vertical velocity, and a pyramid's layers hand such differences up
// growing (docs/solver.md, "The carrier pass", tall stacks). Done for stacks of more than
// kCarrierLevels levels only.
CYCLONE_INLINE void loadContact(const std::vector<SolverBody> &bodies, const SolverManifolds &manifolds,
                                const CarrierRuns &runs, const RunLanes &lanes, int slot, bool patchCentre,
                                WideCarriedContact &c) {
    const CarriedLanes l(bodies, manifolds, runs, lanes, slot);
    for (int d = 0; d < 3; ++d)
        l.vectors([&](int k) -> const Lanes & { return l.m[k]->direction[d]; }, d == 0 ? c.normal : c.tangent[d - 1]);
    const CouplingOrder order[kWideLanes] = {CouplingOrder(*l.m[0]), CouplingOrder(*l.m[1]), CouplingOrder(*l.m[2]),
                                             CouplingOrder(*l.m[3])};
    loadPoints(l, order, patchCentre, c);
    loadFriction(l, order, c);
}

// Writes back the accumulated impulses of each lane's contact `slot` where the carrier is
// immovable (the true problem there, kept as the next step's warm start).
void storeContact(const CarrierRuns &runs, const RunLanes &lanes, int slot, const WideCarriedContact &c,
                  SolverManifolds &manifolds) {
    for (int k = 0; k < lanes.count; ++k) {
        if (slot >= lanes.size[k]) continue;
        SolverManifold &m = manifolds[runs.manifolds[lanes.first[k] + slot]];
        if (m.a != 0 && m.b != 0) continue;
        for (int i = 0; i < m.count; ++i) m.points[m.order[i]].normal.impulse = c.impulse[i][k];
        m.frictionRow[0].impulse = c.frictionImpulse[0][k];
        m.frictionRow[1].impulse = c.frictionImpulse[1][k];
        m.twist.impulse = c.twistImpulse[k];
    }
}

// The velocities of a group's carried bodies, held in registers over its sweeps.
struct CarriedBodies {
    WideVector v, w;
    Lanes invMass{};
};

// One contact of each lane solved once, as ManifoldSweep (contact_solver.cpp) solves a
// manifold: friction as a block, then the points, each impulse reaching the later rows
// through the couplings and the body at the end. Lanes outside `active` take no impulse.
struct CarriedSweep {
    CarriedBodies &body;
    WideCarriedContact &c;
    const LaneMask active;
    Lanes vn[kMaxManifoldPoints];  // relative normal velocity at each point, m/s
    Lanes change[kMaxManifoldPoints];
    Lanes change0{}, change1{}, change2{};  // the friction rows'

    CYCLONE_INLINE CarriedSweep(CarriedBodies &b, WideCarriedContact &contact, const LaneMask &mask)
        : body(b), c(contact), active(mask) {
        Lanes linear, angular;
        dotLanes(c.normal, body.v, linear);
        for (int i = 0; i < kMaxManifoldPoints; ++i) {
            dotLanes(c.points[i].rxd, body.w, angular);
            vn[i] = c.carrier[i] + (linear + angular);
        }
    }

    // Per lane: out = carrier + d . v + (r x d) . w, the relative velocity along a row.
    CYCLONE_INLINE void relative(const WideVector &d, const WideCarriedRow &row, const Lanes &carrier, Lanes &out) const {
        Lanes linear, angular;
        dotLanes(d, body.v, linear);
        dotLanes(row.rxd, body.w, angular);
        out = carrier + (linear + angular);
    }

    CYCLONE_INLINE void couple(const Lanes coupling[kMaxManifoldPoints], const Lanes &impulse) {
        for (int j = 0; j < kMaxManifoldPoints; ++j) vn[j] += impulse * coupling[j];
    }

    // The patch's friction (patch_friction.h).
    CYCLONE_INLINE void friction() {
        const Lanes zero{};
        const LaneMask rubs = (c.coefficient > zero) & active;
        Lanes v0, v1, v2;
        relative(c.tangent[0], c.friction[0], c.frictionCarrier[0], v0);
        relative(c.tangent[1], c.friction[1], c.frictionCarrier[1], v1);
        dotLanes(c.normal, body.w, v2);
        v2 += c.frictionCarrier[2];
        const Lanes load = (c.impulse[0] + c.impulse[1]) + (c.impulse[2] + c.impulse[3]);
        WideFrictionRows rows{c.frictionImpulse[0], c.frictionImpulse[1], c.twistImpulse};
        solveWideFriction(v0, v1, v2, c.frictionInverse, load, c.coefficient, c.twistRadius, rubs, c.frictionCoupling, vn, rows);
        change0 = rows.change0, change1 = rows.change1, change2 = rows.change2;
    }

    // Point i's normal row towards its bias.
    CYCLONE_INLINE void normal(int i) {
        const Lanes zero{};
        const Lanes candidate = c.impulse[i] - c.mass[i] * (vn[i] - c.bias[i]);
        const Lanes updated = active ? (candidate > zero ? candidate : zero) : c.impulse[i];
        change[i] = updated - c.impulse[i];
        c.impulse[i] = updated;
        couple(c.normalCoupling[i], change[i]);
    }

    // Gives the carried bodies the sweep's impulses.
    CYCLONE_INLINE void finish() {
        const Lanes total = (change[0] + change[1]) + (change[2] + change[3]);
        const WideVector linear = {total * c.normal.x + change0 * c.tangent[0].x + change1 * c.tangent[1].x,
                                   total * c.normal.y + change0 * c.tangent[0].y + change1 * c.tangent[1].y,
                                   total * c.normal.z + change0 * c.tangent[0].z + change1 * c.tangent[1].z};
        addScaled(body.v, body.invMass, linear);
        for (int i = 0; i < kMaxManifoldPoints; ++i) addScaled(body.w, change[i], c.points[i].ang);
        addScaled(body.w, change0, c.friction[0].ang);
        addScaled(body.w, change1, c.friction[1].ang);
        addScaled(body.w, change2, c.twist);
    }

    CYCLONE_INLINE void solve(bool backwards) { sweepRows(*this, kMaxManifoldPoints, backwards); }
};

// How far the carried bodies' velocities moved from `from` to `to` at their contacts,
// m/s: |dv| + |dw| times the lever arm.
CYCLONE_INLINE void movedBetween(const CarriedBodies &from, const CarriedBodies &to, const Lanes &lever, Lanes &out) {
    const WideVector dv = {to.v.x - from.v.x, to.v.y - from.v.y, to.v.z - from.v.z};
    const WideVector dw = {to.w.x - from.w.x, to.w.y - from.w.y, to.w.z - from.w.z};
    Lanes linear, angular;
    dotLanes(dv, dv, linear);
    dotLanes(dw, dw, angular);
    sqrtLanes(linear, linear);
    sqrtLanes(angular, angular);
    out = linear + angular * lever;
}

}  // namespace

CYCLONE_SIMD_CLONES
void solveCarriedRuns(std::vector<SolverBody> &bodies, SolverManifolds &manifolds,
                      const CarrierRuns &runs, const int *run, int count, bool reverse, CarrierPassScratch &scratch) {
    const RunLanes lanes = laneRuns(manifolds, runs, run, count);
    // Room for four carriers at least (a box on a 2 x 2 grid), so that a run with more
    // carriers than any before it rarely allocates in a later step.
    constexpr int kCarriersMade = 4;
    if (scratch.contacts.size() < static_cast<std::size_t>(lanes.slots))
        scratch.contacts.resize(std::max(lanes.slots, kCarriersMade));
    WideCarriedContact *contacts = scratch.contacts.data();
    const int levels = static_cast<int>(runs.levelStart.size()) - 1;
    const CarrierStop stop = carrierStop(levels);
    const bool patchCentre = levels > kCarrierLevels;
    for (int slot = 0; slot < lanes.slots; ++slot)
        loadContact(bodies, manifolds, runs, lanes, slot, patchCentre, contacts[slot]);

    CarriedBodies body;
    const SolverBody &b0 = bodies[lanes.body[0]], &b1 = bodies[lanes.body[1]], &b2 = bodies[lanes.body[2]],
                     &b3 = bodies[lanes.body[3]];
    transposeIn(b0.v, b1.v, b2.v, b3.v, body.v);
    transposeIn(b0.w, b1.w, b2.w, b3.w, body.w);
    body.invMass = Lanes{b0.invMass, b1.invMass, b2.invMass, b3.invMass};
    // The stopping test's lever arm: the first contact's first point's (w times it is how
    // fast the body's turning moves that point).
    Lanes lever;
    dotLanes(contacts[0].points[0].rxd, contacts[0].points[0].rxd, lever);
    sqrtLanes(lever, lever);
    const Lanes tolerance{stop.tolerance, stop.tolerance, stop.tolerance, stop.tolerance};
    LaneMask active{};
    for (int k = 0; k < count; ++k) active[k] = -1;

    // Every sweep of a run takes the points in one direction (the caller alternates it from
    // step to step). Sweeps that alternate end, where no velocity meets all of a body's
    // contacts at once, in a cycle of two states that no one-sweep test ends, and the run
    // sweeps to its cap (docs/solver.md, "The carrier pass").
    for (int k = 0; k < kWideLanes; ++k) scratch.laneSweeps[k] = 0;
    for (int sweep = 0; sweep < stop.sweeps && anyLane(active); ++sweep) {
        for (int k = 0; k < count; ++k) scratch.laneSweeps[k] += active[k] != 0;
        const CarriedBodies before = body;
        for (int slot = 0; slot < lanes.slots; ++slot) CarriedSweep(body, contacts[slot], active).solve(reverse);
        // A sweep that changed a body's velocity at its contacts by less than the
        // tolerance ends its run.
        Lanes moved;
        movedBetween(before, body, lever, moved);
        active &= ~(moved < tolerance);
    }

    for (int k = 0; k < count; ++k) scratch.sweeps += scratch.laneSweeps[k];
    Lanes v[kWideLanes], w[kWideLanes];
    transposeOut(body.v, v);
    transposeOut(body.w, w);
    for (int k = 0; k < count; ++k) {
        bodies[lanes.body[k]].v = v[k];
        bodies[lanes.body[k]].w = w[k];
    }
    for (int slot = 0; slot < lanes.slots; ++slot) storeContact(runs, lanes, slot, contacts[slot], manifolds);
}

}  // namespace cyclone::detail
