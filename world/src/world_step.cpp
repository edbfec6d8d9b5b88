// World::step, stage by stage: forces -> broadphase -> narrowphase -> manifolds ->
// islands -> per sub-step (forces, solve, integrate) -> continuous collision -> sleep.
#include <chrono>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "pose_change.h"
#include "validation.h"
#include "world_impl.h"

namespace cyclone {

using detail::Tree;

namespace {

class StageTimer {
public:
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        return ms;
    }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// How far apart (along or across the normal) a contact's anchors may drift once FCL no
// longer reports the pair before the contact is dropped, m.
constexpr real kContactKeepDistance = 0.002;

// B's pose seen from A (the manifold-reuse test compares it with the last narrowphase's):
// A's rotation transposed is its inverse.
detail::RelativePose relativePose(const RigidBody &a, const RigidBody &b) {
    return {a.getTransform().linear().transpose() * (b.getPosition() - a.getPosition()),
            a.getOrientation().conjugate() * b.getOrientation()};
}

int findRoot(std::vector<int> &parent, int i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

}  // namespace

void World::Impl::step(real dt) {
    StageTimer timer;
    stats = StepStats();
    ++stepCount;
    openStepEvents();

    applyForces(dt);
    stats.ms.forces = timer.lap();
    updateBroadphase();
    stats.ms.broadphase = timer.lap();
    runNarrowphase();
    stats.ms.narrowphase = timer.lap();
    detectContactEvents();
    stats.ms.events = timer.lap();
    buildManifolds(dt);
    stats.ms.manifolds = timer.lap();
    buildIslands();
    stats.ms.islands = timer.lap();

    const real h = dt / settings.substeps;
    matchThreads();
    prepareSolver(h);
    stats.ms.solveParts.setup = timer.lap();
    stats.ms.solve += stats.ms.solveParts.setup;
    for (int substep = 0; substep < settings.substeps; ++substep) {
        substepForces(h, substep == 0);
        stats.ms.forces += timer.lap();
        const double supportBefore = stats.ms.solveParts.support;  // solve() times its support pass
        solve(h, substep == 0);
        const double solved = timer.lap();
        stats.ms.solve += solved;
        stats.ms.solveParts.velocity += solved - (stats.ms.solveParts.support - supportBefore);
        integrate(h);
        stats.ms.integrate += timer.lap();
        recoverPenetration(h);  // times itself into solveParts.position
        stats.ms.solve += timer.lap();
    }
    restitution();
    storeImpulses();
    stats.ms.solve += timer.lap();

    sweepContinuous();
    stats.ms.ccd = timer.lap();

    updateSleep();
    stats.ms.sleep = timer.lap();
    closeStepEvents();

    stats.integratedBodies = static_cast<int>(simulatedBodies.size());
    stats.bodies = static_cast<int>(order.size());
    stats.awakeBodies = static_cast<int>(awake.size());
    stats.nonFiniteBodies = quarantinedBodies;
    stats.ms.total = stats.ms.forces + stats.ms.broadphase + stats.ms.narrowphase + stats.ms.events +
                     stats.ms.manifolds + stats.ms.islands + stats.ms.solve + stats.ms.integrate + stats.ms.ccd +
                     stats.ms.sleep;
}

// --- forces -------------------------------------------------------------------------------

void World::Impl::applyForces(real dt) {
    // Bodies are simulated in the order they were added, whatever the order they woke in.
    if (!awakeSorted) {
        std::sort(awake.begin(), awake.end(), [&](std::uint32_t x, std::uint32_t y) { return bodies[x].rank < bodies[y].rank; });
        for (std::size_t k = 0; k < awake.size(); ++k) bodies[awake[k]].awakeSlot = static_cast<int>(k);
        awakeSorted = true;
    }
    // `simulated` of the bodies simulated last step; the others are already false.
    for (std::uint32_t index : simulatedBodies) bodies[index].simulated = false;
    simulatedBodies.clear();
    for (std::size_t k = 0; k < awake.size(); ++k) {
        const std::uint32_t index = awake[k];
        BodyRecord &r = bodies[index];
        r.simulated = true;
        // A force whose velocity overflows within the step (1e300 N on 1 kg) would reach
        // other bodies through springs before the solver's check: isolate the body now.
        const RigidBody &body = r.body;
        const Vector3 v = body.getVelocity() +
                          dt * (body.getAcceleration() + body.getInverseMass() * body.getAccumulatedForce());
        const Vector3 w = body.getRotation() + dt * (body.getInverseInertiaTensorWorld() * body.getAccumulatedTorque());
        if (!std::isfinite(v.squaredNorm() + w.squaredNorm())) {
            quarantine(index);  // takes it out of `awake`: slot k now holds another body
            --k;
            continue;
        }
        r.solverIndex = static_cast<int>(simulatedBodies.size()) + 1;
        simulatedBodies.push_back(index);
    }
    for (SpringRecord &s : springs) {
        if (!s.alive) continue;
        BodyRecord &a = bodies[s.settings.a.index];
        BodyRecord *b = s.settings.b ? &bodies[s.settings.b->index] : nullptr;
        if (!a.simulated && !(b && b->simulated)) continue;
        // An isolated (non-finite) end would carry its state to the other: the spring is off.
        if (a.quarantined || (b && b->quarantined)) continue;
        // A spring joins its bodies: one awake end wakes the other.
        if (!a.simulated) wake(s.settings.a.index);
        if (b && !b->simulated) wake(s.settings.b->index);
        ++stats.springs;
    }
    if (settings.substeps > 1) {
        savedForces.resize(simulatedBodies.size());
        savedTorques.resize(simulatedBodies.size());
        for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
            savedForces[k] = bodies[simulatedBodies[k]].body.getAccumulatedForce();
            savedTorques[k] = bodies[simulatedBodies[k]].body.getAccumulatedTorque();
        }
    }
}

// Forces of one sub-step: the user's forces again after the first sub-step (integrate
// cleared them), then the springs at the state this sub-step starts from. Held for a
// whole step, an explicit spring force would gain energy at any stiffness once there are
// sub-steps (the positions would move under a force that lags them).
void World::Impl::substepForces(real h, bool firstSubstep) {
    if (!firstSubstep) {
        for (std::size_t k = 0; k < simulatedBodies.size(); ++k) {
            BodyRecord &r = bodies[simulatedBodies[k]];
            if (r.quarantined) continue;
            r.body.addForce(savedForces[k]);
            r.body.addTorque(savedTorques[k]);
        }
    }
    if (stats.springs == 0) return;
    // The explicit forces first: the implicit ones are solved with them in place.
    const int implicitCount = chooseSpringForces(h);
    addExplicitSpringForces();
    if (implicitCount > 0) addImplicitSpringForces(h);
}

// --- broadphase ---------------------------------------------------------------------------

void World::Impl::updateBroadphase() {
    movedObjects.clear();
    for (std::uint32_t index : simulatedBodies) {
        BodyRecord &r = bodies[index];
        if (r.object && r.object->place(r.body.getTransform(), detail::kBroadphaseMargin))
            movedObjects.push_back(r.object.get());
    }
    broadphase.refitAwake(movedObjects);
    candidates.clear();
    broadphase.findPairs(candidates);

    // Planes stay out of the trees: test each awake body's AABB against each plane.
    // The half-space is the compiled one (unit normal, offset along it, as FCL has it),
    // placed by the plane body's pose as the narrowphase places it.
    for (std::uint32_t plane : planes) {
        const detail::CollisionShape &p = *bodies[plane].shape;
        const Matrix4 pose = bodies[plane].body.getTransform();
        const Vector3 n = pose.linear() * p.planeNormal();
        const real offset = p.planeOffset() + n.dot(pose.translation());
        for (std::uint32_t index : simulatedBodies) {
            const BodyRecord &r = bodies[index];
            if (!r.object) continue;
            const fcl::AABBd &box = r.object->getAABB();
            const Vector3 centre = detail::boxCentre(box);
            const Vector3 half = 0.5 * (box.max_ - box.min_);
            const real lowest = n.dot(centre) - n.cwiseAbs().dot(half);
            if (lowest <= offset + settings.speculativeDistance) candidates.push_back({plane, index});
        }
    }
    stats.broadphasePairs = static_cast<int>(candidates.size());
}

// --- narrowphase --------------------------------------------------------------------------

void World::Impl::runNarrowphase() {
    // The step's pairs, each once, in the broadphase's order.
    stepPairs.clear();
    // The broadphase lists a settled scene's pairs in the same order step after step:
    // the slot each candidate had last step is checked first, saving most table look-ups.
    candidateSlots.resize(candidates.size(), kNoSlot);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        const detail::CandidatePair &c = candidates[k];
        if (bodies[c.a].isStatic && bodies[c.b].isStatic) continue;
        std::uint32_t p = candidateSlots[k];
        if (!pairs.holds(p, c.a, c.b)) {
            bool created = false;
            p = findOrAddPair(c.a, c.b, created);
            candidateSlots[k] = p;
        }
        detail::PairState &pair = pairs[p];
        if (pair.lastSeen == stepCount) continue;  // reported twice
        pair.lastSeen = stepCount;
        eventSlots.push_back(p);
        stepPairs.push_back(p);
    }

