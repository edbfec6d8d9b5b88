// The solve and integrate stages of World::step.
//
// Each sub-step of h seconds: the velocities each body would reach without contacts are
// predicted (exactly what RigidBody::integrate(h) will produce; with a gyroscopic
// integrator, the step's gyroscopic change is given to the body first; with the
// momentum-conserving one, what integrate(h) turns the body with, but for half the
// torque's impulse, until its torque-free motion changes it), the contact solver
// corrects them, the correction reaches the body through addVelocity / addRotation,
// and RigidBody::integrate(h) moves it. Penetration is then recovered without adding
// energy: pseudo-velocities (SplitImpulse) or a rigid relax pass (SoftStep).
#include <chrono>
#include <cmath>

#include "validation.h"
#include "world_impl.h"

namespace cyclone {
namespace {

// Finite, and within the coordinates FCL can place: otherwise the body is isolated.
bool stateFinite(const RigidBody &body) {
    return body.getPosition().allFinite() && body.getPosition().cwiseAbs().maxCoeff() <= detail::kMaxCoordinate && body.getOrientation().coeffs().allFinite() &&
           body.getVelocity().allFinite() && body.getRotation().allFinite() &&
           std::isfinite(body.getVelocity().squaredNorm() + body.getRotation().squaredNorm());
}

// Adds the milliseconds of its scope to `total` (a part of StageTimes::solve).
class AddTime {
public:
    explicit AddTime(double &total) : total_(total) {}
    AddTime(const AddTime &) = delete;
    AddTime &operator=(const AddTime &) = delete;
    ~AddTime() { total_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count(); }

private:
    double &total_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The frame that gives a manifold's depths along `normal` at the bodies' current poses
// (detail::DepthFrame): a rotation transposed is its inverse.
detail::DepthFrame depthFrame(const RigidBody &a, const RigidBody &b, const Vector3 &normal) {
    return {a.getTransform().linear().transpose() * normal, b.getTransform().linear().transpose() * normal,
            (a.getPosition() - b.getPosition()).dot(normal)};
}

}  // namespace

void World::Impl::matchThreads() {
    if (settings.threads <= 1) pool.reset();
    else if (!pool || pool->threads() != settings.threads) pool = std::make_unique<detail::TaskPool>(settings.threads);
}

void World::Impl::prepareSolver(real h) {
    const std::size_t n = simulatedBodies.size();
    solverBodies.resize(n + 1);
    solverBodies[0] = detail::SolverBody();
    predictedV.resize(n);
    predictedW.resize(n);
    linearFactor.resize(n);
    angularFactor.resize(n);
    solverPositions.resize(n + 1);
    forEachBody([&](std::size_t k) {
        const RigidBody &body = bodies[simulatedBodies[k]].body;
        detail::SolverBody &sb = solverBodies[k + 1];
        sb = detail::SolverBody();
        detail::setLanes(sb.v, body.getVelocity());
        detail::setLanes(sb.w, body.getRotation());
        sb.invMass = body.getInverseMass();
        sb.invInertia = body.getInverseInertiaTensorWorld();
        body.getDampingFactors(h, &linearFactor[k], &angularFactor[k]);
        solverPositions[k + 1] = body.getPosition();
    });
    if (settings.contactSolver == ContactSolverType::SoftStep) {
        // A contact spring faster than a quarter of the sub-step rate is not resolved.
        soft.dynamicSoftness = detail::makeSoftness(std::min(settings.contactHertz, 0.25 / h),
                                                    settings.contactDampingRatio, h);
        soft.staticSoftness = detail::makeSoftness(std::min(2 * settings.contactHertz, 0.25 / h),
                                                   settings.contactDampingRatio, h);
        soft.slop = settings.penetrationSlop;
        soft.maxPushVelocity = settings.maxPushVelocity;
    }
    if (solverManifolds.empty()) return;  // nothing below is read without contacts
    // The split reads the manifolds' bodies, the support their normals, and writes only
    // `support`: the two run at once.
    const bool support = settings.shockPropagation && settings.contactSolver == ContactSolverType::SplitImpulse;
    forEachTask(support ? 2 : 1, [&](int task) {
        if (task == 0) {
            detail::partitionManifolds(solverManifolds, solverHeights, solveOrder, solverPositions, pool != nullptr,
                                          partitionScratch, partition);
        } else {
            detail::assignSupport(static_cast<int>(solverBodies.size()), -settings.gravity, solverManifolds,
                                  solveOrder, supportScratch, supportRuns);
        }
    });
    if (support) {
        const bool shared = pool && partition.split;
        detail::buildSupportLanes(supportRuns, solverManifolds, shared ? &partitionScratch.side : nullptr,
                                  static_cast<int>(solverBodies.size()), supportLanes);
    }
    // Jacobians and effective masses are made once per step, at the step's poses, unless
    // the slot's still hold (jacobian_stamp.h).
    forEachManifold([&](std::size_t s) {
        prepareManifold(s);
        detail::JacobianStamp &stamp = jacobianStamps[s];
        if (support && stamp.support != solverManifolds[s].support) {
            detail::prepareSupportedMasses(solverBodies, solverManifolds[s]);
            stamp.support = solverManifolds[s].support;
        }
    });
    for (std::size_t s = 0; s < solverManifolds.size(); ++s) {
        const detail::SolverManifold &m = solverManifolds[s];
        if (!jacobianStamps[s].kept) ++stats.jacobiansMade;
        if (m.friction > 0) stats.frictionRows += m.twistRadius > 0 ? 3 : 2;  // the patch: two tangents, a twist
        if (m.restitution == 0) continue;
        for (int i = 0; i < m.count; ++i)
            if (m.points[i].approachSpeed < -settings.restitutionThreshold) ++stats.restitutionContacts;
    }
}

void World::Impl::prepareManifold(std::size_t s) {
    detail::SolverManifold &m = solverManifolds[s];
    const SlotBodies records = solverRecords[s];
    const RigidBody &a = bodies[records.a].body;
    const RigidBody &b = bodies[records.b].body;
    m.restitution = std::max(bodies[records.a].material.restitution, bodies[records.b].material.restitution);
    m.touchesStatic = m.a == 0 || m.b == 0;
    const detail::SolverBody &sa = solverBodies[m.a];
    const detail::SolverBody &sb = solverBodies[m.b];
    if (!jacobianStamps[s].kept) {
        detail::prepareDirections(m);
        Vector3 points[detail::kMaxManifoldPoints];
        for (int i = 0; i < m.count; ++i) {
            const detail::SolverPoint &p = m.points[i];
            points[i] = 0.5 * (a.getPointInWorldSpace(p.localA) + b.getPointInWorldSpace(p.localB));
            detail::prepareRows(sa, sb, points[i] - a.getPosition(), points[i] - b.getPosition(), m, m.points[i]);
        }
        detail::prepareFrictionRows(sa, sb, points, a.getPosition(), b.getPosition(), m);
        detail::prepareCouplings(sa, sb, m);
    }
    for (int i = 0; i < m.count; ++i) {
        detail::SolverPoint &p = m.points[i];
        p.maxNormalImpulse = 0;
        // The normal velocity when the step began, measured only for restitution.
        p.approachSpeed = m.restitution == 0 ? 0 : detail::normalVelocity(sa, sb, m, p);
    }
}

// The warm start (without split impulse: loadCoupledPasses makes it) and each coupled
// pass: the two halves of the partition at once, then the seam.
void World::Impl::warmStart() {
    forEachTask(partition.split ? 2 : 1, [&](int half) {
        detail::warmStart(solverBodies, solverManifolds, partition.order[half]);
    });
    detail::warmStart(solverBodies, solverManifolds, partition.order[detail::SolverPartition::kSeam]);
}

// The coupled passes work on a copy of the rows they solve (wide_pass.h), taken at the
// warm start, which each group makes as it is copied, and handed back, with the
// accumulated impulses, after the last pass. Every part is loaded, the empty ones too: an
// unsplit step must not find the seam's rows of an earlier split one. The seam comes
// last, as in a pass: its warm start moves bodies of both halves.
void World::Impl::loadCoupledPasses() {
    const bool warm = settings.warmStarting;
    const bool recovers = settings.positionIterations > 0;
    const auto pseudo = [&](int part) { return recovers ? &widePseudo[part] : nullptr; };
    forEachTask(2, [&](int half) {
        detail::loadWide(solverBodies, solverManifolds, partition.groups[half], warm, wideManifolds[half], pseudo(half));
    });
    const int seam = detail::SolverPartition::kSeam;
    detail::loadWide(solverBodies, solverManifolds, partition.groups[seam], warm, wideManifolds[seam], pseudo(seam));
}

void World::Impl::solveCoupledPass(bool reverse) {
    forEachTask(partition.split ? 2 : 1, [&](int half) { detail::solveWide(solverBodies, wideManifolds[half], reverse); });
    detail::solveWide(solverBodies, wideManifolds[detail::SolverPartition::kSeam], reverse);
}

void World::Impl::storeCoupledPasses() {
    forEachTask(3, [&](int part) {
        detail::storeWide(wideManifolds[part], partition.groups[part], solverManifolds);
    });
}

// The partition's halves at once, each run once its carriers are done (support_lanes.h).
void World::Impl::solveSupportPass(bool reverse) {
    detail::solveUnsupported(solverBodies, solverManifolds, solveOrder, reverse);
    detail::beginSupportPass(supportLanes);
    for (detail::WideSupportScratch &s : supportLanes.scratch) s.sweeps = 0;
    forEachTask(supportLanes.lane[1].empty() ? 1 : 2, [&](int lane) {
        detail::solveSupportLane(solverBodies, solverManifolds, supportRuns, supportLanes, lane, reverse);
    });
    for (const detail::WideSupportScratch &s : supportLanes.scratch) stats.supportSweeps += static_cast<int>(s.sweeps);
}

void World::Impl::solve(real h, bool firstSubstep) {
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
    const bool gyroscopic = settings.integrator == Integrator::NewtonEulerGyroscopic ||
                            settings.integrator == Integrator::NewtonEulerImplicit;
    for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
        BodyRecord &r = bodies[simulatedBodies[k]];
        detail::SolverBody &sb = solverBodies[k + 1];
        if (r.quarantined) {
            sb = detail::SolverBody();  // immovable from now on: its state reaches no one
            continue;
        }
        if (gyroscopic && firstSubstep && !r.body.hasIsotropicInertia()) {
            r.body.applyGyroscopicStep(GyroscopicStep::Midpoint, h * settings.substeps);
            ++stats.gyroscopicBodies;
        }
        const Vector3 a = r.body.getAcceleration() + r.body.getAccumulatedForce() * sb.invMass;
        // The body's current inertia, as integrate(h) uses, not the step's (sb.invInertia).
        const Vector3 alpha = r.body.getInverseInertiaTensorWorld() * r.body.getAccumulatedTorque();
        predictedV[k] = (r.body.getVelocity() + a * h) * linearFactor[k];
        predictedW[k] = (r.body.getRotation() + alpha * h) * angularFactor[k];
        detail::setLanes(sb.v, predictedV[k]);
        detail::setLanes(sb.w, predictedW[k]);
        sb.pv = detail::Lanes{};
        sb.pw = detail::Lanes{};
        if (!std::isfinite(predictedV[k].squaredNorm() + predictedW[k].squaredNorm())) {
            // A velocity beyond ~1e154 m/s would overflow impulses: isolate the body
            // before any contact carries it to a neighbour.
            quarantine(simulatedBodies[k]);
            sb = detail::SolverBody();
        }
    }

