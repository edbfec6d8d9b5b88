// The contact solver: sequential impulses with accumulated-impulse clamping, warm
// starting, Coulomb friction per contact patch (two tangents and a twist), restitution
// above a threshold, and penetration recovery by pseudo-velocities (split impulse) that
// never add energy.
//
// Design note. The solver works on its own contiguous arrays (SolverBody,
// SolverManifold) rather than on RigidBody: those are what every iteration touches.
// World copies the predicted velocities in, and hands the result back to each body
// through RigidBody::addVelocity / addRotation before RigidBody::integrate. Entry 0 of
// the body array is the immovable "world" (zero inverse mass and inertia), which every
// static body maps to, so the iterations need no branches for static contacts.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/body.h"
#include "cyclone/core.h"
#include "solver/simd/vector4.h"
#include "world/block_array.h"

namespace cyclone::detail {

/// Velocity state of one awake dynamic body during the solve. The velocities are held in
/// lanes (simd/vector4.h): the passes read and write nothing else.
struct SolverBody {
    Lanes v{};   ///< Linear velocity, m/s.
    Lanes w{};   ///< Angular velocity, rad/s.
    Lanes pv{};  ///< Pseudo linear velocity (penetration recovery only), m/s.
    Lanes pw{};  ///< Pseudo angular velocity, rad/s.
    real invMass = 0;                      ///< 1/kg.
    Matrix3 invInertia = Matrix3::Zero();  ///< World space, 1/(kg m^2).
};

/// One constraint direction at a point: Jacobian terms and the accumulated impulse. The
/// angular terms come last: the velocity passes' loader (loadBatches) reads the rest, and
/// in a SolverPoint the row's last cache line then holds nothing else.
struct SolverRow {
    /// Effective mass along d, kg. Normal rows only: the friction rows are solved as a
    /// block through SolverManifold::frictionInverse and leave both masses unset.
    real mass = 0;
    real carriedMass = 0;  ///< Effective mass with the carrier immovable (carrier pass), kg.
    real impulse = 0;  ///< Accumulated impulse, N s.
    /// Relative velocity of the bodies along d the row drives towards, m/s: friction rows
    /// only, minus B's surface velocity relative to A's along d
    /// (PreSolveContact::surfaceVelocity), at which the surfaces do not slide; 0 on a
    /// normal row, whose target is the point's velocityBias.
    real target = 0;
    Lanes rAxd{};      ///< rA x d.
    Lanes rBxd{};      ///< rB x d.
    Lanes angA{};      ///< IA^-1 (rA x d).
    Lanes angB{};      ///< IB^-1 (rB x d).
};

/// The fields that the depth loop (ConstraintSolver::solveVelocities) and loadBatches
/// read and write come first, in the point's first cache lines, and the row last, where
/// its lanes need no padding: 256 bytes in all. loadPseudo (penetration_pass.h) reads localA, localB and depth
/// as one run of reals.
struct SolverPoint {
    Vector3 localA;          ///< Anchor on A, A's body space, m.
    Vector3 localB;          ///< Anchor on B, B's body space, m.
    real depth = 0;          ///< Penetration at the start of the step, m (< 0: apart).
    real velocityBias = 0;   ///< Target normal velocity (restitution or speculative), m/s.
    real approachSpeed = 0;  ///< Normal relative velocity when the step began, m/s.
    real maxNormalImpulse = 0;  ///< Largest normal impulse of the step, N s.
    SolverRow normal;
};

inline constexpr int kMaxManifoldPoints = 4;

/// The order of a pass over one manifold's rows (ManifoldSweep in contact_solver.cpp,
/// WideSweep in velocity_pass.cpp, CarriedSweep in carrier_pass.cpp): the patch's friction,
/// then the `count` points' normal rows, from the last with `reverse` (alternate passes
/// keep the first point from taking the largest share of a new load), then the impulses
/// reach the bodies.
template <class Sweep>
CYCLONE_INLINE void sweepRows(Sweep &sweep, int count, bool reverse) {
    sweep.friction();
    if (reverse) {
        for (int i = count - 1; i >= 0; --i) sweep.normal(i);
    } else {
        for (int i = 0; i < count; ++i) sweep.normal(i);
    }
    sweep.finish();
}

/// How an impulse on one row of a manifold changes the relative velocity along its
/// points' normal rows, per N s: lane j of an entry is point j's. A pass solves the
/// manifold's rows one after another, as Gauss-Seidel does, but reads the bodies'
/// velocities once and tracks the normal velocities through these (ManifoldSweep in
/// contact_solver.cpp; WideSweep in velocity_pass.cpp, from loadBatches's copy).
/// Lanes past the manifold's count, and point k's own lane of normal[k], are zero.
struct RowCouplings {
    Lanes normal[kMaxManifoldPoints];  ///< Per unit impulse on point k's normal row.
    Lanes friction[3];                 ///< Per unit impulse on tangent 0, tangent 1, the twist.
};

/// Most Gauss-Seidel sweeps the carrier pass gives one body against the bodies that
/// carry it: one sweep over a face's four corners leaves the body turning, and a stack
/// leans (the choice of 12: docs/solver.md, "The carrier pass").
inline constexpr int kCarrierSweeps = 12;
/// The carrier pass stops sweeping a contact once no impulse changes a relative
/// velocity by more than this, m/s (10 s of such an error would move a body 0.1 mm).
inline constexpr real kCarrierTolerance = 1e-5;
/// Up to this many levels of carried bodies kCarrierTolerance and kCarrierSweeps hold.
/// What a run leaves of its body's velocity relative to its carriers is the next level's
/// carrier velocity, so the residuals add up with the stack's height, and Gauss-Seidel
/// over a face's corners is far from rest when one sweep still changes it by the
/// tolerance: taller stacks need a tighter stop (carrierStop).
inline constexpr int kCarrierLevels = 20;

/// The carrier pass's stopping test for a world whose tallest stack has `levels` levels
/// of carried bodies: kCarrierTolerance and kCarrierSweeps up to kCarrierLevels levels;
/// beyond, the tolerance times (kCarrierLevels / levels)^5 and the cap times
/// levels / kCarrierLevels (the power chosen on the 200-level pyramid, whose top layers a
/// power of 4 let sway past 1 cm: docs/solver.md, "The carrier pass").
struct CarrierStop {
    real tolerance = kCarrierTolerance;  ///< m/s
    int sweeps = kCarrierSweeps;
};

inline CarrierStop carrierStop(int levels) {
    CarrierStop stop;
    if (levels <= kCarrierLevels) return stop;
    const real ratio = real(kCarrierLevels) / levels;
    stop.tolerance *= (ratio * ratio) * (ratio * ratio) * ratio;
    stop.sweeps = kCarrierSweeps * levels / kCarrierLevels;
    return stop;
}

/// Friction acts on the manifold's contact patch as a whole, not point by point: two
/// tangent rows at the centre of its points, limited together to the friction cone of the
/// points' summed normal impulse, and a twist row about the normal, limited by the same
/// sum times twistRadius (the points' mean distance from the centre: the torque that
/// friction at the points could give at most). For a one-point contact that is the
/// per-point model; a face's four corners need three friction rows instead of eight.
/// Which body of a manifold carries the other in a resting stack.
enum class Carrier : int {
    None,  ///< Neither: the carrier pass leaves the manifold to the velocity passes.
    A,     ///< A carries B.
    B,     ///< B carries A.
};

/// Aligned to cache lines, so that each SolverPoint's fields lie on the lines its layout
/// intends (the points start 1280 bytes in).
struct alignas(64) SolverManifold {
    int a = 0;  ///< Index into the SolverBody array (0 = static world).
    int b = 0;
    Vector3 normal;      ///< From A to B.
    Vector3 tangent[2];
    Lanes direction[3]{};  ///< normal, tangent[0], tangent[1] in lanes (prepareDirections).
    SolverRow frictionRow[2];  ///< Along tangent[0], tangent[1], at the patch's centre.
    SolverRow twist;           ///< About the normal (its rAxd and rBxd are the normal).
    real twistRadius = 0;      ///< Mean distance of the points from the centre, m (0: no twist row).
    /// The inverse of the friction rows' 3 x 3 effective-mass matrix (tangents, twist),
    /// upper triangle row by row: the three rows are solved together, exactly, because
    /// the centre's lever arm couples a tangent with the twist. Without a twist row it is
    /// the tangents' 2 x 2 inverse (entries 2, 4, 5 zero).
    real frictionInverse[6] = {};
    real carriedFrictionInverse[6] = {};  ///< The same with the carrying body immovable.
    RowCouplings couplings{};           ///< Through both bodies.
    RowCouplings carriedCouplings{};  ///< Through the carried body alone (carrier pass).
    real friction = 0;
    real restitution = 0;
    /// Which body carries the other (the carrier pass treats it as immovable). A static
    /// or sleeping side always does. See assignCarriers().
    Carrier carrier = Carrier::None;
    int count = 0;
    /// The order the passes solve the points in: the k-th is points[order[k]] (k past
    /// count: k itself). A point's row stays where its Jacobians were made; when a kept
    /// manifold's points come in another order (ConstraintSolver::addSolverManifold), this
    /// changes, not where the rows are.
    signed char order[kMaxManifoldPoints] = {0, 1, 2, 3};
    SolverPoint points[kMaxManifoldPoints];
};

/// The step's solver manifolds by slot: kept from step to step (their Jacobians may
/// hold), and grown a block at a time, so that a few more manifolds move none.
using SolverManifolds = BlockArray<SolverManifold>;

/// The couplings of a manifold (its own or its carried ones) in its solve order: entry k
/// is the k-th point's, lane l the l-th point's. The loaders pick each entry's lanes in
/// registers as they copy it into a group's lanes, with no permuted copy of the couplings
/// made (a resting pyramid's manifolds solve their points in another order than their
/// rows' three steps in four). The lanes are picked as pairs of 32-bit words, one
/// instruction per entry where the CPU has AVX2 (vpermd).
struct CouplingOrder {
    using Words = int __attribute__((vector_size(8 * sizeof(int))));
    const signed char *order;  ///< SolverManifold::order.
    Words pick;

