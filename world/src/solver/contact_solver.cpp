#include "solver/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "solver/simd/batch4.h"

namespace cyclone::detail {
namespace {

// out = a x b in lanes: the products and differences of Eigen's cross, in its order.
CYCLONE_INLINE void crossLanes(const Lanes &a, const Lanes &b, Lanes &out) {
    const LaneIndices yzx = {1, 2, 0, 3};
    const LaneIndices zxy = {2, 0, 1, 3};
    out = __builtin_shuffle(a, yzx) * __builtin_shuffle(b, zxy) - __builtin_shuffle(a, zxy) * __builtin_shuffle(b, yzx);
}

// The columns of a 3 x 3 matrix in lanes.
struct LaneMatrix {
    Lanes column[3];

    CYCLONE_INLINE explicit LaneMatrix(const Matrix3 &m) {
        for (int k = 0; k < 3; ++k) setLanes(column[k], m.col(k));
    }
    // out = m v, each row summed left to right (Eigen's product may round otherwise).
    CYCLONE_INLINE void multiply(const Lanes &v, Lanes &out) const {
        out = column[0] * v[0] + column[1] * v[1] + column[2] * v[2];
    }
};

// The Jacobian terms of one row along d, in lanes.
CYCLONE_INLINE void fillJacobian(const LaneMatrix &inertiaA, const LaneMatrix &inertiaB, const Lanes &rA,
                                 const Lanes &rB, const Lanes &d, SolverRow &row) {
    crossLanes(rA, d, row.rAxd);
    crossLanes(rB, d, row.rBxd);
    inertiaA.multiply(row.rAxd, row.angA);
    inertiaB.multiply(row.rBxd, row.angB);
}

// One row along d with its effective mass, in lanes.
CYCLONE_INLINE void fillRow(real invMasses, const LaneMatrix &inertiaA, const LaneMatrix &inertiaB, const Lanes &rA,
                            const Lanes &rB, const Lanes &d, SolverRow &row) {
    fillJacobian(inertiaA, inertiaB, rA, rB, d, row);
    const real k = invMasses + dot3(row.rAxd, row.angA) + dot3(row.rBxd, row.angB);
    row.mass = k > 0 ? 1 / k : 0;
    row.carriedMass = row.mass;
}

// A manifold's two bodies, set up to fill rows at one place: their summed inverse
// masses, inverse inertias, and the place's lever arms from A and B in lanes.
struct RowFrame {
    real invMasses;
    LaneMatrix inertiaA, inertiaB;
    Lanes rA{}, rB{};

    CYCLONE_INLINE RowFrame(const SolverBody &a, const SolverBody &b, const Vector3 &leverA, const Vector3 &leverB)
        : invMasses(a.invMass + b.invMass), inertiaA(a.invInertia), inertiaB(b.invInertia) {
        setLanes(rA, leverA);
        setLanes(rB, leverB);
    }
    CYCLONE_INLINE void fill(const Lanes &d, SolverRow &row) const {
        fillRow(invMasses, inertiaA, inertiaB, rA, rB, d, row);
    }
    CYCLONE_INLINE void fillJacobianOnly(const Lanes &d, SolverRow &row) const {
        fillJacobian(inertiaA, inertiaB, rA, rB, d, row);
    }
};

// The twist row's Jacobian about the normal n: angular only, its lever arms are n itself.
CYCLONE_INLINE void fillTwistRow(const LaneMatrix &inertiaA, const LaneMatrix &inertiaB, const Lanes &n,
                                 SolverRow &row) {
    row.rAxd = n;
    row.rBxd = n;
    inertiaA.multiply(n, row.angA);
    inertiaB.multiply(n, row.angB);
}

// Which bodies a pass moves: both, or only the one a supporting body carries.
enum Moving { kBoth, kOnlyA, kOnlyB };

// The velocities (v, w) of A and B that one manifold works on, held in registers while
// its rows are solved.
struct PairVelocities {
    Lanes va, wa, vb, wb;
    real invMassA, invMassB;

    CYCLONE_INLINE PairVelocities(const SolverBody &a, const SolverBody &b)
        : va(a.v), wa(a.w), vb(b.v), wb(b.w), invMassA(a.invMass), invMassB(b.invMass) {}

    // Writes the bodies back. Never the immovable world (entry 0), which it would leave
    // unchanged: two threads may hold it at once (threads/partition.h).
    CYCLONE_INLINE void store(std::vector<SolverBody> &bodies, const SolverManifold &m) const {
        if (m.a != 0) bodies[m.a].v = va, bodies[m.a].w = wa;
        if (m.b != 0) bodies[m.b].v = vb, bodies[m.b].w = wb;
    }

