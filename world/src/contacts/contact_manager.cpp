#include "contacts/contact_manager.h"

#include <algorithm>

#include "world/world_impl.h"

namespace cyclone::detail {
namespace {

// How far apart (along or across the normal) a contact's anchors may drift once the
// narrowphase no longer reports the pair before the contact is dropped, m.
constexpr real kContactKeepDistance = 0.002;

// B's pose seen from A (the manifold-reuse test compares it with the last narrowphase's):
// A's rotation transposed is its inverse.
RelativePose relativePose(const RigidBody &a, const RigidBody &b) {
    return {a.getTransform().linear().transpose() * (b.getPosition() - a.getPosition()),
            a.getOrientation().conjugate() * b.getOrientation()};
}

}  // namespace

void ContactManager::findCandidates(WorldState &world) {
    BodyStore &bodies = world.bodies;
    const WorldSettings &settings = world.settings;
    movedObjects_.clear();
    for (std::uint32_t index : bodies.simulated) {
        BodyRecord &r = bodies[index];
        if (r.object && r.object->place(r.body.getTransform(), kBroadphaseMargin))
            movedObjects_.push_back(r.object.get());
    }
    for (std::uint32_t index : bodies.moving) {
        BodyRecord &r = bodies[index];
        if (r.object && r.object->place(r.body.getTransform(), kBroadphaseMargin))
            movedObjects_.push_back(r.object.get());
    }
    world.broadphase.refitAwake(movedObjects_);
    candidates_.clear();

    // Planes stay out of the trees: test each awake body's AABB against each plane.
    // The half-space is the compiled one (unit normal, offset along it, as FCL has it),
    // placed by the plane body's pose as the narrowphase places it. They are found first,
    // so that the pair budget never drops a body's floor, and listed after the trees'.
    planeCandidates_.clear();
    for (std::uint32_t plane : bodies.planes) {
        const CollisionShape &p = *bodies[plane].shape;
        const Matrix4 pose = bodies[plane].body.getTransform();
        const Vector3 n = pose.linear() * p.planeNormal();
        const real offset = p.planeOffset() + n.dot(pose.translation());
        for (std::uint32_t index : bodies.simulated) {
            const BodyRecord &r = bodies[index];
            if (!r.object) continue;
            const fcl::AABBd &box = r.object->getAABB();
            const Vector3 centre = boxCentre(box);
            const Vector3 half = 0.5 * (box.max_ - box.min_);
            const real lowest = n.dot(centre) - n.cwiseAbs().dot(half);
            if (lowest <= offset + settings.speculativeDistance) planeCandidates_.push_back({plane, index});
        }
    }
    const std::size_t budget = static_cast<std::size_t>(settings.maxPairs);
    const std::size_t treeBudget = budget > planeCandidates_.size() ? budget - planeCandidates_.size() : 0;
    const bool complete = world.broadphase.findPairs(candidates_, treeBudget);
    candidates_.insert(candidates_.end(), planeCandidates_.begin(), planeCandidates_.end());
    if (candidates_.size() > budget) candidates_.resize(budget);  // more plane pairs than the budget
    if (!complete || planeCandidates_.size() > budget) world.stats.errors |= StepError::PairBudgetExceeded;
    world.stats.broadphasePairs = static_cast<int>(candidates_.size());
}

void ContactManager::updateContacts(WorldState &world) {
    BodyStore &bodies = world.bodies;
    const std::uint64_t stepCount = world.stepCount;
    // The step's pairs, each once, in the broadphase's order.
    stepPairs_.clear();
    // The broadphase lists a settled scene's pairs in the same order step after step:
    // the slot each candidate had last step is checked first, saving most table look-ups.
    candidateSlots_.resize(candidates_.size(), kNoSlot);
    for (std::size_t k = 0; k < candidates_.size(); ++k) {
        const CandidatePair &c = candidates_[k];
        if (bodies.filteredCount > 0 && !bodies.collide(c.a, c.b)) {
            ++world.stats.filteredPairs;
            continue;
        }
        if (bodies[c.a].immovable && bodies[c.b].immovable) {
            // A moving kinematic body with a static or kinematic one: neither can push.
            ++world.stats.immovablePairsSkipped;
            continue;
        }
        std::uint32_t p = candidateSlots_[k];
        if (!pairs.holds(p, c.a, c.b)) {
            bool created = false;
            p = findOrAddPair(bodies, c.a, c.b, created);
            candidateSlots_[k] = p;
        }
        PairState &pair = pairs[p];
        if (pair.lastSeen == stepCount) continue;  // reported twice
        pair.lastSeen = stepCount;
        eventSlots_.push_back(p);
        stepPairs_.push_back(p);
    }

    // Pairs that hardly moved keep their manifolds, each on its own (in chunks at once);
    // the others go through FCL, one after another.
    pairReused_.assign(stepPairs_.size(), 0);
    world.workers.forEach(stepPairs_.size(), [&](std::size_t k) { pairReused_[k] = reuseManifolds(world, stepPairs_[k]); });
    for (std::size_t k = 0; k < stepPairs_.size(); ++k) {
        if (pairReused_[k]) ++world.stats.pairsReused;
        else testPair(world, stepPairs_[k]);
    }

    touchingPairs.clear();
    for (std::uint32_t p : stepPairs_) {
        const PairState &pair = pairs[p];
        if (!pair.touching()) continue;
        touchingPairs.push_back(p);
        // A new contact with an awake or moving kinematic body wakes a sleeping one (from
        // the next step on).
        const BodyRecord &a = bodies[pair.a];
        const BodyRecord &b = bodies[pair.b];
        if ((a.simulated || a.moving) && !b.immovable && !b.simulated) world.wake(pair.b);
        if ((b.simulated || b.moving) && !a.immovable && !a.simulated) world.wake(pair.a);
    }

    // Pairs with an awake member that the broadphase no longer reports have separated
    // (walked body by body: sleeping bodies' pairs cost nothing).
    const auto dropUnseen = [&](std::uint32_t index) {
        std::vector<std::uint32_t> &list = bodies[index].pairs;
        for (std::size_t k = list.size(); k-- > 0;) {
            const std::uint32_t p = list[k];
            if (pairs[p].lastSeen != stepCount) removePair(bodies, p);
        }
    };
    for (std::uint32_t index : bodies.simulated) dropUnseen(index);
    for (std::uint32_t index : bodies.moving) dropUnseen(index);
}

// Only a touching pair is reused: one with no manifold may come into contact within the
// tolerance, and FCL does not see contacts that are apart by a hair.
bool ContactManager::reuseManifolds(const WorldState &world, std::uint32_t p) {
    const BodyStore &bodies = world.bodies;
    const WorldSettings &settings = world.settings;
    PairState &pair = pairs[p];
    if (!pair.tested || !pair.touching() || settings.manifoldReuseTolerance <= 0) return false;
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const Matrix4 poseA = a.body.getTransform();
    const Matrix4 poseB = b.body.getTransform();
    const RelativePose relative = relativePose(a.body, b.body);
    const real shift = (relative.position - pair.relativePose.position).norm();
    const Quaternion turn = relative.orientation * pair.relativePose.orientation.conjugate();
    const real radius = std::max(a.boundingRadius, b.boundingRadius);
    if (!movedLess(shift, turn, radius, settings.manifoldReuseTolerance)) return false;
    for (ManifoldState &m : pair.manifolds) refreshFromAnchors(m, poseA, poseB);
    return true;
}

void ContactManager::testPair(WorldState &world, std::uint32_t p) {
    const BodyStore &bodies = world.bodies;
    const WorldSettings &settings = world.settings;
    PairState &pair = pairs[p];
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const Matrix4 poseA = a.body.getTransform();
    const Matrix4 poseB = b.body.getTransform();
    fresh_.clear();
    const int n = collide(*a.shape, poseA, *b.shape, poseB, {settings.speculativeDistance}, fresh_);
    ++world.stats.pairsTested;
    pair.tested = true;
    pair.relativePose = relativePose(a.body, b.body);
    const real size = std::min(a.isPlane ? b.boundingRadius : a.boundingRadius,
                               b.isPlane ? a.boundingRadius : b.boundingRadius);
    const real matchDistance = std::clamp(0.1 * size, real(0.001), real(0.05));
    if (n == 0 && !pair.manifolds.empty()) {
        // FCL sees only overlap: a resting contact that opens by a hair would be lost
        // with its warm-start impulses and found again a step later. Keep its points as
        // speculative contacts while they stay close.
        keepNearPoints(pair.manifolds, poseA, poseB, kContactKeepDistance, anchorsIssued_);
        return;
    }
    // At most four manifolds per pair (a mesh may report more normals).
    const int kept = std::min(n, 4);
    pair.manifolds.resize(kept);
    for (int k = 0; k < kept; ++k)
        mergeManifold(pair.manifolds[k], fresh_[k], poseA, poseB, matchDistance, newAnchorsId());
}

std::uint32_t ContactManager::findOrAddPair(BodyStore &bodies, std::uint32_t i, std::uint32_t j, bool &created) {
    const std::uint32_t p = pairs.findOrAdd(i, j, created);
    if (created) {
        bodies[i].pairs.push_back(p);
        bodies[j].pairs.push_back(p);
    }
    return p;
}

void ContactManager::removePair(BodyStore &bodies, std::uint32_t p) {
    const PairState &pair = pairs[p];
    for (std::uint32_t index : {pair.a, pair.b}) {
        std::vector<std::uint32_t> &list = bodies[index].pairs;
        const auto at = std::find(list.begin(), list.end(), p);
        if (at != list.end()) {
            *at = list.back();
            list.pop_back();
        }
    }
    pairs.remove(p);
    eventSlots_.push_back(p);
}

void ContactManager::removePairsOf(BodyStore &bodies, std::uint32_t index) {
    while (!bodies[index].pairs.empty()) removePair(bodies, bodies[index].pairs.back());
}

// Contact begin and end are found by comparing each pair's touching state with the one
// it had at the end of the last step. The state is kept per pair slot together with the
// two BodyIds it belonged to, so a slot reused by another pair, or a pair whose body was
// removed (its generation moved on), ends the old contact before the new one begins.
void ContactManager::reportContactEvents(WorldState &world) {
    const BodyStore &bodies = world.bodies;
    WorldEvents &events = world.events.events;
    if (tracks_.size() < pairs.slots()) tracks_.resize(pairs.slots());
    // Only slots the narrowphase saw or that were removed can have changed. Those whose
    // state did change (few: a resting scene has none) are taken in slot order, so that
    // events come in the same order whichever way they were found.
    const auto stateOf = [&](std::uint32_t p) {
        const PairState *pair = p < pairs.slots() ? &pairs[p] : nullptr;
        const bool touching = pair && pair->alive && pair->touching();
        return ContactTrack{touching ? bodies.idOf(pair->a) : BodyId(), touching ? bodies.idOf(pair->b) : BodyId(), touching};
    };
    // The changed slots are moved to the front of eventSlots_, in place: a list of their
    // own would allocate the first time a late step changes more than it ever held.
    std::size_t changed = 0;
    for (std::uint32_t p : eventSlots_) {
        const ContactTrack &track = tracks_[p];
        const ContactTrack now = stateOf(p);
        if (track.touching != now.touching || (now.touching && (track.a != now.a || track.b != now.b)))
            eventSlots_[changed++] = p;
    }
    eventSlots_.resize(changed);
    std::sort(eventSlots_.begin(), eventSlots_.end());
    eventSlots_.erase(std::unique(eventSlots_.begin(), eventSlots_.end()), eventSlots_.end());
    for (std::uint32_t p : eventSlots_) {
        ContactTrack &track = tracks_[p];
        const ContactTrack now = stateOf(p);
        if (track.touching && (!now.touching || track.a != now.a || track.b != now.b)) {
            events.contactEnds.push_back({track.a, track.b});
            track.touching = false;
        }
        if (!now.touching || track.touching) continue;
        track = now;

        // The deepest point stands for the contact.
        const PairState *pair = &pairs[p];
        const BodyRecord &ra = bodies[pair->a];
        const BodyRecord &rb = bodies[pair->b];
        const Matrix4 poseA = ra.body.getTransform();
        const Matrix4 poseB = rb.body.getTransform();
        ContactBegin begin;
        begin.a = now.a;
        begin.b = now.b;
        bool first = true;
        for (const ManifoldState &m : pair->manifolds) {
            for (int i = 0; i < m.count; ++i) {
                const PersistentPoint &point = m.points[i];
                if (!first && !(point.depth > begin.depth)) continue;
                first = false;
                begin.depth = point.depth;
                begin.normal = m.normal;
                begin.point = 0.5 * (poseA * point.localA + poseB * point.localB);
            }
        }
        const Vector3 va = ra.body.getVelocity() + ra.body.getRotation().cross(begin.point - ra.body.getPosition());
        const Vector3 vb = rb.body.getVelocity() + rb.body.getRotation().cross(begin.point - rb.body.getPosition());
        begin.approachSpeed = (va - vb).dot(begin.normal);
        events.contactBegins.push_back(begin);
    }
    eventSlots_.clear();
}

}  // namespace cyclone::detail
