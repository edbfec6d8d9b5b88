// Who carries whom in a resting stack, for the solver's support pass (shock propagation).
#pragma once

#include <vector>

#include "contact_solver.h"

namespace cyclone::detail {

/// Scratch of assignSupport, kept between steps so that a step allocates nothing.
struct SupportScratch {
    std::vector<int> level;     ///< Per solver body: contacts away from an immovable body.
    std::vector<int> start;     ///< Per solver body: first entry in `adjacent`.
    std::vector<int> adjacent;  ///< Neighbours of each body, body by body.
    std::vector<int> queue;
    struct Key {
        int level;     ///< The carried body's.
        int body;      ///< The carried body, then its first manifold's rank.
        int manifold;  ///< Rank in the solve order.
    };
    std::vector<Key> keys;   ///< The support pass's order being sorted.
    std::vector<int> first;  ///< Per solver body: its first manifold with a carrier.
};

/// Sets `support` of every manifold. A static or sleeping side (solver body 0) always
/// supports the other. A body's level is the number of contacts between it
/// and an immovable body (solver body 0: static or asleep), found breadth-first over the
/// manifolds. A manifold between levels k and k + 1 whose upper body rests on the lower
/// one (normal within 60 degrees of `up`) names the lower as the support. Between two
/// moving bodies, those at the same level, side contacts and worlds without gravity
/// (`up` zero) get none.
/// `bodyCount` counts the solver bodies, body 0 included.
/// Also lists the support pass's runs (SupportRuns) bottom up; within a level, the
/// bodies and each body's manifolds in the solve order `order` (manifold indices).
void assignSupport(int bodyCount, const Vector3 &up, std::vector<SolverManifold> &manifolds,
                   const std::vector<int> &order, SupportScratch &scratch, SupportRuns &runs);

}  // namespace cyclone::detail
