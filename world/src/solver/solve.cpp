// Solving the step's constraints, sub-step by sub-step: velocities predicted without
// contacts, corrected by the velocity passes and the carrier pass and handed to the
// bodies through addVelocity / addRotation; then, after integration, penetration
// recovered without adding energy by pseudo-velocities (split impulse).
#include <algorithm>
#include <atomic>
#include <cmath>

#include "dynamics/axis_locks.h"
#include "joints/joint_set.h"
#include "solver/constraint_solver.h"
#include "world/body_transitions.h"
#include "world/room.h"
#include "world/stage_timer.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// The frame that gives a manifold's depths along `normal` at the bodies' current poses
// (DepthFrame): a rotation transposed is its inverse.
DepthFrame depthFrame(const RigidBody &a, const RigidBody &b, const Vector3 &normal) {
    return {a.getTransform().linear().transpose() * normal, b.getTransform().linear().transpose() * normal,
            (a.getPosition() - b.getPosition()).dot(normal)};
}

// Gives body `index` the solver's change of velocity and rotation; false, changing
// nothing, when the change is not finite (the solve overflowed for this body): the caller
// then isolates the body, as a non-finite state does, so that the rest of the world
// steps on.
bool changeVelocities(RigidBody &body, const Vector3 &dv, const Vector3 &dw) {
    if (!(body.getVelocity() + dv).allFinite() || !(body.getRotation() + dw).allFinite()) return false;
    body.addVelocity(dv);
    body.addRotation(dw);
    return true;
}

}  // namespace

// One sub-step: the velocities each body reaches without contacts, the contacts' targets at
// the sub-step's poses, the passes, and the change they made handed to the bodies.
void ConstraintSolver::solveVelocities(const StepContext &context, BodyStore &bodies, JointSet &joints,
                                       BodyTransitions transitions, StepStats &stats, bool firstSubstep) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    predictVelocities(settings, bodies, workers, transitions, context.plan.substeps, stats, context.h, firstSubstep);
    if (!firstSubstep) refreshTargets(bodies, workers, settings.restitutionThreshold, context.h);
    solvePasses(context, bodies, joints, stats, firstSubstep);
    giveVelocities(settings, bodies, workers, transitions, firstSubstep);
}

void ConstraintSolver::predictVelocities(const WorldSettings &settings, BodyStore &bodies, Workers &workers,
                                         BodyTransitions transitions, int substeps, StepStats &stats, real h,
                                         bool firstSubstep) {
    // Predicted velocities: (v + a h) damping^h, with the sub-step's forces.
    //
    // The gyroscopic step is applied to the body here rather than inside integrate(h): it
    // is not linear in w, so integrate could not turn w + (solver's change) into
    // predicted + change. It is taken once per step, over the whole step, in the first
    // sub-step: the solver's Jacobians hold the inertia of the step's start pose, so a
    // gyroscopic change given in a later sub-step, once the body has turned, is cancelled
    // by impulses that do not conserve its angular momentum. Taken every sub-step, an
    // unbalanced box spinning at 6 rad/s on a frictionless floor gained 12% of its energy
    // in 20 s at 4 sub-steps; taken once, it loses 17% (the contacts cancel the tilt the
    // step gives, at first order in dt), which a first-order step may, but never gains.
    //
    // Each body on its own, in chunks shared between the threads; the bodies to isolate
    // are isolated after, in order (isolation is not for worker threads).
    const bool gyroscopic = settings.integrator == Integrator::NewtonEulerGyroscopic ||
                            settings.integrator == Integrator::NewtonEulerImplicit;
    overflowed_.assign(bodies.simulated.size(), 0);
    std::atomic<int> gyroscopicBodies{0};
    workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
        BodyRecord &r = bodies[bodies.simulated[k]];
        SolverBody &sb = bodies_[k + 1];
        if (r.isolated) {
            sb = SolverBody();  // immovable from now on: its state reaches no one
            return;
        }
        if (gyroscopic && firstSubstep && !r.body.hasIsotropicInertia()) {
            r.body.applyGyroscopicStep(GyroscopicStep::Midpoint, h * substeps);
            gyroscopicBodies.fetch_add(1, std::memory_order_relaxed);
        }
        const Vector3 a = r.body.getAcceleration() + r.body.getAccumulatedForce() * sb.invMass;
        // The body's current inertia, as integrate(h) uses, not the step's (sb.invInertia).
        const Vector3 alpha = r.body.getInverseInertiaTensorWorld() * r.body.getAccumulatedTorque();
        predictedV_[k] = (r.body.getVelocity() + a * h) * linearFactor_[k];
        predictedW_[k] = (r.body.getRotation() + alpha * h) * angularFactor_[k];
        if (r.locked.any()) {
            predictedV_[k] = freeLinear(r.locked, predictedV_[k]);
            predictedW_[k] = freeAngular(r.locked, predictedW_[k]);
        }
        setLanes(sb.v, predictedV_[k]);
        setLanes(sb.w, predictedW_[k]);
        sb.pv = Lanes{};
        sb.pw = Lanes{};
        if (!std::isfinite(predictedV_[k].squaredNorm() + predictedW_[k].squaredNorm())) {
            // A velocity beyond ~1e154 m/s would overflow impulses: isolate the body
            // before any contact carries it to a neighbour.
            overflowed_[k] = 1;
            sb = SolverBody();
        }
    });
    stats.gyroscopicBodies += gyroscopicBodies.load(std::memory_order_relaxed);
    for (std::size_t k = 0; k < bodies.simulated.size(); ++k)
        if (overflowed_[k]) transitions.isolate(bodies.simulated[k]);
}

