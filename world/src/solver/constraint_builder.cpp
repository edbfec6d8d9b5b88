// Building the step's constraints: the touching pairs' manifolds ordered lowest first,
// each in a solver slot (kept from step to step so that its Jacobians can be), then the
// Jacobians and effective masses of every slot whose Jacobians do not still hold
// (jacobian_stamp.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "contacts/contact_manager.h"
#include "contacts/pose_change.h"
#include "contacts/pre_solve.h"
#include "dynamics/axis_locks.h"
#include "solver/constraint_solver.h"
#include "world/room.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// Solve-order height of a contact between a and b: the lower body's, m along `up`.
real contactHeight(const BodyRecord &a, const BodyRecord &b, const Vector3 &up) {
    const real lowest = -std::numeric_limits<real>::infinity();
    const real ha = a.immovable ? lowest : a.body.getPosition().dot(up);
    const real hb = b.immovable ? lowest : b.body.getPosition().dot(up);
    return std::min(ha, hb);
}

// Whether a body is still in its stamped role, within `tolerance` of its stamped pose.
bool stillStamped(const StampedBody &stamped, const BodyRecord &r, real tolerance) {
    if (stamped.movable != (r.simulated || r.moving)) return false;
    if (r.isPlane) return true;  // a plane cannot be moved (World::setPosition refuses it)
    const real shift = (r.body.getPosition() - stamped.position).norm();
    return movedLess(shift, r.body.getOrientation() * stamped.orientation.conjugate(), r.boundingRadius, tolerance);
}

// A moving kinematic body's turn over half the step, |w| dt / 2 about w, into `turn`;
// false when it does not turn. Its side of a contact's rows, with lever arms turned by
// it, sees the velocity its surface point has at mid-step: along the chord of the point's
// arc over the step, so that a body its friction carries lands where the point lands
// (docs/kinematic.md).
bool midStepTurn(const RigidBody &body, real dt, Matrix3 &turn) {
    const Vector3 w = body.getRotation();
    const real speed = w.norm();
    if (!(speed > 0)) return false;
    turn = Eigen::AngleAxis<real>(0.5 * speed * dt, w / speed).toRotationMatrix();
    return true;
}

void stampBody(StampedBody &stamped, const BodyRecord &r) {
    stamped.movable = r.simulated || r.moving;
    stamped.position = r.body.getPosition();
    stamped.orientation = r.body.getOrientation();
}

}  // namespace

