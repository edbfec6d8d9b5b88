// The joints' lifecycle (add, remove, wake, break) and their solve: the direct block of
// the equality rows, the bounded rows' sequential impulses, the position projection.
#include "joints/joint_set.h"

#include <algorithm>
#include <cmath>

#include "cyclone/world/settings.h"
#include "world/body_store.h"
#include "world/free_slots.h"
#include "world/step_context.h"

namespace cyclone::detail {
namespace {

real rate(const JointRow &r, const std::vector<SolverBody> &bodies) {
    const SolverBody &a = bodies[r.a];
    const SolverBody &b = bodies[r.b];
    return r.linA.dot(toVector3(a.v)) + r.angA.dot(toVector3(a.w)) + r.linB.dot(toVector3(b.v)) +
           r.angB.dot(toVector3(b.w));
}

void apply(const JointRow &r, real impulse, std::vector<SolverBody> &bodies) {
    if (r.a != 0) {
        SolverBody &a = bodies[r.a];
        setLanes(a.v, toVector3(a.v) + r.mLinA * impulse);
        setLanes(a.w, toVector3(a.w) + r.mAngA * impulse);
    }
    if (r.b != 0) {
        SolverBody &b = bodies[r.b];
        setLanes(b.v, toVector3(b.v) + r.mLinB * impulse);
        setLanes(b.w, toVector3(b.w) + r.mAngB * impulse);
    }
}

// J_i,c . M_c^-1 J_j,c for the rows' shared body on sides si, sj (0: a, 1: b).
real coupling(const JointRow &ri, int si, const JointRow &rj, int sj) {
    const Vector3 &lin = si == 0 ? ri.linA : ri.linB;
    const Vector3 &ang = si == 0 ? ri.angA : ri.angB;
    const Vector3 &mLin = sj == 0 ? rj.mLinA : rj.mLinB;
    const Vector3 &mAng = sj == 0 ? rj.mAngA : rj.mAngB;
    return lin.dot(mLin) + ang.dot(mAng);
}

}  // namespace

JointId JointSet::add(const BodyStore &bodies, const JointSettings &s) {
    const std::uint32_t index = takeSlot(records, free);
    JointRecord &j = records[index];
    const std::uint32_t generation = j.generation;
    j = JointRecord();
    j.generation = generation;
    j.alive = true;
    j.settings = s;
    const RigidBody &a = bodies[s.a.index].body;
    const bool twoPoints = s.type == JointType::Distance || s.type == JointType::Mouse;
    const Vector3 anchorB = twoPoints && s.anchorB ? *s.anchorB : s.anchor;
    j.localA = a.getPointInLocalSpace(s.anchor);
    j.axisA = a.getDirectionInLocalSpace(s.axis);
    Quaternion qb = Quaternion::Identity();
    if (s.b) {
        const RigidBody &b = bodies[s.b->index].body;
        j.localB = b.getPointInLocalSpace(anchorB);
        j.axisB = b.getDirectionInLocalSpace(s.axis);
        qb = b.getOrientation();
    } else {
        j.localB = anchorB;
        j.axisB = s.axis;
    }
    j.reference = qb.conjugate() * a.getOrientation();
    if (s.swingLimit) {
        // The cone's normal: the one given, or any perpendicular of a round cone's axis.
        const Vector3 helper = std::abs(s.axis.x()) < 0.57 ? Vector3::UnitX() : Vector3::UnitY();
        Vector3 normal = s.normal ? *s.normal : s.axis.cross(helper);
        normal = (normal - normal.dot(s.axis) * s.axis).normalized();
        j.normalA = a.getDirectionInLocalSpace(normal);
    }
    const real distance = (s.anchor - anchorB).norm();
    j.minDistance = s.minDistance.value_or(distance);
    j.maxDistance = s.maxDistance.value_or(distance);
    if (s.b && !s.collideConnected) ++excluded_[pairKey(s.a.index, s.b->index)];
    ++count;
    return {index, j.generation};
}

void JointSet::remove(std::uint32_t index) {
    JointRecord &j = records[index];
    if (j.settings.b && !j.settings.collideConnected) {
        const auto it = excluded_.find(pairKey(j.settings.a.index, j.settings.b->index));
        if (--it->second == 0) excluded_.erase(it);
    }
    freeSlot(records, free, index);
    --count;
}

void JointSet::beginStep(StepContext &context, const BodyStore &bodies, BodyTransitions transitions) {
    if (empty()) return;
    stepTime_ = 0;
    for (JointRecord &j : records) {
        if (!j.alive) continue;
        j.linearImpulse.setZero();
        j.angularImpulse.setZero();
        const BodyRecord &a = bodies[j.settings.a.index];
        const BodyRecord *b = j.settings.b ? &bodies[j.settings.b->index] : nullptr;
        if (!a.simulated && !(b && b->simulated)) continue;
        if (a.isolated || (b && b->isolated)) continue;
        // A joint joins its bodies: one awake end wakes the other.
        if (!a.simulated && !a.immovable) transitions.wake(j.settings.a.index);
        if (b && !b->simulated && !b->immovable) transitions.wake(j.settings.b->index);
        ++context.activeJoints;
    }
}

void JointSet::prepare(const StepContext &context, const BodyStore &bodies,
                       const std::vector<SolverBody> &solverBodies, StepStats &stats) {
    const bool warmStarting = context.settings.debug.warmStarting;
    const real h = context.h;
    if (context.activeJoints == 0) {
        rows_.clear();
        return;
    }
    stepTime_ += h;
    makeRows(bodies, warmStarting, solverBodies, h, false);
    factorise(solverBodies);
    constrainBoundedMasses(solverBodies, h);
    stats.jointRows += static_cast<int>(rows_.size());
}

void JointSet::factorise(const std::vector<SolverBody> &solverBodies) {
    const int n = static_cast<int>(equality_.size());
    factorised_ = false;
    if (n == 0) return;
    // The equality rows of each movable body, with the side it is on.
    rowsOfBody_.resize(solverBodies.size());
    for (std::vector<int> &list : rowsOfBody_) list.clear();
    for (int i = 0; i < n; ++i) {
        const JointRow &r = rows_[equality_[i]];
        if (r.a != 0 && solverBodies[r.a].invMass > 0) rowsOfBody_[r.a].push_back(2 * i);
        if (r.b != 0 && solverBodies[r.b].invMass > 0) rowsOfBody_[r.b].push_back(2 * i + 1);
    }
    // K = J M^-1 J^T, summed body by body (the lower triangle is enough for LDL^T, but
    // both are given: SimplicialLDLT reads the lower one by default).
    triplets_.clear();
    for (const std::vector<int> &list : rowsOfBody_) {
        for (const int ei : list) {
            for (const int ej : list) {
                if (ej > ei) continue;
                const JointRow &ri = rows_[equality_[ei / 2]];
                const JointRow &rj = rows_[equality_[ej / 2]];
                triplets_.emplace_back(ei / 2, ej / 2, coupling(ri, ei % 2, rj, ej % 2));
            }
        }
    }
    // A tiny relative regulariser keeps redundant rows (a loop, two joints on one pair)
    // solvable; their shared impulse then splits between them.
    for (int i = 0; i < n; ++i) {
        const JointRow &r = rows_[equality_[i]];
        const real diagonal = r.mass > 0 ? 1 / r.mass : 0;
        triplets_.emplace_back(i, i, diagonal * 1e-9 + 1e-15);
    }
    Eigen::SparseMatrix<real> k(n, n);
    k.setFromTriplets(triplets_.begin(), triplets_.end());
    ldlt_.compute(k);
    factorised_ = ldlt_.info() == Eigen::Success;
    rhs_.resize(n);
}

// A bounded row's impulse is followed by the equality block's answer to it, which gives
// back part of what it did: a door's limit row alone sees the door's inertia about its
// centre, but the hinge makes it turn about its edge. Its mass is therefore the one it has
// with the equality rows held, 1 / (k_bb - k_be K^-1 k_eb) (the Schur complement), with
// which one pass stops a limit exactly. A pull block's 3x3 mass is held the same way.
void JointSet::constrainBoundedMasses(const std::vector<SolverBody> &solverBodies, real h) {
    const bool held = !equality_.empty() && factorised_;
    const std::size_t n = equality_.size();
    heldResponse_.assign(bounded_.size() * n, 0);
    responds_.assign(bounded_.size(), 0);
    for (std::size_t b = 0; b < bounded_.size(); ++b) {
        JointRow &r = rows_[bounded_[b]];
        holdMass(solverBodies, b, held);
        if (r.frequency > 0) soften(r, h);
    }
    for (PullBlock &p : pulls_) {
        const JointRow *r = &rows_[p.row];
        Matrix3 k;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) k(i, j) = coupling(r[i], 0, r[j], 0);
        if (held) {
            // The rows' couplings to the equality rows, and K^-1 of them, column by column.
            Eigen::Matrix<real, Eigen::Dynamic, 3> coupled(equality_.size(), 3), solved(equality_.size(), 3);
            bool any = false;
            for (int i = 0; i < 3; ++i) {
                any = solveCoupling(solverBodies, r[i]) || any;
                coupled.col(i) = rhs_;
                solved.col(i) = delta_;
            }
            const Matrix3 schur = k - coupled.transpose() * solved;
            if (any && schur.allFinite() && schur.trace() > 1e-9 * k.trace()) k = schur;
        }
        k.diagonal().array() += r[0].gamma;
        p.mass = k.inverse();
    }
}

