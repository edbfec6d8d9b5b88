// World::step: (characters' pushes) -> forces -> broadphase -> narrowphase -> held bodies ->
// contact events -> sensors -> constraints -> islands -> per sub-step (forces, solve,
// integrate, penetration, locked axes) -> continuous collision -> landing correction ->
// locked axes -> sleep -> characters. Each stage adds its time to stats().ms.
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

// One sub-step (context.h s): its forces, the velocities solved, integration,
// penetration recovered, the locked axes held.
void runSubstep(WorldState &world, const StepContext &context, bool first) {
    StageTimes &ms = world.stats.ms;
    const BodyTransitions transitions(world);
    {
        const StageTimer t(ms.forces);
        world.integration.addSubstepForces(context, world.bodies, world.springs, first);
    }
    {
        // The velocity part is the solve less the carrier pass, which times itself.
        const double carrierBefore = ms.solveParts.carrier;
        const StageTimer t(ms.solve);
        world.solver.solveVelocities(context, world.bodies, world.joints, transitions, world.stats, first);
        ms.solveParts.velocity += t.elapsed() - (ms.solveParts.carrier - carrierBefore);
    }
    {
        const StageTimer t(ms.integrate);
        world.integration.integrate(context, world.bodies, transitions);
        KinematicBodies::integrate(world.bodies, context.h);
    }
    {
        const StageTimer t(ms.solve);  // recoverPenetration times itself into solveParts.position
        world.solver.recoverPenetration(context, world.bodies, world.joints, transitions, world.stats);
    }
    { const StageTimer t(ms.integrate); world.axisLocks.hold(world.bodies); }
}

}  // namespace

void WorldState::step(real dt) {
    stats = StepStats();
    workers.match(settings.threads);  // the narrowphase and the solver share their work
    workers.resetTimes();
    StepContext context(settings, workers, ++stepCount, dt);
    events.openStep();
    StageTimes &ms = stats.ms;

    if (!characters.empty()) {
        const StageTimer t(ms.characters);
        characters.beginStep(settings.gravity, bodies, queryScene(), dt);
    }
    {
        const StageTimer t(ms.forces);
        integration.beginStep(context, bodies, springs, BodyTransitions(*this));
        axisLocks.beginStep(bodies);
        KinematicBodies::beginStep(bodies, contacts.pairs, BodyTransitions(*this));
        joints.beginStep(context, bodies, BodyTransitions(*this));
    }
    { const StageTimer t(ms.broadphase); contacts.findCandidates(context, bodies, broadphase, stats); }
    {
        const StageTimer t(ms.narrowphase);
        contacts.updateContacts(context, bodies, joints, BodyTransitions(*this), stats);
    }
    // The step's bodies are final: those woken by its contacts, joints and springs are in,
    // the held ones out.
    { const StageTimer t(ms.sleep); holding.choose(context, bodies, contacts.pairs, stats); }
    integration.closeAdmission(context, bodies);
    KinematicBodies::number(bodies);
    { const StageTimer t(ms.events); contacts.reportContactEvents(context, bodies, events.events); }
    if (bodies.sensorCount > 0) {
        const StageTimer t(ms.sensors);
        sensors.update(context, bodies, broadphase, contacts.sensorCandidates(), *events.sink, stats);
    }
    {
        const StageTimer t(ms.solveParts.setup);  // added to the solve below
        context.plan = planStep(context, bodies, contacts.pairs);
        context.h = dt / context.plan.substeps;
    }
    { const StageTimer t(ms.manifolds); solver.build(context, bodies, contacts, preSolve, stats); }
    {
        const StageTimer t(ms.islands);
        islands.build(bodies, solver.manifolds(), springs, joints, holding.held(), contacts.pairs, workers, stats);
    }

    { const StageTimer t(ms.solveParts.setup); solver.prepare(context, bodies, stats); }
    ms.solve += ms.solveParts.setup;
    for (int substep = 0; substep < context.plan.substeps; ++substep) runSubstep(*this, context, substep == 0);
    {
        const StageTimer t(ms.solve);
        solver.storeImpulses(context, bodies, contacts.pairs, *events.sink);
        joints.finishStep(context, bodies, BodyTransitions(*this), *events.sink);
    }
    { const StageTimer t(ms.ccd); ccd.sweep(context, bodies, broadphase, contacts.pairs, stats); }
    {
        const StageTimer t(ms.landing);
        landing.correct(context, bodies, contacts, preSolve, joints, islands, stats);
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
