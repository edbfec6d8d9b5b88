// Forces and integration: which bodies a step moves, the forces of each sub-step, and
// RigidBody::integrate over it.
#pragma once

#include <vector>

#include "cyclone/world/world.h"
#include "world/body_transitions.h"

namespace cyclone::detail {

struct BodyStore;
class SpringSet;
struct StepContext;
class Workers;

class Integration {
public:
    /// The forces stage: lists the bodies the step moves (BodyStore::simulated, awake
    /// when it starts), isolating any whose forces overflow its velocity; wakes the other
    /// end of a spring on a moving body and counts the active springs
    /// (context.activeSprings). Admission stays open until closeAdmission.
    void beginStep(StepContext &context, BodyStore &bodies, const SpringSet &springs, BodyTransitions transitions);
    /// Adds a body woken during the step (by a contact, joint, spring or kinematic body)
    /// to the bodies it moves, while admission is open; otherwise nothing.
    void admit(BodyStore &bodies, BodyTransitions transitions, std::uint32_t index);
    /// Ends admission once the contacts are known: the step's bodies are final. Keeps the
    /// user's forces for the later sub-steps (when settings.substeps > 1).
    void closeAdmission(const StepContext &context, const BodyStore &bodies);
    /// Forces of one sub-step (context.h s): the user's forces again after the first
    /// sub-step (integrate cleared them), then the springs at the sub-step's start (when
    /// context.activeSprings is not 0).
    void addSubstepForces(const StepContext &context, BodyStore &bodies, SpringSet &springs, bool firstSubstep);
    /// Moves every simulated body over a sub-step (context.h s, shared by the workers);
    /// isolates those whose state is no longer finite.
    void integrate(const StepContext &context, BodyStore &bodies, BodyTransitions transitions);

private:
    /// Lists one awake body as simulated, or isolates it (false) if its forces overflow.
    bool enter(BodyStore &bodies, BodyTransitions transitions, std::uint32_t index);

    real stepSeconds_ = 0;   ///< The step's dt, s.
    bool admitting_ = false; ///< Between beginStep and closeAdmission.
    std::vector<Vector3> savedForces_;   ///< Per simulated body: the user's force this step, N.
    std::vector<Vector3> savedTorques_;  ///< And torque, N m.
    std::vector<char> nonFinite_;        ///< Per simulated body: integrate left it non-finite.
};

}  // namespace cyclone::detail
