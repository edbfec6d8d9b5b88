#include "dynamics/step_plan.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "contacts/pair_cache.h"
#include "world/body_store.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// Whether the body rests on warm contacts: it touches something (a manifold with any
// body, static ones too), each of its manifolds was solved last step, and at least one
// of them carried a normal impulse, which warm-starts it. A contact new in this step
// must build its whole impulse within the step: a box with a twelfth of its shape's
// inertia, placed on the floor, sinks about three times as deep in a first step of one
// sub-step as in one of four (docs/solver.md, "Resting steps"). A manifold solved
// last step that carried nothing is a support the load did not need (a box of a pyramid
// on two boxes below, one of which took the load): it counts as warm, else a tall stack
// whose passes leave some support unloaded never takes a resting step.
bool restsOnWarmContacts(const BodyRecord &r, const PairCache &pairs, std::uint64_t stepCount) {
    bool carried = false;
    for (std::uint32_t p : r.pairs) {
        for (const ManifoldState &m : pairs[p].manifolds) {
            if (!m.solvedInStepBefore(stepCount)) return false;
            for (int i = 0; i < m.count; ++i) carried |= m.points[i].normalImpulse > 0;
        }
    }
    return carried;
}

StepPlan plan(int substeps, int iterations, const WorldSettings &settings) {
    const real r = settings.penetrationRecovery;
    const real ratio = real(settings.substeps) / substeps;
    const real recovery = substeps == settings.substeps ? r : 1 - std::pow(1 - r, ratio);
    return {substeps, iterations, ratio, recovery};
}

}  // namespace

bool rests(const BodyRecord &r, const PairCache &pairs, std::uint64_t stepCount, real dt) {
    const RigidBody &body = r.body;
    const real reach = (body.getVelocity().norm() + body.getRotation().norm() * r.boundingRadius) * dt;
    return reach < kRestingReach && restsOnWarmContacts(r, pairs, stepCount);
}

StepPlan planStep(const StepContext &context, const BodyStore &bodies, const PairCache &pairs) {
    const WorldSettings &settings = context.settings;
    const std::uint64_t stepCount = context.stepCount;
    const real dt = context.dt;
    const StepPlan full = plan(settings.substeps, settings.velocityIterations, settings);
    const int resting = settings.debug.restingSubsteps;
    if (resting <= 0 || resting >= settings.substeps) return full;
    // Joints and springs are stiff where sub-steps are short; a moving kinematic body
    // moves what it touches.
    if (context.activeJoints > 0 || context.activeSprings > 0 || !bodies.moving.empty()) return full;
    // A long step lets gravity carry a resting body through its contacts' reach within one
    // sub-step (|g| h^2 beyond speculativeDistance): its sub-steps stay.
    const real h = dt / resting;
    if (settings.gravity.norm() * h * h > settings.speculativeDistance) return full;
    // On the threads: a body that does not rest settles the answer; the others then skip.
    std::atomic<bool> moves{false};
    context.workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
        if (moves.load(std::memory_order_relaxed)) return;
        const BodyRecord &r = bodies[bodies.simulated[k]];
        if (!r.isolated && !rests(r, pairs, stepCount, dt)) moves.store(true, std::memory_order_relaxed);
    });
    if (moves.load()) return full;
    // restingIterations passes per step, at most a full step's, shared by the sub-steps
    // (rounded up).
    const int passes = std::min(settings.debug.restingIterations, settings.velocityIterations * settings.substeps);
    return plan(resting, (passes + resting - 1) / resting, settings);
}

}  // namespace cyclone::detail
