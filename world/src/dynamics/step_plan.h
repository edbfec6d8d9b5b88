// The sub-steps a step takes: WorldSettings::substeps, or restingSubsteps when every
// awake body rests on what it touches.
//
// Sub-steps buy accuracy for what moves: a landing body meets its contact within a
// fraction of the step, a fast turn is integrated in small pieces, stiff joints and
// springs stay stable. A body at rest on its contacts gains nothing from them that
// velocity passes in one sub-step do not give, and each sub-step costs its warm start,
// carrier pass, penetration pass and integration again. So a step in which every awake
// body rests on contacts warm from the last step and moves less than kRestingReach takes
// restingSubsteps sub-steps with restingIterations velocity passes in all: its warm start
// already carries the load and the carrier pass holds a stack up, so it needs fewer
// passes than a full step (docs/solver.md, "Resting steps").
#pragma once

#include "cyclone/world/world.h"

namespace cyclone::detail {

struct BodyRecord;
struct BodyStore;
class PairCache;
struct StepContext;

/// How far (m) a body may move in a step, at its velocity and turn, and still count as
/// resting: the reach below which its contacts count it as still (contact_manager.cpp).
inline constexpr real kRestingReach = 0.001;

/// Whether the body rests on warm contacts: it touches something (a manifold with any
/// body, static ones too), each of its manifolds was solved last step and one at least
/// carried a normal impulse, and at its velocity and turn it moves less than kRestingReach
/// in a step of `dt`.
bool rests(const BodyRecord &r, const PairCache &pairs, std::uint64_t stepCount, real dt);

/// The sub-steps and velocity passes of one step.
struct StepPlan {
    int substeps = 1;
    int velocityIterations = 1;
    /// settings.substeps / substeps: the accumulated impulses are stored as those of a
    /// sub-step of dt / settings.substeps, and a step of other sub-steps scales its warm
    /// start by this (1 when the step takes settings.substeps: nothing changes).
    real warmScale = 1;
    /// The fraction of a contact's penetration beyond the slop removed per sub-step:
    /// settings.penetrationRecovery r, or, in a step of fewer sub-steps, what
    /// settings.substeps / substeps sub-steps remove together, 1 - (1 - r)^that, so that a
    /// body held a little too deep (a pass that does not converge) sinks no deeper.
    real recovery = 0;
};

/// The plan of the step about to be solved, from the settings, the step's length and
/// its active joints and springs (`context`), the bodies and their contact pairs: called
/// after the narrowphase (it reads which bodies touch something) and before the solver's
/// manifolds are built.
StepPlan planStep(const StepContext &context, const BodyStore &bodies, const PairCache &pairs);

}  // namespace cyclone::detail