    // Relative velocity of B with respect to A along direction d of a row.
    CYCLONE_INLINE real along(const Lanes &d, const SolverRow &row) const {
        return sum3(d * (vb - va) + row.rBxd * wb - row.rAxd * wa);
    }

    // Relative angular velocity of B with respect to A about an angular-only row's axis.
    CYCLONE_INLINE real turning(const SolverRow &row) const { return sum3(row.rBxd * wb - row.rAxd * wa); }

    // Applies an angular impulse along an angular-only row (on B; its opposite on A).
    CYCLONE_INLINE void applyTurning(const SolverRow &row, real impulse) {
        wa -= impulse * row.angA;
        wb += impulse * row.angB;
    }

    // Applies impulse * d (on B; its opposite on A) through a row's angular terms.
    CYCLONE_INLINE void apply(const Lanes &d, const SolverRow &row, real impulse) {
        va -= (invMassA * impulse) * d;
        wa -= impulse * row.angA;
        vb += (invMassB * impulse) * d;
        wb += impulse * row.angB;
    }
};

// A patch's twist held at its limit, `excess` (N m s) short of the block's solution: the
// tangent impulses become the block's solution with the twist's change fixed where it is
// held. With the block inverse [[A, b], [b^T, c]] (tangents, twist: k[0], k[1], k[3] are
// A, k[2], k[4] are b, k[5] is c), fixing the twist's change at d2 gives the tangents
// -(A - b b^T / c) v_t + (b / c) d2, which is the free solution plus (b / c) times the
// twist's shortfall. Without it the tangents would leave to the twist a turn about the
// body's centre that the twist cannot stop: the legs of a table whose turn the block
// gives to each leg's twist, held at a small limit, would let the table turn for ever
// (docs/compound.md).
CYCLONE_INLINE void twistHeld(const real k[6], real excess, real &tangent0, real &tangent1) {
    tangent0 += k[2] / k[5] * excess;
    tangent1 += k[4] / k[5] * excess;
}

// One pass over one manifold's rows: friction, then the normal rows (the ones that must
// hold have the last word), each solved against the velocities the rows before it left,
// as Gauss-Seidel does. The bodies' velocities are read once: the friction rows' and the
// points' normal velocities all at the start, and each impulse then updates the normal
// velocities of the points after it through the manifold's couplings. The impulses reach
// the bodies together at the end. The numbers are those of solving row after row on the
// bodies' velocities, but a row waits only for a few scalar products, not for the
// bodies' velocities to be updated and dotted again.
//
// kCount is the manifold's count: its loops unroll and the velocities stay in registers.
template <int kCount>
struct ManifoldSweep {
    PairVelocities &vel;
    SolverManifold &m;
    const RowCouplings &couplings;
    real vn[kCount];  // relative normal velocity at each point, m/s
    real normalChange[kCount] = {};
    Lanes frictionA{}, frictionB{};  // the friction impulses' angular changes of A and B
    Lanes frictionLinear{};          // and their linear impulse

    CYCLONE_INLINE ManifoldSweep(PairVelocities &v, SolverManifold &manifold)
        : vel(v), m(manifold), couplings(manifold.couplings) {
        const real linear = dot3(m.direction[0], vel.vb - vel.va);
        for (int i = 0; i < kCount; ++i) {
            const SolverRow &row = m.points[i].normal;
            vn[i] = linear + sum3(row.rBxd * vel.wb - row.rAxd * vel.wa);
        }
    }

    // Adds `impulse` times a coupling to the points' normal velocities.
    CYCLONE_INLINE void couple(const Lanes &coupling, real impulse) {
        for (int i = 0; i < kCount; ++i) vn[i] += impulse * coupling[i];
    }

