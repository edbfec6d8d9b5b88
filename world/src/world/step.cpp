// World::step: (characters' pushes) -> forces -> broadphase -> narrowphase -> contact events ->
// sensors -> constraints -> islands -> per sub-step (forces, solve, integrate, penetration,
// locked axes) -> continuous collision -> landing correction -> locked axes -> sleep ->
// characters. Each stage adds its time to stats().ms.
#include "world/body_transitions.h"
#include "world/stage_timer.h"
#include "world/world_impl.h"

namespace cyclone::detail {
namespace {

// The step's counts and times, once its stages are done.
void report(const StepContext &context, const BodyStore &bodies, const Workers &workers, StepStats &stats) {
    stats.substeps = context.plan.substeps;
    stats.joints = context.activeJoints;
    stats.springs = context.activeSprings;
    stats.maxPenetration = context.deepest;
    stats.integratedBodies = static_cast<int>(bodies.simulated.size());
    stats.movingKinematicBodies = static_cast<int>(bodies.moving.size());
    stats.bodies = static_cast<int>(bodies.order.size());
    stats.awakeBodies = static_cast<int>(bodies.awake.size());
    stats.isolatedBodies = bodies.isolatedCount;
    StageTimes &ms = stats.ms;
    ms.total = ms.forces + ms.broadphase + ms.narrowphase + ms.events + ms.sensors + ms.manifolds + ms.islands + ms.solve +
               ms.integrate + ms.ccd + ms.landing + ms.sleep + ms.characters;
    ms.shared = workers.shared();
}

// One sub-step of h s: its forces, the velocities solved, integration, penetration
// recovered, the locked axes held.
void runSubstep(WorldState &world, real h, bool first) {
    StageTimes &ms = world.stats.ms;
    const BodyTransitions transitions(world);
    {
        const StageTimer t(ms.forces);
        world.integration.addSubstepForces(world.settings, world.bodies, world.springs, world.context, h, first);
    }
    {
        // The velocity part is the solve less the carrier pass, which times itself.
        const double carrierBefore = ms.solveParts.carrier;
        const StageTimer t(ms.solve);
        world.solver.solveVelocities(world.settings, world.bodies, world.joints, world.workers, transitions,
                                     world.context, world.stepCount, world.stats, h, first);
        ms.solveParts.velocity += t.elapsed() - (ms.solveParts.carrier - carrierBefore);
    }
    {
        const StageTimer t(ms.integrate);
        world.integration.integrate(world.bodies, world.workers, transitions, h);
        KinematicBodies::integrate(world.bodies, h);
    }
    {
        const StageTimer t(ms.solve);  // recoverPenetration times itself into solveParts.position
        world.solver.recoverPenetration(world.settings, world.bodies, world.joints, world.workers, transitions,
                                        world.context, world.stats, h);
    }
    { const StageTimer t(ms.integrate); world.axisLocks.hold(world.bodies); }
}

}  // namespace

void WorldState::step(real dt) {
    stats = StepStats();
    context = StepContext();
    context.dt = dt;
    ++stepCount;
    events.openStep();
    StageTimes &ms = stats.ms;
    workers.match(settings.threads);  // the narrowphase and the solver share their work
    workers.resetTimes();

    if (!characters.empty()) {
        const StageTimer t(ms.characters);
        characters.beginStep(settings.gravity, bodies, queryScene(), dt);
    }
    {
        const StageTimer t(ms.forces);
        integration.beginStep(bodies, springs, BodyTransitions(*this), context, dt);
        axisLocks.beginStep(bodies);
        KinematicBodies::beginStep(bodies, contacts.pairs, BodyTransitions(*this));
        joints.beginStep(bodies, BodyTransitions(*this), context);
    }
    {
        const StageTimer t(ms.broadphase);
        contacts.findCandidates(settings, bodies, broadphase, workers, stats, dt);
    }
    {
        const StageTimer t(ms.narrowphase);
        contacts.updateContacts(settings, bodies, joints, workers, BodyTransitions(*this), stepCount, stats, dt);
    }
    // The step's bodies are final: those woken by its contacts, joints and springs are in.
    integration.closeAdmission(settings, bodies);
    KinematicBodies::number(bodies);
    { const StageTimer t(ms.events); contacts.reportContactEvents(bodies, workers, events.events); }
    if (bodies.sensorCount > 0) {
        const StageTimer t(ms.sensors);
        sensors.update(bodies, broadphase, contacts.sensorCandidates(), stepCount, *events.sink, stats);
    }
    context.plan = planStep(settings, context, bodies, contacts.pairs, stepCount, dt);
    const StepPlan &plan = context.plan;
    {
        const StageTimer t(ms.manifolds);
        solver.build(settings, bodies, contacts, preSolve, workers, stepCount, context, stats);
    }
    { const StageTimer t(ms.islands); islands.build(bodies, solver.manifolds(), springs, joints, stats); }

    const real h = dt / plan.substeps;
    {
        const StageTimer t(ms.solveParts.setup);
        solver.prepare(settings, bodies, workers, context, stats, h);
    }
    ms.solve += ms.solveParts.setup;
    for (int substep = 0; substep < plan.substeps; ++substep) runSubstep(*this, h, substep == 0);
    {
        const StageTimer t(ms.solve);
        solver.storeImpulses(bodies, contacts.pairs, workers, context, *events.sink);
        joints.finishStep(bodies, context, *events.sink, BodyTransitions(*this), dt);
    }
    { const StageTimer t(ms.ccd); ccd.sweep(settings, bodies, broadphase, contacts.pairs, stepCount, stats); }
    {
        const StageTimer t(ms.landing);
        landing.correct(settings, bodies, contacts, preSolve, joints, islands, workers, context.deepest, stepCount, stats);
    }
    { const StageTimer t(ms.integrate); axisLocks.hold(bodies); }
    {
        const StageTimer t(ms.sleep);
        for (const int island : islands.still(settings, bodies)) sleepIsland(islands.members(island), islands.size(island));
    }
    if (!characters.empty()) {
        const StageTimer t(ms.characters);
        characters.update(settings.gravity, bodies, queryScene(), BodyTransitions(*this), dt);
    }
    events.closeStep();
    report(context, bodies, workers, stats);
}

}  // namespace cyclone::detail