    // Pairs that hardly moved keep their manifolds, each on its own (in chunks at once);
    // the others go through FCL, one after another.
    pairReused.assign(stepPairs.size(), 0);
    forEachInChunks(stepPairs.size(), [&](std::size_t k) { pairReused[k] = reuseManifolds(stepPairs[k]); });
    for (std::size_t k = 0; k < stepPairs.size(); ++k) {
        if (pairReused[k]) ++stats.pairsReused;
        else testPair(stepPairs[k]);
    }

    touchingPairs.clear();
    for (std::uint32_t p : stepPairs) {
        const detail::PairState &pair = pairs[p];
        if (!pair.touching()) continue;
        touchingPairs.push_back(p);
        // A new contact with an awake body wakes a sleeping one (from the next step on).
        const BodyRecord &a = bodies[pair.a];
        const BodyRecord &b = bodies[pair.b];
        if (a.simulated && !b.isStatic && !b.simulated) wake(pair.b);
        if (b.simulated && !a.isStatic && !a.simulated) wake(pair.a);
    }

    // Pairs with an awake member that the broadphase no longer reports have separated
    // (walked body by body: sleeping bodies' pairs cost nothing).
    for (std::uint32_t index : simulatedBodies) {
        std::vector<std::uint32_t> &list = bodies[index].pairs;
        for (std::size_t k = list.size(); k-- > 0;) {
            const std::uint32_t p = list[k];
            if (pairs[p].lastSeen != stepCount) removePair(p);
        }
    }
}