void JointSet::holdMass(const std::vector<SolverBody> &solverBodies, std::size_t b, bool held) {
    JointRow &r = rows_[bounded_[b]];
    if (!held || !solveCoupling(solverBodies, r)) return;
    const std::size_t n = equality_.size();
    const real k0 = r.mass > 0 ? 1 / r.mass - r.gamma : 0;
    const real schur = k0 - rhs_.dot(delta_);
    // A row the equality rows fix entirely (schur ~ 0) keeps its free mass.
    if (!(schur > 1e-9 * k0 && std::isfinite(schur)) || !delta_.allFinite()) return;
    r.mass = 1 / (schur + r.gamma);
    // K^-1 J_e M^-1 J_r^T: what the equality rows give back per N s of this row.
    for (std::size_t i = 0; i < n; ++i) heldResponse_[b * n + i] = delta_[static_cast<Eigen::Index>(i)];
    responds_[b] = 1;
}

// A servo's or a soft limit's spring, stiffness m w^2 and damping 2 m zeta w for the
// row's held mass m, taken implicitly over the sub-step h (Catto's soft step, in Box2D
// v3's form): with a1 = 2 zeta + h w and a2 = h w a1, the impulse is
// -a2/(1+a2) m (J v + w/a1 C) - 1/(1+a2) times the accumulated impulse. A soft limit
// within its range stays a rigid, speculative one (it may close what is left of it).
void JointSet::soften(JointRow &r, real h) {
    const real omega = 2 * M_PI * r.frequency;
    const real a1 = 2 * r.dampingRatio + h * omega;
    const real a2 = h * omega * a1;
    const bool within = (r.bound == RowBound::Lower && r.error >= 0) || (r.bound == RowBound::Upper && r.error <= 0);
    if (within) {
        r.massScale = 1;
        r.impulseScale = 0;
        r.bias = r.error / h;
        return;
    }
    r.massScale = a2 / (1 + a2);
    r.impulseScale = 1 / (1 + a2);
    r.bias = omega / a1 * r.error;
}