    // Current separations from the anchors (positions move only between sub-steps). In the
    // first sub-step the bodies are where the narrowphase found them, and its depths
    // (addSolverManifold) are current: along the normal it last found, which differs from
    // a kept manifold's (jacobian_stamp.h) by less than the reuse tolerance's turn.
    const bool split = settings.contactSolver == ContactSolverType::SplitImpulse;
    const real inverseH = 1 / h;
    forEachManifold([&](std::size_t s) {
        detail::SolverManifold &m = solverManifolds[s];
        if (!firstSubstep) {
            const detail::DepthFrame frame =
                depthFrame(bodies[solverRecords[s].a].body, bodies[solverRecords[s].b].body, m.normal);
            for (int i = 0; i < m.count; ++i) m.points[i].depth = frame.of(m.points[i]);
        }
        if (!split) return;
        for (int i = 0; i < m.count; ++i) {
            detail::SolverPoint &p = m.points[i];
            p.velocityBias = 0;
            if (p.depth < 0) {
                p.velocityBias = p.depth * inverseH;  // apart: may close the gap during this sub-step, no more
            } else if (firstSubstep && m.restitution > 0 && p.approachSpeed < -settings.restitutionThreshold) {
                p.velocityBias = -m.restitution * p.approachSpeed;
            }
        }
    });