void ConstraintSolver::build(StepContext &context, const BodyStore &bodies, ContactManager &contacts,
                             PreSolve &preSolve, StepStats &stats) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    const std::uint64_t stepCount = context.stepCount;
    // The solve order is settled on small keys first and the solver manifolds are then
    // built in that order: sorting the built manifolds (~2 KB each) meant copying all of
    // them every step.
    // The keys are made on the threads, chunk by chunk of the touching pairs, and read
    // back in the chunks' order: the pairs' order.
    const Vector3 up = -settings.gravity;
    const std::vector<std::uint32_t> &touching = contacts.touchingPairs;
    const std::size_t chunks = Workers::chunksOf(touching.size());
    chunkKeys_.start(workers.threads(), chunks);
    workers.forEachChunkOnThreads(touching.size(), [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
        std::vector<ManifoldKey> &found = chunkKeys_.open(chunk, thread);
        for (std::size_t t = begin; t < end; ++t) {
            const PairState &pair = contacts.pairs[touching[t]];
            const BodyRecord &a = bodies[pair.a];
            const BodyRecord &b = bodies[pair.b];
            if (!a.simulated && !b.simulated) continue;
            const real height = contactHeight(a, b, up);
            for (std::size_t k = 0; k < pair.manifolds.size(); ++k)
                if (pair.manifolds[k].count > 0) found.push_back({height, {touching[t], static_cast<std::uint32_t>(k)}});
        }
        chunkKeys_.close(chunk);
    });
    chunkKeys_.finish();
    keys_.clear();
    makeRoom(keys_, chunkKeys_.found());
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
        for (const ManifoldKey &key : chunkKeys_.items(chunk)) keys_.push_back(key);
    // Gauss-Seidel carries a stack's weight down in one pass when the contacts nearest
    // the ground come first; the order must not depend on the broadphase's. Equal heights
    // keep the order of the pair walk: the radix sort is stable. A comparison sort on
    // (height, place in the walk) would mispredict most of its branches here: a layer's
    // heights are equal but for rounding, so their order changes from step to step.
    sortByHeight(keys_, keysScratch_);
    // The contact listener and the built-in rules may disable manifolds (their keys go)
    // and change the others' friction, restitution and surface velocity.
    if (preSolve.active(bodies)) {
        stats.preSolvedManifolds += static_cast<int>(keys_.size());
        preSolve.run(bodies, contacts.pairs, keys_);
    } else if (preSolve.ran()) {
        preSolve.skip();
    }
    assignSlots(contacts.pairs, workers, stepCount);
    // Last step's manifolds are overwritten in place (see addSolverManifold); only new
    // slots are value-initialised.
    manifolds_.resize(keys_.size());
    sources_.resize(keys_.size());
    slotBodies_.resize(keys_.size());
    stamps_.resize(keys_.size());
    // Slot by slot: the slots are written in memory order.
    // The counters are summed chunk by chunk as the slots are written, then in the
    // chunks' order (a count and a maximum: the same whatever the order).
    chunkCounts_.resize(Workers::chunksOf(keys_.size()));
    workers.forEachChunk(keys_.size(), [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkCount &count = chunkCounts_[chunk];
        count = ChunkCount();
        for (std::size_t s = begin; s < end; ++s) {
            addSolverManifold(settings, bodies, contacts, preSolve, stepCount, context.plan.warmScale, keyOfSlot_[s], s);
            const SolverManifold &m = manifolds_[s];
            count.contacts += m.count;
            for (int i = 0; i < m.count; ++i) count.deepest = std::max(count.deepest, m.points[i].depth);
        }
    });
    stats.manifolds += static_cast<int>(keys_.size());
    for (const ChunkCount &count : chunkCounts_) {
        stats.contacts += count.contacts;
        context.deepest = std::max(context.deepest, count.deepest);
    }
    roundDepths_.clear();
    if (bodies.roundCount == 0) return;
    roundDepths_.reset(manifolds_.size());
    workers.forEach(manifolds_.size(), [&](std::size_t s) {
        roundDepths_.add(s, bodies[slotBodies_[s].a], bodies[slotBodies_[s].b], contacts, sources_[s], manifolds_[s].normal);
    });
    roundDepths_.finish();
}

// addSolverManifold writes every field of a solver manifold and of its first `count`
// points but the Jacobians (SolverManifold::direction, SolverRow's lanes and masses, the
// couplings) and the twist radius, which prepareSolver makes for every manifold whose
// Jacobians do not still hold (then the normal and tangents are also kept,
// jacobian_stamp.h); points past `count` keep whatever they held, as nothing reads them.
// A field added to either struct must be reset there too.
static_assert(sizeof(SolverPoint) == 256 && sizeof(SolverManifold) == 2304,
              "a solver manifold or point field was added or removed: reset it in addSolverManifold");