// Only a touching pair is reused: one with no manifold may come into contact within the
// tolerance, and FCL does not see contacts that are apart by a hair.
bool World::Impl::reuseManifolds(std::uint32_t p) {
    detail::PairState &pair = pairs[p];
    if (!pair.tested || !pair.touching() || settings.manifoldReuseTolerance <= 0) return false;
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const Matrix4 poseA = a.body.getTransform();
    const Matrix4 poseB = b.body.getTransform();
    const detail::RelativePose relative = relativePose(a.body, b.body);
    const real shift = (relative.position - pair.relativePose.position).norm();
    const Quaternion turn = relative.orientation * pair.relativePose.orientation.conjugate();
    const real radius = std::max(a.boundingRadius, b.boundingRadius);
    if (!detail::movedLess(shift, turn, radius, settings.manifoldReuseTolerance)) return false;
    for (detail::ManifoldState &m : pair.manifolds) detail::refreshFromAnchors(m, poseA, poseB);
    return true;
}

void World::Impl::testPair(std::uint32_t p) {
    detail::PairState &pair = pairs[p];
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const Matrix4 poseA = a.body.getTransform();
    const Matrix4 poseB = b.body.getTransform();
    fresh.clear();
    const int n = detail::collide(*a.shape, poseA, *b.shape, poseB, {settings.speculativeDistance}, fresh);
    ++stats.pairsTested;
    pair.tested = true;
    pair.relativePose = relativePose(a.body, b.body);
    const real size = std::min(a.isPlane ? b.boundingRadius : a.boundingRadius,
                               b.isPlane ? a.boundingRadius : b.boundingRadius);
    const real matchDistance = std::clamp(0.1 * size, real(0.001), real(0.05));
    if (n == 0 && !pair.manifolds.empty()) {
        // FCL sees only overlap: a resting contact that opens by a hair would be lost
        // with its warm-start impulses and found again a step later. Keep its points as
        // speculative contacts while they stay close.
        detail::keepNearPoints(pair.manifolds, poseA, poseB, kContactKeepDistance, anchorSettings);
        return;
    }
    // At most four manifolds per pair (a mesh may report more normals).
    const int kept = std::min(n, 4);
    pair.manifolds.resize(kept);
    for (int k = 0; k < kept; ++k)
        detail::mergeManifold(pair.manifolds[k], fresh[k], poseA, poseB, matchDistance, ++anchorSettings);
}