    // The patch's friction: the tangents and the twist solved together (the impulses that
    // stop the patch sliding and turning at once), then the twist limited by the points'
    // summed normal impulse times the twist radius (the tangents taking what it could not:
    // twistHeld) and the tangents by the same sum to Coulomb's cone (not a box: friction
    // is isotropic in the contact plane).
    CYCLONE_INLINE void friction() {
        if (m.friction <= 0) return;
        SolverRow &row0 = m.frictionRow[0];
        SolverRow &row1 = m.frictionRow[1];
        SolverRow &twist = m.twist;
        const bool turns = m.twistRadius > 0;
        const real *k = m.frictionInverse;
        real load = 0;
        for (int k = 0; k < kCount; ++k) load += m.points[m.order[k]].normal.impulse;
        const real limit = m.friction * load;
        const real v0 = vel.along(m.direction[1], row0) - row0.target;
        const real v1 = vel.along(m.direction[2], row1) - row1.target;
        const real v2 = turns ? vel.turning(twist) : 0;
        const real old0 = row0.impulse;
        const real old1 = row1.impulse;
        real new0 = old0 - (k[0] * v0 + k[1] * v1 + k[2] * v2);
        real new1 = old1 - (k[1] * v0 + k[3] * v1 + k[4] * v2);
        const real old2 = twist.impulse;
        real new2 = old2;
        if (turns) {
            const real twistLimit = limit * m.twistRadius;
            const real free2 = old2 - (k[2] * v0 + k[4] * v1 + k[5] * v2);
            new2 = std::clamp(free2, -twistLimit, twistLimit);
            if (new2 != free2 && k[5] > 0) twistHeld(k, new2 - free2, new0, new1);  // a singular block's inverse is all zeros
        }
        const real magnitude2 = new0 * new0 + new1 * new1;
        if (magnitude2 > limit * limit) {
            const real scale = limit / std::sqrt(magnitude2);
            new0 *= scale;
            new1 *= scale;
        }
        row0.impulse = new0;
        row1.impulse = new1;
        const real change0 = new0 - old0;
        const real change1 = new1 - old1;
        twist.impulse = new2;
        const real change2 = new2 - old2;
        couple(couplings.friction[0], change0);
        couple(couplings.friction[1], change1);
        couple(couplings.friction[2], change2);
        frictionLinear = change0 * m.direction[1] + change1 * m.direction[2];
        frictionA = change0 * row0.angA + change1 * row1.angA + change2 * twist.angA;
        frictionB = change0 * row0.angB + change1 * row1.angB + change2 * twist.angB;
    }

    // Sets point i's accumulated impulse `impulse` to `updated`.
    CYCLONE_INLINE void setNormal(int i, real updated, real &impulse) {
        normalChange[i] = updated - impulse;
        impulse = updated;
        couple(couplings.normal[i], normalChange[i]);
    }

    // Point i's normal row towards `target` normal velocity, on its accumulated impulse
    // `impulse`.
    CYCLONE_INLINE void normal(int i, real target, real &impulse) {
        setNormal(i, std::max(impulse - m.points[i].normal.mass * (vn[i] - target), real(0)), impulse);
    }

    // The k-th point in solve order towards its velocity bias.
    CYCLONE_INLINE void normal(int k) {
        const int i = m.order[k];
        SolverPoint &p = m.points[i];
        normal(i, p.velocityBias, p.normal.impulse);
    }

    // Gives the bodies the sweep's impulses.
    CYCLONE_INLINE void finish() {
        real total = 0;
        Lanes angularA = frictionA, angularB = frictionB;
        for (int k = 0; k < kCount; ++k) {
            const int i = m.order[k];
            const SolverRow &row = m.points[i].normal;
            total += normalChange[i];
            angularA += normalChange[i] * row.angA;
            angularB += normalChange[i] * row.angB;
        }
        const Lanes linear = total * m.direction[0] + frictionLinear;
        vel.va -= vel.invMassA * linear;
        vel.wa -= angularA;
        vel.vb += vel.invMassB * linear;
        vel.wb += angularB;
    }