bool JointSet::solveCoupling(const std::vector<SolverBody> &solverBodies, const JointRow &r) {
    rhs_.setZero(static_cast<Eigen::Index>(equality_.size()));
    bool coupled = false;
    for (int side = 0; side < 2; ++side) {
        const int body = side == 0 ? r.a : r.b;
        if (body == 0 || !(solverBodies[body].invMass > 0)) continue;
        for (const int e : rowsOfBody_[body]) {
            rhs_[e / 2] += coupling(rows_[equality_[e / 2]], e % 2, r, side);
            coupled = true;
        }
    }
    if (coupled) delta_ = ldlt_.solve(rhs_);
    else delta_.setZero(rhs_.size());
    return coupled;
}

void JointSet::warmStart(std::vector<SolverBody> &solverBodies) const {
    for (const JointRow &r : rows_)
        if (r.impulse != 0) apply(r, r.impulse, solverBodies);
}

// The equality rows at once: the impulses that make J v = 0 exactly.
void JointSet::solveEquality(std::vector<SolverBody> &solverBodies) {
    const int n = static_cast<int>(equality_.size());
    for (int i = 0; i < n; ++i) rhs_[i] = -rate(rows_[equality_[i]], solverBodies);
    delta_ = ldlt_.solve(rhs_);
    for (int i = 0; i < n; ++i) {
        JointRow &r = rows_[equality_[i]];
        if (!std::isfinite(delta_[i])) continue;
        r.impulse += delta_[i];
        apply(r, delta_[i], solverBodies);
    }
}