// --- manifolds ----------------------------------------------------------------------------

void World::Impl::buildManifolds(real) {
    // The solve order is settled on small keys first and the solver manifolds are then
    // built in that order: sorting the built manifolds (~2 KB each) meant copying all of
    // them every step.
    manifoldKeys.clear();
    const Vector3 up = -settings.gravity;
    for (std::uint32_t p : touchingPairs) {
        const detail::PairState &pair = pairs[p];
        const BodyRecord &a = bodies[pair.a];
        const BodyRecord &b = bodies[pair.b];
        if (!a.simulated && !b.simulated) continue;
        const real height = contactHeight(a, b, up);
        for (std::size_t k = 0; k < pair.manifolds.size(); ++k) {
            if (pair.manifolds[k].count == 0) continue;
            manifoldKeys.push_back({height, (p << 2) | static_cast<std::uint32_t>(k)});
        }
    }
    orderManifolds();
    assignSlots();
    // Last step's manifolds are overwritten in place (see addSolverManifold); only new
    // slots are value-initialised.
    solverManifolds.resize(manifoldKeys.size());
    solverSource.resize(manifoldKeys.size());
    solverRecords.resize(manifoldKeys.size());
    jacobianStamps.resize(manifoldKeys.size());
    // Slot by slot: the slots are written in memory order.
    forEachInChunks(manifoldKeys.size(), [&](std::size_t s) { addSolverManifold(manifoldKeys[keyOfSlot[s]], s); });
    for (const detail::SolverManifold &m : solverManifolds) {
        ++stats.manifolds;
        stats.contacts += m.count;
        for (int i = 0; i < m.count; ++i) stats.maxPenetration = std::max(stats.maxPenetration, m.points[i].depth);
    }
}

// addSolverManifold writes every field of a solver manifold and of its first `count`
// points but the Jacobians (SolverManifold::direction, SolverRow's lanes and masses, the
// couplings) and the twist radius, which prepareSolver makes for every manifold whose
// Jacobians do not still hold (then the normal and tangents are also kept,
// jacobian_stamp.h); points past `count` keep whatever they held, as nothing reads them.
// A field added to either struct must be reset there too.
static_assert(sizeof(detail::SolverPoint) == 256 && sizeof(detail::SolverManifold) == 2304,
              "a solver manifold or point field was added or removed: reset it in addSolverManifold");

void World::Impl::addSolverManifold(const ManifoldKey &key, std::size_t slot) {
    detail::PairState &pair = pairs[key.source >> 2];
    detail::ManifoldState &m = manifoldOf(key);
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const real friction = std::sqrt(a.material.friction * b.material.friction);
    // The slot holds an earlier step's manifold (or a value-initialised one). Resetting
    // all ~2.3 KB of it every step cost more than the rest of this function, and most of
    // it is the Jacobians, which prepareSolver writes anyway unless they still hold.
    detail::SolverManifold &sm = solverManifolds[slot];
    detail::JacobianStamp &stamp = jacobianStamps[slot];
    stamp.kept = jacobiansHold(stamp, pair, m);
    if (stamp.kept) {
        // The manifold's points come in the order of their depths (refreshFromAnchors):
        // the solve order follows them, and the rows stay where they were made.
        for (int i = 0; i < m.count; ++i) sm.order[i] = stamp.rowOf[m.points[i].id];
    } else {
        // The normal and tangents stay those the Jacobians were made with.
        sm.normal = m.normal;
        detail::tangentBasis(sm.normal, sm.tangent[0], sm.tangent[1]);
        stamp.anchors = m.anchors;
        stampBody(stamp.body[0], pair.a);
        stampBody(stamp.body[1], pair.b);
        stamp.support = detail::kSupportNotMade;
        for (int i = 0; i < m.count; ++i) {
            sm.order[i] = static_cast<signed char>(i);
            stamp.rowOf[m.points[i].id] = static_cast<signed char>(i);
        }
    }
    for (int i = m.count; i < detail::kMaxManifoldPoints; ++i) sm.order[i] = static_cast<signed char>(i);
    m.solverSlot = static_cast<std::uint32_t>(slot);
    m.solverStep = stepCount;
    sm.a = a.simulated ? a.solverIndex : 0;
    sm.b = b.simulated ? b.solverIndex : 0;
    sm.friction = friction;
    sm.restitution = 0;
    sm.touchesStatic = false;
    sm.support = detail::kNoSupport;
    sm.count = m.count;
    const bool warm = settings.warmStarting;
    sm.frictionRow[0].impulse = warm ? m.frictionImpulse.dot(sm.tangent[0]) : 0;
    sm.frictionRow[1].impulse = warm ? m.frictionImpulse.dot(sm.tangent[1]) : 0;
    sm.twist.impulse = warm ? m.twistImpulse : 0;
    for (int i = 0; i < m.count; ++i) {
        const detail::PersistentPoint &src = m.points[i];
        detail::SolverPoint &dst = sm.points[sm.order[i]];
        dst.localA = src.localA;
        dst.localB = src.localB;
        dst.normal.impulse = warm ? src.normalImpulse : 0;
        dst.velocityBias = 0;
        dst.depth = src.depth;
        dst.approachSpeed = 0;
        dst.maxNormalImpulse = 0;
    }
    solverSource[slot] = key.source;
    solverRecords[slot] = {pair.a, pair.b};
}

