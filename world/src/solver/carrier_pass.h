// The carrier pass's runs, four at a time.
//
// Design note. A run (CarrierRuns) sweeps one carried body against its carriers, which it
// holds immovable, until a sweep changes the body's velocity by less than a tolerance
// or for a number of sweeps, both tighter for taller stacks (carrierStop). The runs of
// one level never carry one another, so four of them are solved by the same
// instructions, one run per lane, as the velocity passes solve four manifolds
// (velocity_pass.h): slot k of a group holds each lane's k-th contact with a carrier. Because only the carried body moves, a run's rows cost
// less than a velocity pass's:
// - each row is written as the carried body takes it: along the normal when it is B,
//   along the negated normal (its lever terms negated too) when it is A, so one formula
//   serves both sides;
// - the carrier's share of each row's relative velocity is a constant of the run, taken
//   once when the group is loaded;
// - the carried body's velocity stays in registers over all its contacts and sweeps.
// Each lane stops by its own test and takes no impulse after that, so a run's numbers do
// not depend on which runs share its group, nor on the thread count (threads/carrier_threads.h).
//
// A run sweeps its body against all its carriers at once. One carrier after the other
// would leave the body as high as the highest contact point of any carrier pushed it (an
// impulse that lifts it is never taken back); swept together, a carrier's impulse falls
// again when another lifts the body. Against a static or sleeping carrier a run's accumulated impulses are the true
// problem's and are kept; against a moving one they are dropped: computed with the
// carried body's mass alone, kept, they would swing the warm start of a heavy body on a
// light one by the mass ratio times its error, and the stack diverges. So they live in
// the group's copy and only the first kind is written back.
#pragma once

#include <vector>

#include "solver/contact_solver.h"
#include "solver/simd/batch4.h"

namespace cyclone::detail {

/// One row's terms for the carried bodies of four runs, d pointing into each body.
struct WideCarriedRow {
    WideVector rxd;  ///< r x d, r from the carried body's centre to the row's point.
    WideVector ang;  ///< I^-1 (r x d) of the carried body.
};

/// The k-th contact of four runs with a carrier, as their carried bodies take it. Lanes
/// without such a contact hold zero rows, which change nothing.
struct WideCarriedContact {
    WideVector normal, tangent[2];  ///< The manifold's, negated where the carried body is A.
    WideCarriedRow points[kMaxManifoldPoints];
    Lanes mass[kMaxManifoldPoints]{};     ///< Effective mass with the carrier immovable, kg.
    Lanes impulse[kMaxManifoldPoints]{};  ///< Accumulated normal impulse, N s.
    Lanes bias[kMaxManifoldPoints]{};     ///< Target normal velocity, m/s.
    Lanes carrier[kMaxManifoldPoints]{};  ///< The carrier's share of the normal velocity, m/s.
    WideCarriedRow friction[2];           ///< Along tangent[0], tangent[1].
    WideVector twist;                     ///< I^-1 normal (the twist row's r x d is the normal).
    Lanes frictionCarrier[3]{};  ///< The carrier's share along the tangents (m/s) and about the normal (rad/s), less the tangents' targets (SolverRow::target).
    Lanes frictionImpulse[2]{};  ///< N s.
    Lanes twistImpulse{};        ///< N m s.
    Lanes frictionInverse[6]{};  ///< SolverManifold::carriedFrictionInverse.
    /// SolverManifold::carriedCouplings in lanes, as ManifoldBatch holds the couplings.
    Lanes normalCoupling[kMaxManifoldPoints][kMaxManifoldPoints]{};
    Lanes frictionCoupling[3][kMaxManifoldPoints]{};
    Lanes coefficient{};  ///< Friction coefficient (0: no friction rows).
    Lanes twistRadius{};  ///< m (0: no twist row).
};

/// One thread's copy of a group's contacts, kept so that a step allocates nothing, and
/// its count of the sweeps it gave runs.
struct CarrierPassScratch {
    std::vector<WideCarriedContact> contacts;
    long sweeps = 0;  ///< Sweeps of single runs, summed (a group's sweep counts once per run still going).
    int laneSweeps[kWideLanes] = {};  ///< Sweeps of each run of the last group solved.
};

/// Solves runs run[0 .. count) (count <= kWideLanes, all of one level, their carriers'
/// runs finished) side by side, every sweep from the last point of each contact with
/// `reverse`.
void solveCarriedRuns(std::vector<SolverBody> &bodies, SolverManifolds &manifolds,
                      const CarrierRuns &runs, const int *run, int count, bool reverse, CarrierPassScratch &scratch);

}  // namespace cyclone::detail