void ConstraintSolver::addSolverManifold(const WorldSettings &settings, const BodyStore &bodies,
                                         ContactManager &contacts, const PreSolve &preSolve, std::uint64_t stepCount,
                                         real warmScale, std::uint32_t keyIndex, std::size_t slot) {
    const ManifoldKey &key = keys_[keyIndex];
    const PairState &pair = contacts.pairs[key.manifold.pair];
    ManifoldState &m = contacts.manifold(key.manifold);
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const bool preSolved = preSolve.ran();
    const real friction = preSolved ? preSolve.override(keyIndex).friction
                                    : std::sqrt(a.material.friction * b.material.friction);
    // The slot holds an earlier step's manifold (or a value-initialised one). Resetting
    // all ~2.3 KB of it every step cost more than the rest of this function, and most of
    // it is the Jacobians, which prepareSolver writes anyway unless they still hold.
    SolverManifold &sm = manifolds_[slot];
    JacobianStamp &stamp = stamps_[slot];
    stamp.kept = jacobiansHold(settings.debug.manifoldReuseTolerance, bodies, stamp, pair, m);
    if (stamp.kept) {
        // The manifold's points come in the order of their depths (refreshFromAnchors):
        // the solve order follows them, and the rows stay where they were made.
        for (int i = 0; i < m.count; ++i) sm.order[i] = stamp.rowOf[m.points[i].id];
    } else {
        // The normal and tangents stay those the Jacobians were made with.
        sm.normal = m.normal;
        tangentBasis(sm.normal, sm.tangent[0], sm.tangent[1]);
        stamp.anchorsId = m.anchorsId;
        stampBody(stamp.body[0], bodies[pair.a]);
        stampBody(stamp.body[1], bodies[pair.b]);
        stamp.carrier.reset();
        for (int i = 0; i < m.count; ++i) {
            sm.order[i] = static_cast<signed char>(i);
            stamp.rowOf[m.points[i].id] = static_cast<signed char>(i);
        }
    }
    for (int i = m.count; i < kMaxManifoldPoints; ++i) sm.order[i] = static_cast<signed char>(i);
    m.solverSlot = static_cast<std::uint32_t>(slot);
    m.solverStep = stepCount;
    sm.a = a.simulated || a.moving ? a.solverIndex : 0;
    sm.b = b.simulated || b.moving ? b.solverIndex : 0;
    sm.friction = friction;
    sm.restitution = preSolved ? preSolve.override(keyIndex).restitution
                               : std::max(a.material.restitution, b.material.restitution);
    // The surfaces do not slide while vB + sB = vA + sA: the bodies' relative velocity
    // vB - vA is driven towards sA - sB, minus B's surface velocity relative to A's.
    const Vector3 surface = preSolved ? preSolve.override(keyIndex).surfaceVelocity : Vector3::Zero();
    sm.frictionRow[0].target = -surface.dot(sm.tangent[0]);
    sm.frictionRow[1].target = -surface.dot(sm.tangent[1]);
    sm.carrier = Carrier::None;
    sm.count = m.count;
    const bool warm = settings.debug.warmStarting;
    const real scale = warmScale;  // stored per default sub-step (step_plan.h)
    sm.frictionRow[0].impulse = warm ? m.frictionImpulse.dot(sm.tangent[0]) * scale : 0;
    sm.frictionRow[1].impulse = warm ? m.frictionImpulse.dot(sm.tangent[1]) * scale : 0;
    sm.twist.impulse = warm ? m.twistImpulse * scale : 0;
    for (int i = 0; i < m.count; ++i) {
        const PersistentPoint &src = m.points[i];
        SolverPoint &dst = sm.points[sm.order[i]];
        dst.localA = src.localA;
        dst.localB = src.localB;
        dst.normal.impulse = warm ? src.normalImpulse * scale : 0;
        dst.velocityBias = 0;
        dst.depth = src.depth;
        dst.approachSpeed = 0;
        dst.maxNormalImpulse = 0;
    }
    sources_[slot] = key.manifold;
    slotBodies_[slot] = {pair.a, pair.b};
}

// Whether the Jacobians in a slot, made at an earlier step (jacobian_stamp.h), hold for
// manifold `m` of `pair`: the same anchors (in any order, and so the same bodies), the
// bodies in the same roles, neither moved more than the manifold-reuse tolerance since.
bool ConstraintSolver::jacobiansHold(real tolerance, const BodyStore &bodies, const JacobianStamp &stamp,
                                     const PairState &pair, const ManifoldState &m) const {
    return tolerance > 0 && m.anchorsId != 0 && stamp.anchorsId == m.anchorsId &&
           stillStamped(stamp.body[0], bodies[pair.a], tolerance) &&
           stillStamped(stamp.body[1], bodies[pair.b], tolerance);
}