// Current separations from the anchors (positions move only between sub-steps), and the
// targets they give. In the first sub-step the bodies are where the narrowphase found
// them, and its depths (addSolverManifold) are current: along the normal it last found,
// which differs from a kept manifold's (jacobian_stamp.h) by less than the reuse
// tolerance's turn; prepareManifold set their targets.
void ConstraintSolver::refreshTargets(const BodyStore &bodies, Workers &workers, real threshold, real h) {
    const real inverseH = 1 / h;
    workers.forEach(manifolds_.size(), [&](std::size_t s) {
        SolverManifold &m = manifolds_[s];
        DepthFrame frame = depthFrame(bodies[slotBodies_[s].a].body, bodies[slotBodies_[s].b].body, m.normal);
        if (!roundDepths_.empty()) frame.offset += roundDepths_.change(s, frame);
        for (int i = 0; i < m.count; ++i) {
            SolverPoint &p = m.points[i];
            p.depth = frame.of(p);
            p.velocityBias = velocityBias(m, p, h, inverseH, threshold, false);
        }
    });
}

// The velocity passes, the resistance rows and the joints, then the carrier pass; each
// slot's normal impulses are added to its step's total.
void ConstraintSolver::solvePasses(const StepContext &context, const BodyStore &bodies, JointSet &joints,
                                   StepStats &stats, bool firstSubstep) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    // Joints: rows made at the sub-step's poses, warm-started, and solved in the same
    // passes as the contacts, after them (joints/joint_set.h).
    const bool joined = context.activeJoints > 0;
    if (joined) {
        joints.prepare(context, bodies, bodies_, stats);
        joints.warmStart(bodies_);
    }
    if (!manifolds_.empty()) {
        loadVelocityPasses(workers, settings, firstSubstep);
        workers.forEach(resistance_.size(), [&](std::size_t k) { beginResistance(manifolds_, resistance_[k]); });
        const int passes = context.plan.velocityIterations;
        for (int it = 0; it < passes; ++it) {
            solveVelocityPass(workers, (it & 1) != 0);
            solveResistancePass(workers);
            if (joined) joints.solveVelocities(bodies_);
        }
        storeVelocityPasses(workers);
        stats.velocityIterations += passes;
        // The carrier pass comes after the velocity passes, never instead of one: alone,
        // it would let no body push the bodies carrying it.
        if (settings.debug.carrierPass) {
            const StageTimer timed(stats.ms.solveParts.carrier);
            // A run sweeps its points in one direction: the other one next step, so that
            // no point of a face takes the larger share step after step (carrier_pass.h).
            solveCarrierPass(workers, stats, ((passes & 1) != 0) != ((context.stepCount & 1) != 0));
            // The carrier pass moved joined bodies too: the joints have the last word.
            if (joined) joints.solveVelocities(bodies_);
        }
    } else if (joined) {
        for (int it = 0; it < context.plan.velocityIterations; ++it) joints.solveVelocities(bodies_);
    }
    if (joined) joints.storeImpulses();
    // What the sub-step's contacts gave: each point's accumulated impulse, warm start included.
    workers.forEach(manifolds_.size(), [&](std::size_t s) {
        const SolverManifold &m = manifolds_[s];
        for (int i = 0; i < m.count; ++i) stepImpulse_[s] += m.points[i].normal.impulse;
    });
}

