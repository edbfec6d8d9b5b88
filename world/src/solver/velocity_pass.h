// The velocity pass, four manifolds at a time.
//
// Design note. A pass over one manifold is a chain: each row reads the velocities the row
// before it wrote, and waits for them. Four manifolds that share no moving body commute
// (schedule.h groups them), so their rows can be solved by the same instructions,
// one manifold per lane: ManifoldBatch holds a group's rows side by side, lane k of each
// field being member k's, with the x, y and z of each vector in lanes of their own (no
// sums across lanes). A row of four manifolds then costs what a row of one did. Within a
// manifold the rows are solved as ManifoldSweep (contact_solver.cpp) solves them: one
// after another, each impulse reaching the later rows through the couplings, so the
// numbers are row-by-row Gauss-Seidel's.
//
// The rows are copied in at the start of a step's first sub-step, each group giving the
// bodies its warm-start impulses as it is copied (loadBatches); a later sub-step copies
// again only what changed, the impulses and targets (reloadBatches). The accumulated
// impulses go back after the velocity passes (storeBatches): a pass reads only the rows
// it solves, 3648 bytes per group of four (912 per manifold; a SolverManifold is
// 2304). The rows hold no angular terms I^-1 (r x d): a pass sums each side's lever
// impulses, sum of impulse times (r x d), and turns the sum by the body's inverse inertia
// once, which the group holds per lane (the passes stream the rows from memory on large
// scenes, so bytes count more than the extra products: docs/solver.md, "How the passes
// are made fast"). A lane past a group's size, and a point past a member's count, hold
// zero rows, which change nothing.
#pragma once

#include <vector>

#include "solver/contact_solver.h"
#include "solver/schedule.h"
#include "solver/simd/batch4.h"

namespace cyclone::detail {

static_assert(kGroupSize == kWideLanes, "a group fills one wide manifold");

/// One row's lever terms for four manifolds (SolverRow's rAxd and rBxd).
struct WideRow {
    WideVector rAxd, rBxd;  ///< rA x d, rB x d.
};

/// One point's normal row for four manifolds.
struct WidePoint {
    WideRow row;
    Lanes mass{};     ///< Effective mass, kg.
    Lanes impulse{};  ///< Accumulated impulse, N s.
    Lanes bias{};     ///< Target normal velocity, m/s.
};

/// The rows of up to four manifolds that share no moving body (a SolverGroup).
struct ManifoldBatch {
    int a[kWideLanes] = {};  ///< Solver bodies of each lane (0 = the immovable world).
    int b[kWideLanes] = {};
    int size = 0;  ///< Lanes in use.
    Lanes invMassA{}, invMassB{};
    WideVector normal, tangent[2];
    WidePoint points[kMaxManifoldPoints];
    WideRow friction[2];            ///< Along tangent[0], tangent[1].
    Lanes frictionTarget[2]{};      ///< Their SolverRow::target, m/s.
    /// World-space inverse inertia of each lane's A and B (SolverBody::invInertia, the
    /// step's), 1/(kg m^2). The twist row's lever terms are the normal itself.
    WideSymmetric invInertiaA, invInertiaB;
    Lanes frictionImpulse[2]{};     ///< N s.
    Lanes twistImpulse{};           ///< N m s.
    Lanes frictionInverse[6]{};     ///< SolverManifold::frictionInverse.
    /// RowCouplings in lanes: [k][j] is point j's normal velocity change per N s on point
    /// k's normal row (0 for j = k), and per N s on tangent 0, tangent 1, the twist.
    Lanes normalCoupling[kMaxManifoldPoints][kMaxManifoldPoints]{};
    Lanes frictionCoupling[3][kMaxManifoldPoints]{};
    Lanes coefficient{};            ///< Friction coefficient (0: no friction rows).
    Lanes twistRadius{};            ///< m (0: no twist row).
};

struct PenetrationBatch;

/// Copies the rows of the manifolds of `groups` into `wide`, one per group, and with
/// `warmStart` gives the bodies each group's accumulated impulses once it is copied, as
/// warmStart (contact_solver.h) does for its manifolds. With `pseudo`, also copies what
/// the penetration pass needs into it, one per group (loadPseudo).
void loadBatches(std::vector<SolverBody> &bodies, const SolverManifolds &manifolds, const std::vector<SolverGroup> &groups,
              bool warmStart, std::vector<ManifoldBatch> &wide, std::vector<PenetrationBatch> *pseudo = nullptr);
/// What loadBatches copies that changes between the sub-steps of one step (the
/// accumulated impulses, the targets, the bodies' inverse masses and inertias), copied
/// again into `wide`, loaded by loadBatches from the same `groups` and manifolds earlier
/// in the step, then the warm start as loadBatches makes it. The rows, made once a step,
/// are left as they are, and so is what the penetration pass took (its anchors).
void reloadBatches(std::vector<SolverBody> &bodies, const SolverManifolds &manifolds,
                   const std::vector<SolverGroup> &groups, bool warmStart, std::vector<ManifoldBatch> &wide);
/// One velocity pass over the wide manifolds, in order: in each, friction and then the
/// points' normal rows, from the last point with `reverse` (alternating passes keep the
/// first point from taking the largest share of a new contact's load, which would tilt
/// the body).
void solveVelocityBatches(std::vector<SolverBody> &bodies, std::vector<ManifoldBatch> &wide, bool reverse);
/// Copies the accumulated impulses back to the manifolds of `groups`.
void storeBatches(const std::vector<ManifoldBatch> &wide, const std::vector<SolverGroup> &groups,
               SolverManifolds &manifolds);

}  // namespace cyclone::detail