// The bounded rows' and pulls' masses are those with the equality rows held
// (constrainBoundedMasses): right only for velocities that keep the equality rows, and
// only if each row's impulse is answered by the equality rows before the next row looks.
// So the equality rows are solved first as well as last, and each bounded row's impulse
// is followed at once by their answer to it (heldResponse_): the bounded rows then make a
// Gauss-Seidel pass over the held system. Without either, a ragdoll whose limbs are thrown
// apart has its limits' impulses overshoot more with every pass until its state is no
// longer finite (docs/joints.md, "Limits and pulls see held velocities").
void JointSet::solveVelocities(std::vector<SolverBody> &solverBodies) {
    const bool held = factorised_ && !equality_.empty();
    if (held && (!bounded_.empty() || !pulls_.empty())) solveEquality(solverBodies);
    const std::size_t n = equality_.size();
    for (std::size_t b = 0; b < bounded_.size(); ++b) {
        JointRow &r = rows_[bounded_[b]];
        real delta;
        const real old = r.impulse;
        if (r.frequency > 0) {
            // A servo or a soft limit: a spring (soften).
            delta = -r.massScale * r.mass * (rate(r, solverBodies) + r.bias) - r.impulseScale * old;
            if (r.bound == RowBound::Motor) r.impulse = std::clamp(old + delta, -r.maxImpulse, r.maxImpulse);
            else r.impulse = r.bound == RowBound::Lower ? std::max(old + delta, real(0)) : std::min(old + delta, real(0));
        } else if (r.bound == RowBound::Motor) {
            delta = -r.mass * (rate(r, solverBodies) - r.target);
            r.impulse = std::clamp(old + delta, -r.maxImpulse, r.maxImpulse);
        } else {
            delta = -r.mass * (rate(r, solverBodies) + r.bias + r.gamma * old);
            r.impulse = r.bound == RowBound::Lower ? std::max(old + delta, real(0)) : std::min(old + delta, real(0));
        }
        const real change = r.impulse - old;
        apply(r, change, solverBodies);
        // The equality rows' answer at once, as the held mass assumed: the bounded rows
        // then see each other through the held system, not the free one.
        if (!held || !responds_[b] || change == 0) continue;
        for (std::size_t i = 0; i < n; ++i) {
            const real answer = -heldResponse_[b * n + i] * change;
            JointRow &e = rows_[equality_[i]];
            e.impulse += answer;
            apply(e, answer, solverBodies);
        }
    }
    if (!pulls_.empty()) solvePulls(solverBodies);
    if (n == 0) return;
    if (!factorised_) {
        // Sequential impulses, should the factorisation ever fail.
        for (const int k : equality_) {
            JointRow &r = rows_[k];
            const real delta = -r.mass * rate(r, solverBodies);
            r.impulse += delta;
            apply(r, delta, solverBodies);
        }
        return;
    }
    solveEquality(solverBodies);
}