void ConstraintSolver::giveVelocities(const WorldSettings &settings, BodyStore &bodies, Workers &workers,
                                      BodyTransitions transitions, bool firstSubstep) {
    // integrate(h) will turn v into (v + a h) damping^h, so the change to give the body
    // now is the solver's change divided by the damping factor.
    //
    // The solver's rows hold the inverse inertia of the step's start pose, so its change
    // of w is that of an angular impulse through that inertia. The momentum-conserving
    // step turns w into angular momentum through the current one: it is given that
    // impulse (I_start dw) instead, or a body whose contacts cancel its torque-free wobble
    // in every sub-step would gain energy (docs/solver.md, "Figures behind constants in
    // the code").
    //
    // Each body on its own, in chunks shared between the threads, as above.
    const bool conserving = settings.integrator == Integrator::MomentumConserving;
    overflowed_.assign(bodies.simulated.size(), 0);
    workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
        BodyRecord &r = bodies[bodies.simulated[k]];
        if (r.isolated) return;
        const SolverBody &sb = bodies_[k + 1];
        const Vector3 dv =
            linearFactor_[k] > 0 ? Vector3((toVector3(sb.v) - predictedV_[k]) / linearFactor_[k]) : Vector3::Zero();
        Vector3 dw = Vector3::Zero();
        if (angularFactor_[k] > 0) {
            dw = toVector3(sb.w) - predictedW_[k];
            // (A locked body's projected inertia has no inverse: its w is held anyway.)
            if (conserving && !firstSubstep && !r.body.hasIsotropicInertia() && !r.locked.any())
                dw = r.body.getInverseInertiaTensorWorld() * sb.invInertia.inverse() * dw;
            dw /= angularFactor_[k];
        }
        overflowed_[k] = !changeVelocities(r.body, dv, dw);
    });
    for (std::size_t k = 0; k < bodies.simulated.size(); ++k)
        if (overflowed_[k]) transitions.isolate(bodies.simulated[k]);
}

// The velocity passes work on a copy of the rows they solve (velocity_pass.h), taken at the
// warm start, which each group makes as it is copied, and handed back, with the
// accumulated impulses, after the last pass. The rows are the step's: later sub-steps copy
// only the impulses and targets again. Every part is loaded, the empty ones too: an
// unsplit step must not find the seam's rows of an earlier split one. The seam comes
// last, as in a pass: its warm start moves bodies of both halves.
void ConstraintSolver::loadVelocityPasses(Workers &workers, const WorldSettings &settings, bool firstSubstep) {
    const bool warm = settings.debug.warmStarting;
    const bool recovers = settings.positionIterations > 0;
    const auto load = [&](int part) {
        if (firstSubstep)
            loadBatches(bodies_, manifolds_, partition_.groups[part], warm, batches_[part],
                        recovers ? &penetration_[part] : nullptr);
        else
            reloadBatches(bodies_, manifolds_, partition_.groups[part], warm, batches_[part]);
    };
    workers.forEachTask(2, load);
    load(SolverPartition::kSeam);
}

void ConstraintSolver::solveVelocityPass(Workers &workers, bool reverse) {
    workers.forEachTask(partition_.split ? 2 : 1, [&](int half) { solveVelocityBatches(bodies_, batches_[half], reverse); });
    solveVelocityBatches(bodies_, batches_[SolverPartition::kSeam], reverse);
}

void ConstraintSolver::storeVelocityPasses(Workers &workers) {
    workers.forEachTask(3, [&](int part) {
        storeBatches(batches_[part], partition_.groups[part], manifolds_);
    });
}

