// Who carries whom in a resting stack, for the solver's carrier pass.
#pragma once

#include <vector>

#include "solver/contact_solver.h"

namespace cyclone::detail {

/// Scratch of assignCarriers, kept between steps so that a step allocates nothing.
struct CarrierScratch {
    std::vector<int> level;     ///< Per solver body: contacts away from an immovable body.
    std::vector<int> start;     ///< Per solver body: first entry in `adjacent`.
    std::vector<int> adjacent;  ///< Neighbours of each body, body by body.
    std::vector<char> carries;  ///< Per entry of `adjacent`: whether the neighbour stands on the body.
    std::vector<int> queue;     ///< Bodies reached up the contacts they stand on, by level.
    std::vector<int> later;     ///< Bodies reached over every contact after those, by level.
    std::vector<int> count;   ///< Per solver body: its manifolds with a carrier.
    std::vector<int> met;     ///< Carried bodies in the order of their first manifolds.
    std::vector<int> bodies;  ///< The same, by level.
    std::vector<int> cursor;  ///< Per level, then per solver body: the next entry to write.
};

/// Sets `carrier` of every manifold. An immovable side (solver body 0: static or asleep;
/// a moving kinematic body) always carries the other. A body's level counts the contacts
/// between it and an immovable body, found breadth first: first only up the contacts a
/// body stands on (normal within 30 degrees of `up`), then, for the bodies not reached,
/// over every contact, each from its lowest neighbour. A manifold between two moving
/// bodies whose upper body rests on the lower one (normal within 60 degrees of `up`)
/// names the lower the carrier where its level is the lower. Those at the same level, side
/// contacts and worlds without gravity (`up` zero) get none.
/// `bodyCount` counts the solver bodies, body 0 included; entries from `firstKinematic`
/// on are moving kinematic bodies, immovable like body 0 (bodyCount when none).
/// Also lists the carrier pass's runs (CarrierRuns) bottom up; within a level, the
/// bodies and each body's manifolds in the solve order `order` (manifold indices); and the
/// manifolds without a carrier, in `order`.
void assignCarriers(int bodyCount, int firstKinematic, const Vector3 &up, SolverManifolds &manifolds,
                   const std::vector<int> &order, CarrierScratch &scratch, CarrierRuns &runs);

}  // namespace cyclone::detail