// Catto's soft step for the three rows at once: the impulse that makes J v + bias +
// gamma lambda vanish, the accumulated impulse's length then clamped to maxForce h (so the
// pull's force is bounded whatever its direction, not component by component).
void JointSet::solvePulls(std::vector<SolverBody> &solverBodies) {
    for (const PullBlock &p : pulls_) {
        JointRow *r = &rows_[p.row];
        Vector3 old, residual;
        for (int i = 0; i < 3; ++i) {
            old[i] = r[i].impulse;
            residual[i] = rate(r[i], solverBodies) + r[i].bias + r[i].gamma * old[i];
        }
        Vector3 impulse = old - p.mass * residual;
        const real length = impulse.norm();
        if (length > r[0].maxImpulse) impulse *= r[0].maxImpulse / length;
        for (int i = 0; i < 3; ++i) {
            r[i].impulse = impulse[i];
            apply(r[i], impulse[i] - old[i], solverBodies);
        }
    }
}

void JointSet::storeImpulses() {
    // A joint's rows are consecutive: its slots without a row this sub-step start at 0.
    std::uint32_t last = UINT32_MAX;
    for (const JointRow &r : rows_) {
        JointRecord &j = records[r.joint];
        if (r.joint != last) std::fill(std::begin(j.impulse), std::end(j.impulse), real(0));
        last = r.joint;
        j.impulse[r.slot] = r.impulse;
        if (r.angular) j.angularImpulse += r.angA * r.impulse;
        else j.linearImpulse += r.linA * r.impulse;
    }
}

JointSet::EqualityErrors JointSet::equalityErrors() const {
    EqualityErrors e;
    for (const int k : equality_) {
        e.largest = std::max(e.largest, std::abs(rows_[k].error));
        e.squares += rows_[k].error * rows_[k].error;
    }
    return e;
}

void JointSet::applyMoves(BodyStore &bodies, real scale) const {
    for (std::size_t k = 0; k < bodies.simulated.size(); ++k) {
        const Vector3 dx = scale * moves_[2 * (k + 1)];
        const Vector3 dq = scale * moves_[2 * (k + 1) + 1];
        if (dx.isZero(0) && dq.isZero(0)) continue;
        RigidBody &body = bodies[bodies.simulated[k]].body;
        Quaternion q = body.getOrientation();
        const Quaternion spin(0, dq.x(), dq.y(), dq.z());
        q.coeffs() += 0.5 * (spin * q).coeffs();
        body.setPosition(body.getPosition() + dx);
        body.setOrientation(q);
    }
}