    // The whole pass (sweepRows).
    CYCLONE_INLINE void solve(bool reverse) { sweepRows(*this, kCount, reverse); }
};

// Calls f(std::integral_constant<int, count>()) for a count of 1 to kMaxManifoldPoints
// (nothing for 0).
template <typename F>
CYCLONE_INLINE void withCount(int count, F &&f) {
    switch (count) {
    case 1: f(std::integral_constant<int, 1>()); break;
    case 2: f(std::integral_constant<int, 2>()); break;
    case 3: f(std::integral_constant<int, 3>()); break;
    case 4: f(std::integral_constant<int, 4>()); break;
    default: break;
    }
}

CYCLONE_INLINE void solveManifold(PairVelocities &vel, SolverManifold &m, bool reverse) {
    withCount(m.count, [&](auto count) __attribute__((always_inline)) { ManifoldSweep<count()>(vel, m).solve(reverse); });
}

}  // namespace

void tangentBasis(const Vector3 &n, Vector3 &t1, Vector3 &t2) {
    if (std::abs(n.x()) >= 0.57735) {
        t1 = Vector3(n.y(), -n.x(), 0).normalized();
    } else {
        t1 = Vector3(0, n.z(), -n.y()).normalized();
    }
    t2 = n.cross(t1);
}

void prepareDirections(SolverManifold &m) {
    setLanes(m.direction[0], m.normal);
    setLanes(m.direction[1], m.tangent[0]);
    setLanes(m.direction[2], m.tangent[1]);
}

real normalVelocity(const SolverBody &a, const SolverBody &b, const SolverManifold &m, const SolverPoint &p) {
    return PairVelocities(a, b).along(m.direction[0], p.normal);
}

CYCLONE_SIMD_CLONES
void prepareRows(const SolverBody &a, const SolverBody &b, const Vector3 &rA, const Vector3 &rB,
                 const SolverManifold &m, SolverPoint &p) {
    RowFrame(a, b, rA, rB).fill(m.direction[0], p.normal);
}

namespace {

// Coupling of rows x and y through the bodies a pass moves: the angular terms (the
// tangents are orthogonal, so the linear ones cancel off the diagonal).
real coupling(const SolverRow &x, const SolverRow &y, Moving moving) {
    const real a = dot3(x.rAxd, y.angA);
    const real b = dot3(x.rBxd, y.angB);
    return moving == kBoth ? a + b : moving == kOnlyA ? a : b;
}

// The inverse of the friction block's effective-mass matrix (SolverManifold::
// frictionInverse) for the bodies a pass moves, whose summed inverse masses are
// invMasses. A singular block (no moving body) gives zeros: no friction impulse.
void invertFrictionBlock(const SolverManifold &m, Moving moving, real invMasses, real out[6]) {
    const SolverRow &t0 = m.frictionRow[0];
    const SolverRow &t1 = m.frictionRow[1];
    const bool turns = m.twistRadius > 0;
    // Without a twist row the block is the tangents' 2 x 2 one: a unit third row and
    // column leave the cofactors below its inverse.
    const real k00 = invMasses + coupling(t0, t0, moving);
    const real k01 = coupling(t0, t1, moving);
    const real k11 = invMasses + coupling(t1, t1, moving);
    const real k02 = turns ? coupling(t0, m.twist, moving) : 0;
    const real k12 = turns ? coupling(t1, m.twist, moving) : 0;
    const real k22 = turns ? coupling(m.twist, m.twist, moving) : 1;
    // The symmetric inverse by cofactors.
    const real c00 = k11 * k22 - k12 * k12;
    const real c01 = k02 * k12 - k01 * k22;
    const real c02 = k01 * k12 - k02 * k11;
    const real c11 = k00 * k22 - k02 * k02;
    const real c12 = k01 * k02 - k00 * k12;
    const real c22 = k00 * k11 - k01 * k01;
    const real det = k00 * c00 + k01 * c01 + k02 * c02;
    const real inverse = det > 0 && std::isfinite(det) ? 1 / det : 0;
    out[0] = c00 * inverse, out[1] = c01 * inverse, out[3] = c11 * inverse;
    out[2] = turns ? c02 * inverse : 0;
    out[4] = turns ? c12 * inverse : 0;
    out[5] = turns ? c22 * inverse : 0;
}

// The couplings (RowCouplings) through the bodies a pass moves, whose summed inverse
// masses are invMasses. A normal row's linear terms meet another's along the same normal,
// and none of a tangent's or the twist's.
void fillCouplings(const SolverManifold &m, Moving moving, real invMasses, RowCouplings &out) {
    out = RowCouplings{};
    for (int j = 0; j < m.count; ++j) {
        const SolverRow &row = m.points[j].normal;
        for (int k = 0; k < m.count; ++k)
            if (k != j) out.normal[k][j] = invMasses + coupling(row, m.points[k].normal, moving);
        out.friction[0][j] = coupling(row, m.frictionRow[0], moving);
        out.friction[1][j] = coupling(row, m.frictionRow[1], moving);
        out.friction[2][j] = coupling(row, m.twist, moving);
    }
}

}  // namespace

void prepareCouplings(const SolverBody &a, const SolverBody &b, SolverManifold &m) {
    fillCouplings(m, kBoth, a.invMass + b.invMass, m.couplings);
    m.carriedCouplings = m.couplings;
}

void prepareJacobians(const SolverBody &sa, const SolverBody &sb, const RigidBody &bodyA, const RigidBody &bodyB,
                      SolverManifold &m, const LeverTurns &turns) {
    prepareDirections(m);
    Vector3 points[kMaxManifoldPoints];
    real depths[kMaxManifoldPoints];
    for (int i = 0; i < m.count; ++i) {
        const SolverPoint &p = m.points[i];
        const Vector3 pointA = bodyA.getPointInWorldSpace(p.localA);
        const Vector3 pointB = bodyB.getPointInWorldSpace(p.localB);
        points[i] = 0.5 * (pointA + pointB);
        depths[i] = (pointA - pointB).dot(m.normal);
        prepareRows(sa, sb, turns.leverA(points[i] - bodyA.getPosition()), turns.leverB(points[i] - bodyB.getPosition()),
                    m, m.points[i]);
    }
    const Vector3 centre = frictionCentre(depths, m.count, m.normal, points);
    prepareFrictionRows(sa, sb, points, centre, bodyA.getPosition(), bodyB.getPosition(), m, turns);
    prepareCouplings(sa, sb, m);
}

Vector3 frictionCentre(const real *depths, int count, const Vector3 &normal, Vector3 *points) {
    if (count == 0) return Vector3::Zero();
    const int deepest = static_cast<int>(std::max_element(depths, depths + count) - depths);
    const real plane = points[deepest].dot(normal);
    Vector3 centre = Vector3::Zero();
    int near = 0;
    for (int i = 0; i < count; ++i) {
        points[i] += (plane - points[i].dot(normal)) * normal;
        if (depths[i] >= depths[deepest] - kFrictionBand) centre += points[i], ++near;
    }
    return near > 0 ? Vector3(centre / near) : points[deepest];  // none near: a depth is NaN
}

CYCLONE_SIMD_CLONES
void prepareFrictionRows(const SolverBody &a, const SolverBody &b, const Vector3 *points, const Vector3 &centre,
                         const Vector3 &positionA, const Vector3 &positionB, SolverManifold &m,
                         const LeverTurns &turns) {
    // The twist radius: the torque about the normal that friction at the points could
    // give at most, per unit of friction force.
    real radius = 0;
    for (int i = 0; i < m.count; ++i) radius += (points[i] - centre).norm();
    m.twistRadius = m.count > 1 ? radius / m.count : 0;
    const RowFrame frame(a, b, turns.leverA(centre - positionA), turns.leverB(centre - positionB));
    frame.fillJacobianOnly(m.direction[1], m.frictionRow[0]);
    frame.fillJacobianOnly(m.direction[2], m.frictionRow[1]);
    fillTwistRow(frame.inertiaA, frame.inertiaB, m.direction[0], m.twist);
    invertFrictionBlock(m, kBoth, frame.invMasses, m.frictionInverse);
    std::copy(m.frictionInverse, m.frictionInverse + 6, m.carriedFrictionInverse);
}

void prepareCarriedMasses(const std::vector<SolverBody> &bodies, SolverManifold &m) {
    // Against a static or sleeping body the pair's mass is already the carried body's.
    if (m.carrier == Carrier::None || m.a == 0 || m.b == 0) return;
    const bool bMoves = m.carrier == Carrier::A;
    const real invMass = bodies[bMoves ? m.b : m.a].invMass;
    auto fill = [&](SolverRow &row, real linear) {
        const real k = linear + (bMoves ? dot3(row.rBxd, row.angB) : dot3(row.rAxd, row.angA));
        row.carriedMass = k > 0 ? 1 / k : 0;
    };
    for (int i = 0; i < m.count; ++i) fill(m.points[i].normal, invMass);
    invertFrictionBlock(m, bMoves ? kOnlyB : kOnlyA, invMass, m.carriedFrictionInverse);
    fillCouplings(m, bMoves ? kOnlyB : kOnlyA, invMass, m.carriedCouplings);
}

// Out of line, so that one thread's pass (solveUncarried) and two threads' shares
// (threads/ordered_shares.h) run the same instructions and round alike.
CYCLONE_SIMD_CLONES __attribute__((noinline))
void solveUncarriedManifold(std::vector<SolverBody> &bodies, SolverManifold &m, bool reverse) {
    PairVelocities vel(bodies[m.a], bodies[m.b]);
    solveManifold(vel, m, reverse);
    vel.store(bodies, m);
}

void solveUncarried(std::vector<SolverBody> &bodies, SolverManifolds &manifolds,
                      const std::vector<int> &order, bool reverse) {
    for (int index : order) {
        SolverManifold &m = manifolds[index];
        if (m.carrier != Carrier::None) continue;
        solveUncarriedManifold(bodies, m, reverse);
    }
}

}  // namespace cyclone::detail
