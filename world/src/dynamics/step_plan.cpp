#include "dynamics/step_plan.h"

#include "world/world_impl.h"

namespace cyclone::detail {
namespace {

// Whether the body touches something: a manifold with any body (static ones too).
bool touches(const BodyRecord &r, const PairCache &pairs) {
    for (std::uint32_t p : r.pairs)
        if (pairs[p].touching()) return true;
    return false;
}

StepPlan plan(int substeps, int iterations, const WorldSettings &settings) {
    return {substeps, iterations, real(settings.substeps) / substeps};
}

}  // namespace

StepPlan planStep(const WorldState &world, real dt) {
    const WorldSettings &settings = world.settings;
    const StepPlan full = plan(settings.substeps, settings.velocityIterations, settings);
    const int resting = settings.restingSubsteps;
    if (resting <= 0 || resting >= settings.substeps) return full;
    // Only split impulse: the soft step's springs are tuned per sub-step. Joints and
    // springs are stiff where sub-steps are short; a moving kinematic body moves what it
    // touches.
    if (settings.contactSolver != ContactSolverType::SplitImpulse) return full;
    if (world.stats.joints > 0 || world.stats.springs > 0 || !world.bodies.moving.empty()) return full;
    // A long step lets gravity carry a resting body through its contacts' reach within one
    // sub-step (|g| h^2 beyond speculativeDistance): its sub-steps stay.
    const real h = dt / resting;
    if (settings.gravity.norm() * h * h > settings.speculativeDistance) return full;
    const BodyStore &bodies = world.bodies;
    const PairCache &pairs = world.contacts.pairs;
    for (std::uint32_t index : bodies.simulated) {
        const BodyRecord &r = bodies[index];
        if (r.isolated) continue;
        const RigidBody &body = r.body;
        const real reach = (body.getVelocity().norm() + body.getRotation().norm() * r.boundingRadius) * dt;
        if (reach >= kRestingReach || !touches(r, pairs)) return full;
    }
    // The same velocity passes per step, rounded up.
    const int passes = settings.velocityIterations * settings.substeps;
    return plan(resting, (passes + resting - 1) / resting, settings);
}

}  // namespace cyclone::detail