    CYCLONE_INLINE explicit CouplingOrder(const SolverManifold &m)
        : order(m.order),
          pick{2 * order[0], 2 * order[0] + 1, 2 * order[1], 2 * order[1] + 1,
               2 * order[2], 2 * order[2] + 1, 2 * order[3], 2 * order[3] + 1} {}

    /// Entry k of c.normal in solve order, into `out`.
    CYCLONE_INLINE void normal(const RowCouplings &c, int k, Lanes &out) const { picked(c.normal[order[k]], out); }
    /// Entry r of c.friction with its lanes in solve order, into `out`.
    CYCLONE_INLINE void friction(const RowCouplings &c, int r, Lanes &out) const { picked(c.friction[r], out); }

private:
    CYCLONE_INLINE void picked(const Lanes &entry, Lanes &out) const {
        out = reinterpret_cast<Lanes>(__builtin_shuffle(reinterpret_cast<Words>(entry), pick));
    }
};

/// The carrier pass's order (assignCarriers): the carried bodies bottom up; run r is one
/// body's manifolds with its carriers, manifolds[start[r] .. start[r + 1]). A level holds
/// the bodies equally far from the ground (in contacts); no body carries another of its
/// level.
struct CarrierRuns {
    std::vector<int> start;
    std::vector<int> levelStart;  ///< Level l's runs are [levelStart[l], levelStart[l + 1]).
    std::vector<int> manifolds;
    /// The manifolds without a carrier, in the solve order: the carrier pass's first pass
    /// (solveUncarried) takes these alone.
    std::vector<int> uncarried;
};

/// Tangents of a normal: deterministic, so that the same normal gives the same basis
/// every step and warm-started friction stays meaningful.
void tangentBasis(const Vector3 &normal, Vector3 &t1, Vector3 &t2);

/// Copies a manifold's normal and tangents into its lanes (before prepareRows).
void prepareDirections(SolverManifold &m);

/// Relative velocity of B with respect to A along a point's normal, m/s.
real normalVelocity(const SolverBody &a, const SolverBody &b, const SolverManifold &m, const SolverPoint &p);

/// Fills the Jacobian terms and effective mass of one point's normal row.
void prepareRows(const SolverBody &a, const SolverBody &b, const Vector3 &rA, const Vector3 &rB,
                 const SolverManifold &m, SolverPoint &p);
/// The turns that take each side's lever arms from the step's start to mid-step: a moving
/// kinematic body's surface point, moving at its velocity there, goes straight along the
/// chord of its arc over the step (docs/kinematic.md). Identity for any other body.
struct LeverTurns {
    Matrix3 a = Matrix3::Identity();
    Matrix3 b = Matrix3::Identity();
    bool any = false;  ///< Whether either is not the identity.
    Vector3 leverA(const Vector3 &r) const { return any ? Vector3(a * r) : r; }
    Vector3 leverB(const Vector3 &r) const { return any ? Vector3(b * r) : r; }
};

/// How much farther apart than the deepest point of its manifold a point may lie and
/// still take part in the centre of the manifold's friction, m (frictionCentre;
/// docs/solver.md, "Figures behind constants in the code").
inline constexpr real kFrictionBand = 0.02;

/// The centre a manifold's friction acts at. Moves its points (midpoints between the
/// anchors, world space, `count` of them, `depths` their depths along `normal`) along the
/// normal into the plane through the deepest one, and returns the centre of those within
/// kFrictionBand of it. A point far apart (a turning rod's other end, up to the landing
/// reach away) bears no load this step; friction at a centre lifted off the surfaces has
/// a lever about the body's axes that no contact has: a needle, whose moment about its
/// own axis is a thousandth of the others, spun up and gained energy.
Vector3 frictionCentre(const real *depths, int count, const Vector3 &normal, Vector3 *points);

/// Fills the manifold's patch friction from its points (world space, m.count of them, in
/// the contact plane: frictionCentre), the centre friction acts at and the bodies'
/// centres of mass: the twist radius (the points' mean distance from the centre), the
/// friction rows at the centre, the twist row and frictionInverse.
void prepareFrictionRows(const SolverBody &a, const SolverBody &b, const Vector3 *points, const Vector3 &centre,
                         const Vector3 &positionA, const Vector3 &positionB, SolverManifold &m,
                         const LeverTurns &turns = LeverTurns());

/// Fills the manifold's couplings from its rows (after prepareRows and
/// prepareFrictionRows), and its carried couplings with the same.
void prepareCouplings(const SolverBody &a, const SolverBody &b, SolverManifold &m);

/// Makes the manifold's Jacobians (its directions, point rows, friction rows and
/// couplings; its normal and tangents set) for bodies `bodyA` and `bodyB` (solver bodies
/// sa and sb) at their poses now, lever arms turned by `turns`. The step's and a saved
/// state's restore (snapshot/solver_slots.h) go through it, so that both make the same bits.
void prepareJacobians(const SolverBody &sa, const SolverBody &sb, const RigidBody &bodyA, const RigidBody &bodyB,
                      SolverManifold &m, const LeverTurns &turns = LeverTurns());

/// Fills carriedMass and the carried couplings of a manifold that has a carrying
/// side (after assignCarriers).
void prepareCarriedMasses(const std::vector<SolverBody> &bodies, SolverManifold &m);

/// The carrier pass, run after the velocity passes: first one plain
/// pass over the manifolds where neither side carries the other, in `order`
/// (solveUncarried), then,
/// level by level bottom up (CarrierRuns::levelStart), each carried body against its
/// carriers as immovable bodies with up to kCarrierSweeps sweeps (solveCarriedRuns in
/// carrier_pass.h, four runs at a time; threads/carrier_threads.h on two threads). It leaves
/// no body of a resting stack sinking into the one below or turning on it, whatever
/// their mass ratio (plain Gauss-Seidel converges ever slower as a heavy body rests on a
/// lighter one). Its impulses change velocities only: the accumulated impulses stay those
/// of the velocity passes. The runs of one level are independent: any of them may be
/// solved at the same time.
void solveUncarried(std::vector<SolverBody> &bodies, SolverManifolds &manifolds,
                      const std::vector<int> &order, bool reverse);
/// solveUncarried's pass for one manifold without a carrier (threads/ordered_shares.h
/// shares that pass's manifolds between threads).
void solveUncarriedManifold(std::vector<SolverBody> &bodies, SolverManifold &m, bool reverse);

}  // namespace cyclone::detail
