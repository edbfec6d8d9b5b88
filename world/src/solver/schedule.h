// The order in which a velocity pass visits the manifolds, in groups it can solve
// side by side.
//
// Design note. Gauss-Seidel is a chain: each row reads the velocities the row before it
// wrote, so one manifold's rows run one after another at the speed of the CPU's latency,
// not its throughput. Two manifolds that share no moving body commute: solving them in
// either order, or at once row by row, gives the same numbers. The schedule puts such
// manifolds into groups of up to kGroupSize, keeping the result of the plain order: a
// manifold is taken forward into an earlier group only past manifolds it shares no
// moving body with. A pass solves a group's manifolds at once, one per SIMD lane
// (velocity_pass.h).
//
// The plain order is by contact height, and a layer of a stack has its contacts at one
// height but for rounding: their order within the layer is rounding's choice, and in it
// few contacts of a chain (a box on two, each of those on two more) could pass the
// others. The level schedule lets a manifold pass a level one too, which keeps the order
// by height but picks the order within a level for the groups (how full they are:
// docs/solver.md, "How the passes are made fast").
#pragma once

#include <vector>

#include "solver/contact_solver.h"

namespace cyclone::detail {

inline constexpr int kGroupSize = 4;

/// Manifolds solved side by side (indices into the manifold array; `size` of them).
struct SolverGroup {
    int manifold[kGroupSize];
    int size = 0;
};

/// How far ahead (in manifolds) the schedule looks for a group's members (the choice:
/// docs/solver.md, "How the passes are made fast").
inline constexpr int kScheduleWindow = 16;

/// Contacts within this height of each other (m along -gravity) are taken as level: the
/// solve order puts lower contacts first, and among level ones it follows rounding only.
inline constexpr real kLevelBand = 1e-3;

/// buildSchedule's working memory, kept between steps.
struct ScheduleScratch {
    std::vector<char> taken;         ///< Per entry of `order`: already in a group.
    std::vector<int> joinedFor;      ///< Per body: the group start whose members move it.
    std::vector<int> waitingFor;     ///< Per body: the group start a waiting manifold moving it was passed for.
    std::vector<int> firstWaiting;   ///< The first such manifold.
};

/// Groups the manifolds listed in `order` (indices into `manifolds`), keeping that
/// order's results, and lists them in `order` as the groups take them (the same results).
void buildSchedule(const SolverManifolds &manifolds, std::vector<int> &order,
                   std::vector<SolverGroup> &groups, ScheduleScratch &scratch);

/// The same for `order` listed by height (`heights` of each manifold, lowest first), but a
/// manifold may also move past one it shares a moving body with when the two are level
/// (kLevelBand); `order` then lists the order whose results the groups keep.
void buildLevelSchedule(const SolverManifolds &manifolds, const std::vector<real> &heights,
                        std::vector<int> &order, std::vector<SolverGroup> &groups, ScheduleScratch &scratch);

}  // namespace cyclone::detail
