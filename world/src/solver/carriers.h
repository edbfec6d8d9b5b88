// Who carries whom in a resting stack, for the solver's carrier pass (shock propagation).
#pragma once

#include <vector>

#include "solver/contact_solver.h"

namespace cyclone::detail {

/// Scratch of assignCarriers, kept between steps so that a step allocates nothing.
struct CarrierScratch {
    std::vector<int> level;     ///< Per solver body: contacts away from an immovable body.
    std::vector<int> start;     ///< Per solver body: first entry in `adjacent`.
    std::vector<int> adjacent;  ///< Neighbours of each body, body by body.
    std::vector<int> queue;
    std::vector<int> count;   ///< Per solver body: its manifolds with a carrier.
    std::vector<int> met;     ///< Carried bodies in the order of their first manifolds.
    std::vector<int> bodies;  ///< The same, by level.
    std::vector<int> cursor;  ///< Per level, then per solver body: the next entry to write.
};

/// Sets `support` of every manifold. A static or sleeping side (solver body 0) always
/// supports the other. A body's level is the number of contacts between it
/// and an immovable body (solver body 0: static or asleep), found breadth-first over the
/// manifolds. A manifold between levels k and k + 1 whose upper body rests on the lower
/// one (normal within 60 degrees of `up`) names the lower as the support. Between two
/// moving bodies, those at the same level, side contacts and worlds without gravity
/// (`up` zero) get none.
/// `bodyCount` counts the solver bodies, body 0 included; entries from `firstKinematic`
/// on are moving kinematic bodies, immovable like body 0 (bodyCount when none).
/// Also lists the carrier pass's runs (CarrierRuns) bottom up; within a level, the
/// bodies and each body's manifolds in the solve order `order` (manifold indices).
void assignCarriers(int bodyCount, int firstKinematic, const Vector3 &up, std::vector<SolverManifold> &manifolds,
                   const std::vector<int> &order, CarrierScratch &scratch, CarrierRuns &runs);

}  // namespace cyclone::detail
