// The carrier pass on two threads without a barrier per level.
//
// Design note. The carrier pass sets each carried body at rest on its carriers, bottom
// up. A run (one carried body against its carriers, CarrierRuns) reads only its carriers,
// which are one level lower or more, and writes only its own body: once every carrier's
// run has finished, the run gives the same numbers whenever and on whichever thread it
// runs. So each thread takes the runs of its half of the partition (threads/partition.h)
// level by level, and before a run waits only for those of its carriers that the other
// thread solves: they lie near the seam. Waiting level by level for both threads instead
// would cost a hand-over per level and leave one thread idle on a stack's narrow top.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/carrier_pass.h"
#include "solver/contact_solver.h"
#include "solver/threads/pass_flags.h"

namespace cyclone::detail {

struct CarrierThreads {
    /// Runs of each thread's share, level by level; share 1 is empty when not shared.
    std::vector<int> share[2];
    std::vector<int> runOf;     ///< Per solver body: its run, or -1 (none: final before the pass).
    std::vector<int> runLevel;  ///< Per run: its level.
    std::vector<int> runBody;   ///< Per run: its carried body.
    /// Per solver body: the sweeps its run took in the last carrier pass that gave it one (0
    /// before any). The runs of a level are taken in this order, so that runs that swept
    /// alike share a group; only the cost depends on it.
    std::vector<int> sweepsOf;
    std::vector<int> sortCount, sortScratch;  ///< Scratch of the runs' order, kept so that a step allocates nothing.
    PassFlags finished;  ///< Per run: whether it finished in this pass.
    CarrierPassScratch scratch[2];  ///< Per share.
};

/// Lists the runs of each thread's share: with `side` (per solver body, 0 or 1; the partition's
/// halves) a run goes to its carried body's side, without it every run goes to share 0.
void buildCarrierThreads(const CarrierRuns &runs, const SolverManifolds &manifolds,
                       const std::vector<signed char> *side, int bodyCount, CarrierThreads &threads);

/// Solves the runs of share `share` in order, each once its carriers' runs have finished (a
/// carrier in the other share may still be running: this waits for it).
void solveCarrierShare(std::vector<SolverBody> &bodies, SolverManifolds &manifolds, CarrierRuns &runs,
                      CarrierThreads &threads, int share, bool reverse);

}  // namespace cyclone::detail
