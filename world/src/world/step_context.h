// What the stages of one step share besides the subsystems they work on: the settings,
// the threads, the step's number and length, its plan, and what the step holds.
// WorldState::step makes one per step and fills it stage by stage; each field names the
// stage that writes it, and the stages after it read it. StepStats is the step's report,
// written by the stages and read by no stage.
#pragma once

#include <cstdint>

#include "cyclone/core.h"
#include "dynamics/step_plan.h"

namespace cyclone {
struct WorldSettings;
}

namespace cyclone::detail {

class Workers;

struct StepContext {
    StepContext(const WorldSettings &s, Workers &w, std::uint64_t step, real length)
        : settings(s), workers(w), stepCount(step), dt(length) {}

    const WorldSettings &settings;  ///< The World's settings, read only.
    Workers &workers;               ///< The threads the stages share their work with.
    const std::uint64_t stepCount;  ///< The step's number, from 1.
    const real dt;                  ///< The step's length, s.
    int activeJoints = 0;           ///< Joints with a simulated body this step (JointSet::beginStep).
    int activeSprings = 0;          ///< Springs with a simulated body this step (Integration::beginStep).
    StepPlan plan;                  ///< Its sub-steps and velocity passes (planStep, after the narrowphase).
    real h = 0;                     ///< A sub-step's length, dt / plan.substeps, s (with the plan).
    real deepest = 0;               ///< Deepest point of the solver's manifolds, m (ConstraintSolver::build).
};

}  // namespace cyclone::detail
