// The order in which a coupled velocity pass visits the manifolds, in groups it can solve
// side by side.
//
// Design note. Gauss-Seidel is a chain: each row reads the velocities the row before it
// wrote, so one manifold's rows run one after another at the speed of the CPU's latency,
// not its throughput. Two manifolds that share no moving body commute: solving them in
// either order, or at once row by row, gives the same numbers. The schedule puts such
// manifolds into groups of up to kGroupSize, keeping the result of the plain order: a
// manifold is taken forward into an earlier group only past manifolds it shares no
// moving body with. A pass solves a group's manifolds at once, one per SIMD lane
// (wide_pass.h).
#pragma once

#include <vector>

#include "contact_solver.h"

namespace cyclone::detail {

inline constexpr int kGroupSize = 4;

/// Manifolds solved side by side (indices into the manifold array; `size` of them).
struct SolverGroup {
    int manifold[kGroupSize];
    int size = 0;
};

/// How far ahead (in manifolds) the schedule looks for a group's members: at 8, groups
/// of four held 73 % of pyramid40's manifolds, at 16 90 %, at 32 92 %.
inline constexpr int kScheduleWindow = 16;

/// buildSchedule's working memory, kept between steps.
struct ScheduleScratch {
    std::vector<char> taken;     ///< Per entry of `order`: already in a group.
    std::vector<int> blockedFor;  ///< Per body: the group start it is blocked for.
};

/// Groups the manifolds listed in `order` (indices into `manifolds`), keeping that
/// order's results.
void buildSchedule(const std::vector<SolverManifold> &manifolds, const std::vector<int> &order,
                   std::vector<SolverGroup> &groups, ScheduleScratch &scratch);

}  // namespace cyclone::detail
