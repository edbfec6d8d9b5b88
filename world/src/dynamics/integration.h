// Forces and integration: which bodies a step moves, the forces of each sub-step, and
// RigidBody::integrate over it.
#pragma once

#include <vector>

#include "cyclone/world/world.h"

namespace cyclone::detail {

struct WorldState;

class Integration {
public:
    /// The forces stage: lists the bodies the step moves (BodyStore::simulated, awake
    /// when it starts), isolating any whose forces overflow its velocity; wakes the other
    /// end of a spring on a moving body; keeps the user's forces for later sub-steps.
    void beginStep(WorldState &world, real dt);
    /// Forces of one sub-step of h seconds: the user's forces again after the first
    /// sub-step (integrate cleared them), then the springs at the sub-step's start.
    void addSubstepForces(WorldState &world, real h, bool firstSubstep);
    /// Moves every simulated body over h seconds; isolates those whose state is no
    /// longer finite.
    void integrate(WorldState &world, real h);

private:
    std::vector<Vector3> savedForces_;   ///< Per simulated body: the user's force this step, N.
    std::vector<Vector3> savedTorques_;  ///< And torque, N m.
    std::vector<char> nonFinite_;        ///< Per simulated body: integrate left it non-finite.
};

}  // namespace cyclone::detail