// Each manifold goes back to the slot it had last step when it can, so that the slot's
// Jacobians may be kept (jacobian_stamp.h); the others take the free slots in solve
// order. solveOrder_ lists the slots in solve order.
void ConstraintSolver::assignSlots(const PairCache &pairs, Workers &workers, std::uint64_t stepCount) {
    const std::size_t n = keys_.size();
    // Each manifold's slot of last step is read on several threads (the reads miss the
    // cache), then claimed in solve order: the first to claim a slot keeps it.
    solveOrder_.resize(n);
    workers.forEach(n, [&](std::size_t k) {
        const ManifoldRef &ref = keys_[k].manifold;
        const ManifoldState &m = pairs[ref.pair].manifolds[ref.index];
        const bool kept = m.solvedInStepBefore(stepCount) && m.solverSlot < n;
        solveOrder_[k] = kept ? static_cast<int>(m.solverSlot) : -1;
    });
    slotTaken_.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
        const int slot = solveOrder_[k];
        if (slot < 0) continue;
        if (slotTaken_[slot]) {
            solveOrder_[k] = -1;
            continue;
        }
        slotTaken_[slot] = 1;
    }
    std::size_t free = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (solveOrder_[k] >= 0) continue;
        while (slotTaken_[free]) ++free;
        solveOrder_[k] = static_cast<int>(free);
        slotTaken_[free] = 1;
    }
    keyOfSlot_.resize(n);
    heights_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        keyOfSlot_[solveOrder_[k]] = static_cast<std::uint32_t>(k);
        heights_[solveOrder_[k]] = keys_[k].height;
    }
}

void ConstraintSolver::prepare(const StepContext &context, const BodyStore &bodies, StepStats &stats) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    const real h = context.h;
    prepareBodies(bodies, workers, h);
    if (manifolds_.empty()) return;  // nothing below is read without contacts
    orderManifolds(settings, bodies, workers);
    prepareManifolds(settings, bodies, workers, context.plan.substeps, stats, h);
    prepareResistanceAndShares(settings, bodies, workers, stats);
}

// The solver bodies: each simulated body's velocities, inverse mass and inertia at the
// step's start; moving kinematic bodies as immovable entries that keep their velocity.
void ConstraintSolver::prepareBodies(const BodyStore &bodies, Workers &workers, real h) {
    const std::size_t n = bodies.simulated.size();
    bodies_.resize(n + 1 + bodies.moving.size());
    bodies_[0] = SolverBody();
    predictedV_.resize(n);
    predictedW_.resize(n);
    linearFactor_.resize(n);
    angularFactor_.resize(n);
    positions_.resize(bodies_.size());
    stepImpulse_.assign(manifolds_.size(), 0);
    resistance_.clear();
    workers.forEach(n, [&](std::size_t k) {
        const BodyRecord &r = bodies[bodies.simulated[k]];
        const RigidBody &body = r.body;
        SolverBody &sb = bodies_[k + 1];
        sb = SolverBody();
        setLanes(sb.v, body.getVelocity());
        setLanes(sb.w, body.getRotation());
        sb.invMass = body.getInverseMass();
        sb.invInertia = body.getInverseInertiaTensorWorld();
        if (r.locked.any()) lockSolverBody(r.locked, sb);
        body.getDampingFactors(h, &linearFactor_[k], &angularFactor_[k]);
        positions_[k + 1] = body.getPosition();
    });
    // Moving kinematic bodies: immovable entries that keep their velocity.
    for (std::size_t k = 0; k < bodies.moving.size(); ++k) {
        const RigidBody &body = bodies[bodies.moving[k]].body;
        SolverBody &sb = bodies_[n + 1 + k];
        sb = SolverBody();
        setLanes(sb.v, body.getVelocity());
        setLanes(sb.w, body.getRotation());
        positions_[n + 1 + k] = body.getPosition();
    }
}