    if (!solverManifolds.empty()) {
        if (split) loadCoupledPasses();
        else if (settings.warmStarting) warmStart();
        for (int it = 0; it < settings.velocityIterations; ++it) {
            if (split) solveCoupledPass((it & 1) != 0);
            else detail::solveSoft(solverBodies, solverManifolds, solveOrder, h, true, soft);
        }
        if (split) storeCoupledPasses();
        stats.velocityIterations += settings.velocityIterations;
        // The support pass comes after the coupled passes, never instead of one: alone,
        // it would let no body push the bodies carrying it.
        if (split && settings.shockPropagation) {
            const AddTime timed(stats.ms.solveParts.support);
            // A run sweeps its points in one direction: the other one next step, so that
            // no point of a face takes the larger share step after step (wide_support.h).
            solveSupportPass(((settings.velocityIterations & 1) != 0) != ((stepCount & 1) != 0));
        }
    }

    // integrate(h) will turn v into (v + a h) damping^h, so the change to give the body
    // now is the solver's change divided by the damping factor.
    //
    // The solver's rows hold the inverse inertia of the step's start pose, so its change
    // of w is that of an angular impulse through that inertia. The momentum-conserving
    // step turns w into angular momentum through the current one: it is given that
    // impulse (I_start dw) instead, or a body whose contacts cancel its torque-free wobble
    // in every sub-step would gain energy (a box spinning on a frictionless floor: 8.6% in
    // 20 s at 60 Hz, 4 sub-steps).
    const bool conserving = settings.integrator == Integrator::MomentumConserving;
    for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
        BodyRecord &r = bodies[simulatedBodies[k]];
        if (r.quarantined) continue;
        const detail::SolverBody &sb = solverBodies[k + 1];
        if (linearFactor[k] > 0) r.body.addVelocity((detail::toVector3(sb.v) - predictedV[k]) / linearFactor[k]);
        if (!(angularFactor[k] > 0)) continue;
        Vector3 dw = detail::toVector3(sb.w) - predictedW[k];
        if (conserving && !firstSubstep && !r.body.hasIsotropicInertia())
            dw = r.body.getInverseInertiaTensorWorld() * sb.invInertia.inverse() * dw;
        r.body.addRotation(dw / angularFactor[k]);
    }
}

