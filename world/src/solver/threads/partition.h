// Which manifolds two threads may solve at once.
//
// Design note. A velocity pass is Gauss-Seidel: one manifold reads the velocities the one
// before it wrote. Split the moving bodies in two halves by place (a plane through the
// median body across the scene's widest extent): manifolds inside one half never touch a
// body of the other, so the two halves' manifolds commute and can be solved by two
// threads; the seam, whose manifolds join the halves, is solved after both. The split
// depends on the scene only, never on the thread count, so a world gives the same
// numbers with one thread or several. Small scenes are not split: their pass is too short
// to share, and they keep the plain order.
#pragma once

#include <vector>

#include "solver/contact_solver.h"
#include "solver/schedule.h"

namespace cyclone::detail {

/// Scenes with fewer manifolds than this keep one list (no split).
inline constexpr int kMinSplitManifolds = 128;

/// The velocity passes' order in three parts: the two halves (solvable at once), then the
/// seam. Unsplit, part 0 holds every manifold in the solve order and the others are empty.
struct SolverPartition {
    static constexpr int kSeam = 2;
    std::vector<int> order[3];          ///< Manifold indices of each part, in solve order.
    /// The same, grouped (schedule.h). For one thread, groups[0] holds both
    /// halves' groups, in one list (they fill more lanes), and groups[1] is empty.
    std::vector<SolverGroup> groups[3];
    bool split = false;
};

/// Scratch kept between steps (no allocation in a steady step).
struct PartitionScratch {
    std::vector<real> places;
    std::vector<signed char> side;
    std::vector<int> halves;  ///< Both halves' manifolds, in one list.
    ScheduleScratch schedule;
};

/// Splits the manifolds listed in `order` (lowest contact first, at `heights`) by
/// `positions` of the solver bodies (entry 0, the immovable world, is ignored) and
/// schedules each part (buildLevelSchedule), each half's groups apart only for
/// `twoThreads`. The orders, and so the numbers, do not depend on it.
void partitionManifolds(const SolverManifolds &manifolds, const std::vector<real> &heights,
                        const std::vector<int> &order, const std::vector<Vector3> &positions, bool twoThreads,
                        PartitionScratch &scratch, SolverPartition &partition);

}  // namespace cyclone::detail