// Newton's iteration on the positions: one step is exact for a joint alone, but a
// whipping chain turns its links far enough in a sub-step that the linearisation needs a
// few more; they stop once every row is within kProjectionTolerance. Near a singular pose
// (a chain pulled straight by a heavy end) a full step can overshoot and leave the rows
// further out than before, and sub-step after sub-step such steps can tear a thrown heavy
// chain apart for good (docs/joints.md, "A Newton step that overshoots"). So a step
// that leaves the sum of the squared row errors larger is taken back and halved, up to
// kProjectionHalvings times; if it still does then, it is taken back and the projection
// ends for the sub-step. A step that does not overshoot is taken whole. (The Newton step
// lowers the sum of squares to first order, so a short enough part of it does too; the
// largest error alone has no such guarantee.)
void JointSet::correctPositions(const StepContext &context, BodyStore &bodies,
                                const std::vector<SolverBody> &solverBodies) {
    const bool warmStarting = context.settings.debug.warmStarting;
    const int iterations = context.settings.positionIterations;
    if (context.activeJoints == 0) return;
    const int projections = iterations > 0 ? std::max(iterations, kMaxProjections) : 0;
    if (projections == 0) {
        rows_.clear();
        return;
    }
    makeRows(bodies, warmStarting, solverBodies, 1, true);
    EqualityErrors errors = equalityErrors();
    for (int it = 0; it < projections; ++it) {
        if (!(errors.largest > kProjectionTolerance)) break;
        factorise(solverBodies);
        if (!factorised_) break;
        const int n = static_cast<int>(equality_.size());
        for (int i = 0; i < n; ++i) rhs_[i] = -rows_[equality_[i]].error;
        delta_ = ldlt_.solve(rhs_);
        if (!delta_.allFinite()) break;
        // The moves M^-1 J^T delta, body by body.
        moves_.assign(2 * solverBodies.size(), Vector3::Zero());
        for (int i = 0; i < n; ++i) {
            const JointRow &r = rows_[equality_[i]];
            moves_[2 * r.a] += r.mLinA * delta_[i];
            moves_[2 * r.a + 1] += r.mAngA * delta_[i];
            moves_[2 * r.b] += r.mLinB * delta_[i];
            moves_[2 * r.b + 1] += r.mAngB * delta_[i];
        }
        savedPositions_.resize(bodies.simulated.size());
        savedOrientations_.resize(bodies.simulated.size());
        for (std::size_t k = 0; k < bodies.simulated.size(); ++k) {
            const RigidBody &body = bodies[bodies.simulated[k]].body;
            savedPositions_[k] = body.getPosition();
            savedOrientations_[k] = body.getOrientation();
        }
        const auto takeBack = [&] {
            for (std::size_t k = 0; k < bodies.simulated.size(); ++k) {
                RigidBody &body = bodies[bodies.simulated[k]].body;
                body.setPosition(savedPositions_[k]);
                body.setOrientation(savedOrientations_[k]);
            }
        };
        bool progressed = false;
        real scale = 1;
        for (int halving = 0; halving <= kProjectionHalvings && !progressed; ++halving, scale *= 0.5) {
            if (halving > 0) takeBack();
            applyMoves(bodies, scale);
            makeRows(bodies, warmStarting, solverBodies, 1, true);
            const EqualityErrors after = equalityErrors();
            progressed = after.squares <= errors.squares;
            if (progressed) errors = after;
        }
        if (!progressed) {
            takeBack();
            break;
        }
    }
    rows_.clear();
}

void JointSet::finishStep(const StepContext &context, const BodyStore &bodies, BodyTransitions transitions,
                          WorldEvents &events) {
    if (context.activeJoints == 0) return;
    const real time = stepTime_ > 0 ? stepTime_ : context.dt;
    broken_.clear();
    for (std::uint32_t index = 0; index < records.size(); ++index) {
        JointRecord &j = records[index];
        if (!j.alive) continue;
        j.force = j.linearImpulse / time;
        j.torque = j.angularImpulse / time;
        if (j.force.norm() > j.settings.breakForce || j.torque.norm() > j.settings.breakTorque)
            broken_.push_back(index);
    }
    for (const std::uint32_t index : broken_) {
        JointRecord &j = records[index];
        events.jointsBroken.push_back({{index, j.generation}, j.force, j.torque});
        const BodyId a = j.settings.a;
        const std::optional<BodyId> b = j.settings.b;
        remove(index);
        if (!bodies[a.index].immovable) transitions.wake(a.index);
        if (b && !bodies[b->index].immovable) transitions.wake(b->index);
    }
}

void JointSet::removeJointsOf(const BodyStore &bodies, BodyTransitions transitions, BodyId id) {
    if (empty()) return;
    for (std::uint32_t index = 0; index < records.size(); ++index) {
        const JointRecord &j = records[index];
        if (!j.alive) continue;
        const bool onA = j.settings.a == id;
        const bool onB = j.settings.b && *j.settings.b == id;
        if (!onA && !onB) continue;
        const std::optional<BodyId> other = onA ? j.settings.b : std::optional<BodyId>(j.settings.a);
        remove(index);
        if (other && bodies.contains(*other) && !bodies[other->index].immovable) transitions.wake(other->index);
    }
}

}  // namespace cyclone::detail