// The velocity passes' partition between threads and the carrier pass's order.
void ConstraintSolver::orderManifolds(const WorldSettings &settings, const BodyStore &bodies, Workers &workers) {
    const std::size_t n = bodies.simulated.size();
    // The split reads the manifolds' bodies, the carriers their normals, and writes only
    // the carriers: the two run at once.
    const bool carriers = settings.debug.carrierPass;
    workers.forEachTask(carriers ? 2 : 1, [&](int task) {
        if (task == 0) {
            partitionManifolds(manifolds_, heights_, solveOrder_, positions_, workers.parallel(),
                                          partitionScratch_, partition_);
        } else {
            assignCarriers(static_cast<int>(bodies_.size()), static_cast<int>(n + 1), -settings.gravity, manifolds_,
                                  solveOrder_, carrierScratch_, carrierRuns_);
        }
    });
    if (carriers) {
        const bool shared = workers.parallel() && partition_.split;
        buildCarrierThreads(carrierRuns_, manifolds_, shared ? &partitionScratch_.side : nullptr,
                                  static_cast<int>(bodies_.size()), carrierThreads_);
    }
}

void ConstraintSolver::prepareManifolds(const WorldSettings &settings, const BodyStore &bodies, Workers &workers,
                                        int substeps, StepStats &stats, real h) {
    const bool carriers = settings.debug.carrierPass;
    // Jacobians and effective masses are made once per step, at the step's poses, unless
    // the slot's still hold (jacobian_stamp.h).
    // The counters are summed chunk by chunk, then in the chunks' order.
    chunkCounts_.resize(Workers::chunksOf(manifolds_.size()));
    workers.forEachChunk(manifolds_.size(), [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkCount &count = chunkCounts_[chunk];
        count = ChunkCount();
        for (std::size_t s = begin; s < end; ++s) {
            prepareManifold(bodies, s, h, h * substeps, settings.restitutionThreshold);
            JacobianStamp &stamp = stamps_[s];
            const SolverManifold &m = manifolds_[s];
            if (carriers && stamp.carrier != m.carrier) {
                prepareCarriedMasses(bodies_, manifolds_[s]);
                stamp.carrier = m.carrier;
            }
            if (!stamp.kept) ++count.jacobians;
            if (m.friction > 0) count.frictionRows += m.twistRadius > 0 ? 3 : 2;  // the patch: two tangents, a twist
            if (m.restitution == 0) continue;
            for (int i = 0; i < m.count; ++i)
                if (m.points[i].approachSpeed < -settings.restitutionThreshold) ++count.restitution;
        }
    });
    for (const ChunkCount &count : chunkCounts_) {
        stats.jacobiansMade += count.jacobians;
        stats.frictionRows += count.frictionRows;
        stats.restitutionContacts += count.restitution;
    }
}

