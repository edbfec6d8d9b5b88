#include "dynamics/integration.h"

#include <cmath>

#include "dynamics/springs.h"
#include "world/body_store.h"
#include "world/step_context.h"
#include "world/validation.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// Finite, and within the coordinates FCL can place: otherwise the body is isolated.
bool stateFinite(const RigidBody &body) {
    return body.getPosition().allFinite() && body.getPosition().cwiseAbs().maxCoeff() <= kMaxCoordinate && body.getOrientation().coeffs().allFinite() &&
           body.getVelocity().allFinite() && body.getRotation().allFinite() &&
           std::isfinite(body.getVelocity().squaredNorm() + body.getRotation().squaredNorm());
}

}  // namespace

void Integration::beginStep(StepContext &context, BodyStore &bodies, const SpringSet &springs,
                            BodyTransitions transitions) {
    bodies.sortAwake();
    // `simulated` of the bodies simulated last step; the others are already false.
    for (std::uint32_t index : bodies.simulated) bodies[index].simulated = false;
    bodies.simulated.clear();
    stepSeconds_ = context.dt;
    admitting_ = true;
    for (std::size_t k = 0; k < bodies.awake.size(); ++k)
        if (!enter(bodies, transitions, bodies.awake[k])) --k;  // isolated: slot k now holds another body
    for (const SpringRecord &s : springs) {
        if (!s.alive) continue;
        const BodyRecord &a = bodies[s.settings.a.index];
        const BodyRecord *b = s.settings.b ? &bodies[s.settings.b->index] : nullptr;
        if (!a.simulated && !(b && b->simulated)) continue;
        // An isolated (non-finite) end would carry its state to the other: the spring is off.
        if (a.isolated || (b && b->isolated)) continue;
        // A spring joins its bodies: one awake end wakes the other, which joins this step.
        if (!a.simulated) transitions.wake(s.settings.a.index);
        if (b && !b->simulated) transitions.wake(s.settings.b->index);
        ++context.activeSprings;
    }
}

void Integration::admit(BodyStore &bodies, BodyTransitions transitions, std::uint32_t index) {
    const BodyRecord &r = bodies[index];
    if (!admitting_ || r.simulated || r.immovable || r.isolated || !r.body.getAwake()) return;
    enter(bodies, transitions, index);
}

bool Integration::enter(BodyStore &bodies, BodyTransitions transitions, std::uint32_t index) {
    BodyRecord &r = bodies[index];
    // A force whose velocity overflows within the step (1e300 N on 1 kg) would reach
    // other bodies through springs before the solver's check: isolate the body now.
    const RigidBody &body = r.body;
    const real dt = stepSeconds_;
    const Vector3 v = body.getVelocity() + dt * (body.getAcceleration() + body.getInverseMass() * body.getAccumulatedForce());
    const Vector3 w = body.getRotation() + dt * (body.getInverseInertiaTensorWorld() * body.getAccumulatedTorque());
    if (!std::isfinite(v.squaredNorm() + w.squaredNorm())) {
        transitions.isolate(index);
        return false;
    }
    r.simulated = true;
    r.solverIndex = static_cast<int>(bodies.simulated.size()) + 1;
    bodies.simulated.push_back(index);
    return true;
}

void Integration::closeAdmission(const StepContext &context, const BodyStore &bodies) {
    admitting_ = false;
    if (context.settings.substeps <= 1) return;
    savedForces_.resize(bodies.simulated.size());
    savedTorques_.resize(bodies.simulated.size());
    context.workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
        savedForces_[k] = bodies[bodies.simulated[k]].body.getAccumulatedForce();
        savedTorques_[k] = bodies[bodies.simulated[k]].body.getAccumulatedTorque();
    });
}

// Held for a whole step, an explicit spring force would gain energy at any stiffness once
// there are sub-steps (the positions would move under a force that lags them): springs
// act at each sub-step's start.
void Integration::addSubstepForces(const StepContext &context, BodyStore &bodies, SpringSet &springs,
                                   bool firstSubstep) {
    if (!firstSubstep) {
        context.workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
            BodyRecord &r = bodies[bodies.simulated[k]];
            if (r.isolated) return;
            r.body.addForce(savedForces_[k]);
            r.body.addTorque(savedTorques_[k]);
        });
    }
    if (context.activeSprings == 0) return;
    // The explicit forces first: the implicit ones are solved with them in place.
    const int implicitCount = springs.chooseForces(bodies, context.settings, context.h);
    springs.addExplicitForces(bodies);
    if (implicitCount > 0) springs.addImplicitForces(bodies, context.h);
}

void Integration::integrate(const StepContext &context, BodyStore &bodies, BodyTransitions transitions) {
    const real h = context.h;
    nonFinite_.assign(bodies.simulated.size(), 0);
    context.workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
        RigidBody &body = bodies[bodies.simulated[k]].body;
        if (bodies[bodies.simulated[k]].isolated) return;
        body.integrate(h, false);
        nonFinite_[k] = !stateFinite(body);
    });
    for (std::size_t k = 0; k < bodies.simulated.size(); ++k)
        if (nonFinite_[k]) transitions.isolate(bodies.simulated[k]);
}

}  // namespace cyclone::detail
