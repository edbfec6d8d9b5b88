// Penetration recovery (split impulse), four manifolds at a time.
//
// Design note. A pseudo-velocity pass is a velocity pass without friction, on the bodies'
// pseudo-velocities: each point's normal row pushes towards a target set from its depth.
// Solved one manifold at a time, each manifold's rows would wait on one another, as a
// velocity pass's would (velocity_pass.h). This pass runs on the same
// groups and the same wide rows (ManifoldBatch, copied by loadBatches), plus what only it
// needs (PenetrationBatch, copied with them): the anchors its depths come from and which
// bodies the carrier pass moves. The groups keep the results of the plain order
// (schedule.h), so the numbers are those of solving manifold after manifold.
#pragma once

#include <vector>

#include "solver/velocity_pass.h"

namespace cyclone::detail {

/// Where a manifold's bodies are, as far as its points' depths need: with anchors a on A
/// and b on B, the depth (xA + RA a - xB - RB b) . n is a . (RA^T n) - b . (RB^T n) +
/// (xA - xB) . n, two dot products a point instead of two rotations.
struct DepthFrame {
    Vector3 normalA;  ///< RA^T n.
    Vector3 normalB;  ///< RB^T n.
    real offset = 0;  ///< (xA - xB) . n, m.
    real of(const SolverPoint &p) const { return p.localA.dot(normalA) - p.localB.dot(normalB) + offset; }
};

/// What the first penetration pass of a sub-step sets its targets from.
struct PseudoTargets {
    const DepthFrame *frames = nullptr;  ///< Per manifold, at the poses after integration.
    real slop = 0;                       ///< Penetration left alone, m.
    real recoveryRate = 0;               ///< Of the depth beyond the slop, per second.
};

/// What the penetration pass needs of a group beyond its ManifoldBatch.
struct PenetrationBatch {
    WideVector localA[kMaxManifoldPoints];  ///< Anchors on A, A's body space, in solve order, m.
    WideVector localB[kMaxManifoldPoints];  ///< Anchors on B, B's body space, m.
    Lanes count{};                          ///< Points of each lane's manifold.
    /// The pass with the carrier pass (the last of a sub-step): where a lane has a
    /// carrier (SolverManifold::carrier, Carrier::None without the carrier pass), only the
    /// carried body moves. 1 where that side moves, else 0.
    Lanes moveA{}, moveB{};
    Lanes target[kMaxManifoldPoints]{};   ///< Pseudo normal velocity aimed at, m/s.
    Lanes impulse[kMaxManifoldPoints]{};  ///< Accumulated pseudo impulse, N s.
};

/// Copies into `out` what the penetration pass needs of the four manifolds `m` (those of
/// one group, padded with empty ones). Called by loadBatches while the manifolds are in the
/// cache.
void loadPseudo(const SolverManifold *const m[kWideLanes], PenetrationBatch &out);

/// One penetration pass over a part's wide manifolds, in order (pseudo[g] goes with
/// wide[g]). With `carried` (the carrier pass), lanes with a carrier move only the
/// carried body. With `targets` (the sub-step's first pass), each group's targets are
/// set first from its depths at `targets->frames` (`groups` name each lane's manifold)
/// and its impulses cleared; a group with no target anywhere is then left alone, as its
/// pass would change nothing. Returns whether any point had a target.
bool solvePenetrationBatches(std::vector<SolverBody> &bodies, const std::vector<ManifoldBatch> &wide,
                     std::vector<PenetrationBatch> &pseudo, const std::vector<SolverGroup> &groups, bool carried,
                     const PseudoTargets *targets);

}  // namespace cyclone::detail