// The rolling and spinning resistance rows, in solve order, and how two threads share
// them and the manifolds without a carrier.
void ConstraintSolver::prepareResistanceAndShares(const WorldSettings &settings, const BodyStore &bodies,
                                                  Workers &workers, StepStats &stats) {
    const bool carriers = settings.debug.carrierPass;
    const auto lengths = [&](int s) {
        const Material &ma = bodies[slotBodies_[s].a].material;
        const Material &mb = bodies[slotBodies_[s].b].material;
        return std::pair(std::max(ma.rollingFriction, mb.rollingFriction),
                         std::max(ma.spinningFriction, mb.spinningFriction));
    };
    // Which manifolds need rows and their rows are made on the threads, one row each in
    // solve order; the rows whose masses are all zero then go. The list is emptied first,
    // and lets its old room go before it takes the new (makeRoom).
    resistanceLengths_.resize(solveOrder_.size());
    workers.forEach(solveOrder_.size(), [&](std::size_t k) {
        const int s = solveOrder_[k];
        const auto [rolling, spinning] = lengths(s);
        resistanceLengths_[k] = needsResistance(manifolds_[s], rolling, spinning) ? std::pair(rolling, spinning)
                                                                                   : std::pair(real(0), real(0));
    });
    resistancePlaces_.clear();
    for (std::size_t k = 0; k < solveOrder_.size(); ++k)
        if (resistanceLengths_[k].first > 0 || resistanceLengths_[k].second > 0)
            resistancePlaces_.push_back(static_cast<int>(k));
    makeRoom(resistance_, resistancePlaces_.size());
    resistance_.resize(resistancePlaces_.size());
    workers.forEach(resistancePlaces_.size(), [&](std::size_t j) {
        const int k = resistancePlaces_[j];
        const auto [rolling, spinning] = resistanceLengths_[k];
        const int s = solveOrder_[k];
        if (!makeResistanceRows(bodies_, manifolds_[s], s, rolling, spinning, resistance_[j])) resistance_[j].slot = -1;
    });
    resistance_.erase(std::remove_if(resistance_.begin(), resistance_.end(),
                                     [](const ResistanceRow &row) { return row.slot < 0; }),
                      resistance_.end());
    for (const ResistanceRow &row : resistance_)
        stats.resistanceRows += (row.mass[0] > 0) + (row.mass[1] > 0) + (row.mass[2] > 0);
    // Two threads share the resistance rows and the manifolds without a carrier by the
    // partition's halves, with the numbers of one (threads/ordered_shares.h).
    orderedShares_ = workers.parallel() && partition_.split;
    if (!orderedShares_) return;
    const int bodyCount = static_cast<int>(bodies_.size());
    const std::vector<signed char> &side = partitionScratch_.side;
    buildOrderedShares(
        resistance_.size(), [&](std::size_t k) { return resistance_[k].a; },
        [&](std::size_t k) { return resistance_[k].b; }, side, bodyCount, resistanceShares_);
    if (!carriers) return;
    const std::vector<int> &uncarried = carrierRuns_.uncarried;
    buildOrderedShares(
        uncarried.size(), [&](std::size_t k) { return manifolds_[uncarried[k]].a; },
        [&](std::size_t k) { return manifolds_[uncarried[k]].b; }, side, bodyCount, uncarriedShares_);
}

void ConstraintSolver::prepareManifold(const BodyStore &bodies, std::size_t s, real h, real dt,
                                       real restitutionThreshold) {
    SolverManifold &m = manifolds_[s];
    const SlotBodies records = slotBodies_[s];
    const RigidBody &a = bodies[records.a].body;
    const RigidBody &b = bodies[records.b].body;
    const SolverBody &sa = bodies_[m.a];
    const SolverBody &sb = bodies_[m.b];
    if (!stamps_[s].kept) {
        const int simulated = static_cast<int>(bodies.simulated.size());
        LeverTurns turns;
        if (m.a > simulated) turns.any |= midStepTurn(a, dt, turns.a);
        if (m.b > simulated) turns.any |= midStepTurn(b, dt, turns.b);
        prepareJacobians(sa, sb, a, b, m, turns);
    }
    // The first sub-step's targets are set here, while the points are in the cache (later
    // sub-steps set theirs at their depths: ConstraintSolver::solveVelocities).
    const real inverseH = 1 / h;
    for (int i = 0; i < m.count; ++i) {
        SolverPoint &p = m.points[i];
        p.maxNormalImpulse = 0;
        // The normal velocity when the step began, measured only for restitution.
        p.approachSpeed = m.restitution == 0 ? 0 : normalVelocity(sa, sb, m, p);
        p.velocityBias = velocityBias(m, p, h, inverseH, restitutionThreshold, true);
    }
}

}  // namespace cyclone::detail
