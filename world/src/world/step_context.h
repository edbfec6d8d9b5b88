// What the stages of one step share besides the subsystems they work on: the step's
// length, its plan, and what the step holds. WorldState::step fills it stage by stage;
// each field names the stage that writes it, and the stages after it read it. StepStats
// is the step's report, written by the stages and read by no stage.
#pragma once

#include <cstdint>

#include "cyclone/core.h"
#include "dynamics/step_plan.h"

namespace cyclone::detail {

struct StepContext {
    real dt = 0;             ///< The step's length, s (WorldState::step).
    int activeJoints = 0;    ///< Joints with a simulated body this step (JointSet::beginStep).
    int activeSprings = 0;   ///< Springs with a simulated body this step (Integration::beginStep).
    StepPlan plan;           ///< Its sub-steps and velocity passes (planStep, after the narrowphase).
    real deepest = 0;        ///< Deepest point of the solver's manifolds, m (ConstraintSolver::build).
};

}  // namespace cyclone::detail