// Whether the Jacobians in a slot, made at an earlier step (jacobian_stamp.h), hold for
// manifold `m` of `pair`: the same anchors (in any order, and so the same bodies), the
// bodies in the same roles, neither moved more than the manifold-reuse tolerance since.
bool World::Impl::jacobiansHold(const detail::JacobianStamp &stamp, const detail::PairState &pair,
                                const detail::ManifoldState &m) const {
    return settings.manifoldReuseTolerance > 0 && m.anchors != 0 && stamp.anchors == m.anchors &&
           bodyStillStamped(stamp.body[0], pair.a) && bodyStillStamped(stamp.body[1], pair.b);
}

bool World::Impl::bodyStillStamped(const detail::StampedBody &stamped, std::uint32_t index) const {
    const BodyRecord &r = bodies[index];
    if (stamped.movable != r.simulated) return false;
    if (r.isPlane) return true;  // a plane cannot be moved (World::setPosition refuses it)
    const real shift = (r.body.getPosition() - stamped.position).norm();
    return detail::movedLess(shift, r.body.getOrientation() * stamped.orientation.conjugate(), r.boundingRadius,
                             settings.manifoldReuseTolerance);
}

void World::Impl::stampBody(detail::StampedBody &stamped, std::uint32_t index) const {
    const BodyRecord &r = bodies[index];
    stamped.movable = r.simulated;
    stamped.position = r.body.getPosition();
    stamped.orientation = r.body.getOrientation();
}

real World::Impl::contactHeight(const BodyRecord &a, const BodyRecord &b, const Vector3 &up) const {
    const real lowest = -std::numeric_limits<real>::infinity();
    const real ha = a.isStatic ? lowest : a.body.getPosition().dot(up);
    const real hb = b.isStatic ? lowest : b.body.getPosition().dot(up);
    return std::min(ha, hb);
}

// Each manifold goes back to the slot it had last step when it can, so that the slot's
// Jacobians may be kept (jacobian_stamp.h); the others take the free slots in solve
// order. solveOrder lists the slots in solve order.
void World::Impl::assignSlots() {
    const std::size_t n = manifoldKeys.size();
    solveOrder.assign(n, -1);
    slotTaken.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
        const detail::ManifoldState &m = manifoldOf(manifoldKeys[k]);
        if (m.solverStep + 1 != stepCount || m.solverSlot >= n || slotTaken[m.solverSlot]) continue;
        solveOrder[k] = static_cast<int>(m.solverSlot);
        slotTaken[m.solverSlot] = 1;
    }
    std::size_t free = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (solveOrder[k] >= 0) continue;
        while (slotTaken[free]) ++free;
        solveOrder[k] = static_cast<int>(free);
        slotTaken[free] = 1;
    }
    keyOfSlot.resize(n);
    solverHeights.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        keyOfSlot[solveOrder[k]] = static_cast<std::uint32_t>(k);
        solverHeights[solveOrder[k]] = manifoldKeys[k].height;
    }
}