// The partition's halves at once, each run once its carriers are done (threads/carrier_threads.h).
void ConstraintSolver::solveCarrierPass(Workers &workers, StepStats &stats, bool reverse) {
    const std::vector<int> &uncarried = carrierRuns_.uncarried;
    if (orderedShares_ && uncarried.size() >= kMinSharedEntries) {
        uncarriedShares_.finished.begin();
        workers.forEachTask(2, [&](int share) {
            solveOrderedShare(uncarriedShares_, share,
                              [&](int k) { solveUncarriedManifold(bodies_, manifolds_[uncarried[k]], reverse); });
        });
    } else {
        solveUncarried(bodies_, manifolds_, uncarried, reverse);
    }
    carrierThreads_.finished.begin();
    for (CarrierPassScratch &s : carrierThreads_.scratch) s.sweeps = 0;
    workers.forEachTask(carrierThreads_.share[1].empty() ? 1 : 2, [&](int share) {
        solveCarrierShare(bodies_, manifolds_, carrierRuns_, carrierThreads_, share, reverse);
    });
    for (const CarrierPassScratch &s : carrierThreads_.scratch) stats.carrierSweeps += static_cast<int>(s.sweeps);
}

// One pass over the resistance rows: on two threads (threads/ordered_shares.h) when there
// are enough of them to outweigh the hand-over, with the same numbers either way.
void ConstraintSolver::solveResistancePass(Workers &workers) {
    if (!orderedShares_ || resistance_.size() < kMinSharedEntries) {
        solveResistance(bodies_, resistance_);
        return;
    }
    resistanceShares_.finished.begin();
    workers.forEachTask(2, [&](int share) {
        solveOrderedShare(resistanceShares_, share, [&](int k) { solveResistanceRow(bodies_, resistance_[k]); });
    });
}

void ConstraintSolver::recoverPenetration(const StepContext &context, BodyStore &bodies, JointSet &joints,
                                          BodyTransitions transitions, StepStats &stats) {
    recoverContactPenetration(context.settings, bodies, context.workers, transitions, context.plan.recovery, stats,
                              context.h);
    if (context.activeJoints > 0) joints.correctPositions(context, bodies, bodies_);
}

void ConstraintSolver::recoverContactPenetration(const WorldSettings &settings, BodyStore &bodies, Workers &workers,
                                                 BodyTransitions transitions, real recovery, StepStats &stats, real h) {
    if (settings.positionIterations == 0 || manifolds_.empty()) return;
    const StageTimer timed(stats.ms.solveParts.position);
    // Split impulse: pseudo-velocities push penetration beyond the slop out by a fraction
    // per sub-step; they move positions only and are forgotten, so they add no energy.
    // The passes run on the velocity passes' groups and rows (penetration_pass.h); the first
    // sets each group's targets from its depths at the poses integration left.
    depthFrames_.resize(manifolds_.size());
    workers.forEach(manifolds_.size(), [&](std::size_t s) {
        depthFrames_[s] = depthFrame(bodies[slotBodies_[s].a].body, bodies[slotBodies_[s].b].body,
                                    manifolds_[s].normal);
        if (!roundDepths_.empty()) depthFrames_[s].offset += roundDepths_.change(s, depthFrames_[s]);
    });
    const PseudoTargets targets{depthFrames_.data(), settings.penetrationSlop,
                                        recovery / h};
    const int seam = SolverPartition::kSeam;
    const int last = settings.positionIterations - 1;
    for (int it = 0; it <= last; ++it) {
        const bool carried = it == last && settings.debug.carrierPass;
        const PseudoTargets *set = it == 0 ? &targets : nullptr;
        const auto pass = [&](int part) {
            return solvePenetrationBatches(bodies_, batches_[part], penetration_[part], partition_.groups[part],
                                           carried, set);
        };
        bool pushed[3] = {};
        workers.forEachTask(partition_.split ? 2 : 1, [&](int half) { pushed[half] = pass(half); });
        pushed[seam] = pass(seam);
        if (it == 0 && !pushed[0] && !pushed[1] && !pushed[seam]) return;  // nothing penetrates beyond what is allowed
    }
    stats.positionIterations += settings.positionIterations;
    overflowed_.assign(bodies.simulated.size(), 0);
    workers.forEach(bodies.simulated.size(), [&](std::size_t k) {
        BodyRecord &r = bodies[bodies.simulated[k]];
        SolverBody &sb = bodies_[k + 1];
        const Vector3 pv = toVector3(sb.pv);
        const Vector3 pw = toVector3(sb.pw);
        if (r.isolated || (pv.isZero(0) && pw.isZero(0))) return;
        Quaternion q = r.body.getOrientation();
        const Quaternion spin(0, pw.x() * h, pw.y() * h, pw.z() * h);
        q.coeffs() += 0.5 * (spin * q).coeffs();
        const Vector3 position = r.body.getPosition() + pv * h;
        sb.pv = Lanes{};
        sb.pw = Lanes{};
        if (!position.allFinite() || !q.coeffs().allFinite()) {
            overflowed_[k] = 1;  // isolated below: isolation is not for worker threads
            return;
        }
        r.body.setPosition(position);
        r.body.setOrientation(q);
    });
    for (std::size_t k = 0; k < bodies.simulated.size(); ++k)
        if (overflowed_[k]) transitions.isolate(bodies.simulated[k]);
}