void World::Impl::integrate(real h) {
    bodyFlags.assign(simulatedBodies.size(), 0);
    forEachBody([&](std::size_t k) {
        RigidBody &body = bodies[simulatedBodies[k]].body;
        if (bodies[simulatedBodies[k]].quarantined) return;
        body.integrate(h, false);
        bodyFlags[k] = !stateFinite(body);
    });
    for (std::size_t k = 0; k < simulatedBodies.size(); ++k)
        if (bodyFlags[k]) quarantine(simulatedBodies[k]);
}

void World::Impl::recoverPenetration(real h) {
    if (settings.positionIterations == 0 || solverManifolds.empty()) return;
    const AddTime timed(stats.ms.solveParts.position);
    if (settings.contactSolver == ContactSolverType::SoftStep) {
        // Relax: rigid passes without bias remove the velocity the soft push added.
        for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
            const RigidBody &body = bodies[simulatedBodies[k]].body;
            detail::setLanes(solverBodies[k + 1].v, body.getVelocity());
            detail::setLanes(solverBodies[k + 1].w, body.getRotation());
        }
        for (int it = 0; it < settings.positionIterations; ++it)
            detail::solveSoft(solverBodies, solverManifolds, solveOrder, h, false, soft);
        for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
            BodyRecord &r = bodies[simulatedBodies[k]];
            if (r.quarantined) continue;
            r.body.addVelocity(detail::toVector3(solverBodies[k + 1].v) - r.body.getVelocity());
            r.body.addRotation(detail::toVector3(solverBodies[k + 1].w) - r.body.getRotation());
        }
        stats.positionIterations += settings.positionIterations;
        return;
    }

    // Split impulse: pseudo-velocities push penetration beyond the slop out by a fraction
    // per sub-step; they move positions only and are forgotten, so they add no energy.
    // The passes run on the coupled passes' groups and rows (wide_pseudo.h); the first
    // sets each group's targets from its depths at the poses integration left.
    depthFrames.resize(solverManifolds.size());
    forEachManifold([&](std::size_t s) {
        depthFrames[s] = depthFrame(bodies[solverRecords[s].a].body, bodies[solverRecords[s].b].body,
                                    solverManifolds[s].normal);
    });
    const detail::PseudoTargets targets{depthFrames.data(), settings.penetrationSlop,
                                        settings.penetrationRecovery / h};
    const int seam = detail::SolverPartition::kSeam;
    const int last = settings.positionIterations - 1;
    for (int it = 0; it <= last; ++it) {
        const bool support = it == last && settings.shockPropagation;
        const detail::PseudoTargets *set = it == 0 ? &targets : nullptr;
        const auto pass = [&](int part) {
            return detail::solveWidePseudo(solverBodies, wideManifolds[part], widePseudo[part], partition.groups[part],
                                           support, set);
        };
        bool pushed[3] = {};
        forEachTask(partition.split ? 2 : 1, [&](int half) { pushed[half] = pass(half); });
        pushed[seam] = pass(seam);
        if (it == 0 && !pushed[0] && !pushed[1] && !pushed[seam]) return;  // nothing penetrates beyond what is allowed
    }
    stats.positionIterations += settings.positionIterations;
    forEachBody([&](std::size_t k) {
        BodyRecord &r = bodies[simulatedBodies[k]];
        detail::SolverBody &sb = solverBodies[k + 1];
        const Vector3 pv = detail::toVector3(sb.pv);
        const Vector3 pw = detail::toVector3(sb.pw);
        if (r.quarantined || (pv.isZero(0) && pw.isZero(0))) return;
        Quaternion q = r.body.getOrientation();
        const Quaternion spin(0, pw.x() * h, pw.y() * h, pw.z() * h);
        q.coeffs() += 0.5 * (spin * q).coeffs();
        r.body.setPosition(r.body.getPosition() + pv * h);
        r.body.setOrientation(q);
        sb.pv = detail::Lanes{};
        sb.pw = detail::Lanes{};
    });
}