void World::Impl::orderManifolds() {
    // Gauss-Seidel carries a stack's weight down in one pass when the contacts nearest
    // the ground come first; the order must not depend on the broadphase's. Equal heights
    // keep the order of the pair walk: the radix sort is stable. A comparison sort on
    // (height, place in the walk) mispredicted most of its branches here: a layer's
    // heights are equal but for rounding, so their order changes from step to step.
    detail::sortByHeight(manifoldKeys, manifoldKeysScratch);
}

// --- islands ------------------------------------------------------------------------------

void World::Impl::buildIslands() {
    const int n = static_cast<int>(simulatedBodies.size());
    islandParent.resize(n);
    std::iota(islandParent.begin(), islandParent.end(), 0);
    auto unite = [&](int x, int y) {
        x = findRoot(islandParent, x);
        y = findRoot(islandParent, y);
        if (x != y) islandParent[std::max(x, y)] = std::min(x, y);
    };
    for (const detail::SolverManifold &m : solverManifolds)
        if (m.a > 0 && m.b > 0) unite(m.a - 1, m.b - 1);
    for (const SpringRecord &s : springs) {
        if (!s.alive || !s.settings.b) continue;
        const BodyRecord &a = bodies[s.settings.a.index];
        const BodyRecord &b = bodies[s.settings.b->index];
        if (a.simulated && b.simulated) unite(a.solverIndex - 1, b.solverIndex - 1);
    }
    // Islands are numbered in the order of their first members. A parent never comes
    // after its child (unite keeps the smaller root), so in one walk each entry's parent
    // already holds its island, stored as ~island to tell it from a parent's index.
    int islands = 0;
    for (int k = 0; k < n; ++k) {
        const int up = islandParent[k];
        islandParent[k] = up == k ? ~islands++ : islandParent[up];
    }
    // Lay the members out island by island. islandStart is the cursor, which leaves each
    // island's entry at the next island's start: shifted back at the end.
    islandStart.assign(islands + 1, 0);
    for (int k = 0; k < n; ++k) {
        const int island = ~islandParent[k];
        bodies[simulatedBodies[k]].island = island;
        ++islandStart[island + 1];
    }
    for (int i = 0; i < islands; ++i) islandStart[i + 1] += islandStart[i];
    islandBodies.resize(n);
    for (int k = 0; k < n; ++k) islandBodies[islandStart[~islandParent[k]]++] = simulatedBodies[k];
    for (int i = islands - 1; i > 0; --i) islandStart[i] = islandStart[i - 1];
    islandStart[0] = 0;
    stats.islands = islands;
}

// --- sleep --------------------------------------------------------------------------------

void World::Impl::updateSleep() {
    if (!settings.sleep) return;
    const int islands = static_cast<int>(islandStart.size()) - 1;
    for (int i = 0; i < islands; ++i) {
        const int start = islandStart[i];
        const int end = islandStart[i + 1];
        bool still = true;
        for (int k = start; k < end && still; ++k) {
            const BodyRecord &r = bodies[islandBodies[k]];
            still = !r.quarantined && r.body.getAwake() && r.body.getCanSleep() &&
                    r.body.getMotion() < r.body.getSleepEpsilon();
        }
        if (still) sleepIsland(islandBodies.data() + start, end - start);
    }
}

void World::Impl::quarantine(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    if (!r.quarantined) ++quarantinedBodies;
    r.quarantined = true;
    r.simulated = false;
    updateAwakeList(index);
    setTree(index, Tree::None);
    removePairsOf(index);
}

std::uint32_t World::Impl::findOrAddPair(std::uint32_t i, std::uint32_t j, bool &created) {
    const std::uint32_t p = pairs.findOrAdd(i, j, created);
    if (created) {
        bodies[i].pairs.push_back(p);
        bodies[j].pairs.push_back(p);
    }
    return p;
}

void World::Impl::removePair(std::uint32_t p) {
    const detail::PairState &pair = pairs[p];
    for (std::uint32_t index : {pair.a, pair.b}) {
        std::vector<std::uint32_t> &list = bodies[index].pairs;
        const auto at = std::find(list.begin(), list.end(), p);
        if (at != list.end()) {
            *at = list.back();
            list.pop_back();
        }
    }
    pairs.remove(p);
    eventSlots.push_back(p);
}

void World::Impl::removePairsOf(std::uint32_t index) {
    while (!bodies[index].pairs.empty()) removePair(bodies[index].pairs.back());
}

}  // namespace cyclone