void ConstraintSolver::storeImpulses(const StepContext &context, const BodyStore &bodies, PairCache &pairs,
                                     WorldEvents &events) {
    const real scale = 1 / context.plan.warmScale;  // stored per default sub-step (step_plan.h)
    context.workers.forEach(manifolds_.size(), [&](std::size_t s) {
        const SolverManifold &m = manifolds_[s];
        PairState &pair = pairs[sources_[s].pair];
        const std::size_t k = sources_[s].index;
        if (!pair.alive || k >= pair.manifolds.size()) return;  // a body was isolated
        ManifoldState &state = pair.manifolds[k];
        for (int i = 0; i < m.count; ++i) state.points[i].normalImpulse = m.points[m.order[i]].normal.impulse * scale;
        state.frictionImpulse = (m.frictionRow[0].impulse * m.tangent[0] + m.frictionRow[1].impulse * m.tangent[1]) * scale;
        state.twistImpulse = m.twist.impulse * scale;
    });
    reportImpulses(context.workers, bodies, pairs, events.contactImpulses);
}

// One entry per solved pair, summed over its manifolds, in the order of the bodies'
// indices (the slots' order changes with the heights); in place, so that a steady step
// allocates nothing.
void ConstraintSolver::reportImpulses(Workers &workers, const BodyStore &bodies, const PairCache &pairs,
                                      std::vector<ContactImpulse> &out) {
    // Written on the threads, slot by slot; a slot whose body was isolated keeps no-body
    // handles and goes before the sort.
    const std::size_t first = out.size();
    makeRoom(out, manifolds_.size());
    out.resize(first + manifolds_.size());
    workers.forEach(manifolds_.size(), [&](std::size_t s) {
        ContactImpulse &entry = out[first + s];
        if (!pairs[sources_[s].pair].alive) {
            entry = ContactImpulse();
            return;
        }
        const SlotBodies pair = slotBodies_[s];
        entry = {bodies.idOf(pair.a), bodies.idOf(pair.b), bodies[pair.a].userData, bodies[pair.b].userData,
                 stepImpulse_[s]};
    });
    const auto begin = out.begin() + static_cast<std::ptrdiff_t>(first);
    out.erase(std::remove_if(begin, out.end(), [](const ContactImpulse &x) { return x.a == BodyId(); }),
              out.end());
    std::sort(begin, out.end(), [](const ContactImpulse &x, const ContactImpulse &y) {
        return x.a.index != y.a.index ? x.a.index < y.a.index : x.b.index < y.b.index;
    });
    auto kept = begin;
    for (auto it = begin; it != out.end(); ++it) {
        if (it != begin && kept->a == it->a && kept->b == it->b) {
            kept->normalImpulse += it->normalImpulse;
            continue;
        }
        if (it != begin) ++kept;
        *kept = *it;
    }
    if (begin != out.end()) out.erase(kept + 1, out.end());
}

}  // namespace cyclone::detail