void World::Impl::restitution() {
    if (settings.contactSolver != ContactSolverType::SoftStep || stats.restitutionContacts == 0) return;
    for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
        const RigidBody &body = bodies[simulatedBodies[k]].body;
        detail::setLanes(solverBodies[k + 1].v, body.getVelocity());
        detail::setLanes(solverBodies[k + 1].w, body.getRotation());
    }
    detail::applyRestitution(solverBodies, solverManifolds, solveOrder, settings.restitutionThreshold);
    for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
        BodyRecord &r = bodies[simulatedBodies[k]];
        if (r.quarantined) continue;
        r.body.addVelocity(detail::toVector3(solverBodies[k + 1].v) - r.body.getVelocity());
        r.body.addRotation(detail::toVector3(solverBodies[k + 1].w) - r.body.getRotation());
    }
}

void World::Impl::storeImpulses() {
    forEachManifold([&](std::size_t s) {
        const detail::SolverManifold &m = solverManifolds[s];
        detail::PairState &pair = pairs[solverSource[s] >> 2];
        const std::size_t k = solverSource[s] & 3;
        if (!pair.alive || k >= pair.manifolds.size()) return;  // a body was quarantined
        detail::ManifoldState &state = pair.manifolds[k];
        for (int i = 0; i < m.count; ++i) state.points[i].normalImpulse = m.points[m.order[i]].normal.impulse;
        state.frictionImpulse = m.frictionRow[0].impulse * m.tangent[0] + m.frictionRow[1].impulse * m.tangent[1];
        state.twistImpulse = m.twist.impulse;
    });
}

}  // namespace cyclone
