#include "contacts/contact_manager.h"

#include <algorithm>
#include <limits>

#include "collision/time_of_impact.h"
#include "joints/joint_set.h"
#include "world/body_transitions.h"
#include "world/room.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// How far apart (along or across the normal) a contact's anchors may drift once the
// narrowphase no longer reports the pair before the contact is dropped, m.
constexpr real kContactKeepDistance = 0.002;

// Speculative contacts come from the velocities at the start of the step. The speed
// gravity adds during the step moves a body at most |g| dt^2 farther (2.7 mm at 60 Hz):
// while that is within the speculative distance, whose contacts every pair gets anyway,
// it is left out, so that resting bodies, which move less than kMinReach in a step, keep
// exactly the contacts they touch and pay nothing more. Beyond it (dt > 45 ms at the
// defaults) a body at rest in the air could fall through a floor in one step: a body
// that touches nothing then reaches with its speed at the step's end, v + g dt
// (stepFall), against immovable bodies. Bodies that touch something, or have another
// dynamic body as a candidate, are left as they are: a stack's upper boxes given
// speculative contacts with the floor under it sink into one another.
constexpr real kMinReach = 0.001;  // m

// The speed gravity adds to a body falling freely over the step when it counts (above), m/s.
Vector3 stepFall(const WorldSettings &settings, real dt) {
    const real fall = settings.gravity.norm() * dt * dt;
    return fall > settings.speculativeDistance ? Vector3(settings.gravity * dt) : Vector3(Vector3::Zero());
}

// Whether a dynamic body touches nothing: none of its pairs has a manifold (last step's).
bool fallsFreely(const BodyRecord &r, const PairCache &pairs) {
    if (r.immovable) return false;
    for (std::uint32_t p : r.pairs)
        if (pairs[p].touching()) return false;
    return true;
}

// Whether a dynamic body falls freely in this step's narrowphase: it touched nothing last
// step and no other dynamic body is a candidate with it now. A stack placed this step has
// no manifold yet, but its boxes are each other's candidates, so none of them falls. The
// answer depends only on last step's manifolds and this step's candidates, not on the
// order in which the threads test the pairs.
bool fallsFreelyNow(const BodyRecord &r, const BodyStore &bodies, const PairCache &pairs, std::uint64_t stepCount) {
    if (!fallsFreely(r, pairs)) return false;
    for (std::uint32_t p : r.pairs) {
        const PairState &pair = pairs[p];
        if (pair.lastSeen == stepCount && !bodies[pair.a].immovable && !bodies[pair.b].immovable) return false;
    }
    return true;
}

// The speed gravity adds over the step that counts between the pair's bodies: only
// between a dynamic body that falls freely now and an immovable one.
Vector3 pairFall(const BodyRecord &a, const BodyRecord &b, const BodyStore &bodies, const PairCache &pairs,
                 const WorldSettings &settings, real dt, std::uint64_t stepCount) {
    if (a.immovable == b.immovable) return Vector3::Zero();
    const Vector3 fall = stepFall(settings, dt);
    if (fall.squaredNorm() > 0 && !fallsFreelyNow(a.immovable ? b : a, bodies, pairs, stepCount)) return Vector3::Zero();
    return fall;
}

// Whether a body stands still: no velocity, no rotation.
bool standsStill(const RigidBody &body) { return body.getVelocity().isZero(0) && body.getRotation().isZero(0); }

// The velocity a body reaches with over the step: its own, plus `fall` if dynamic (the
// caller passes zero for a body that does not fall freely).
Vector3 reachVelocity(const BodyRecord &r, const Vector3 &fall) {
    return r.immovable ? r.body.getVelocity() : Vector3(r.body.getVelocity() + fall);
}

// How far any point of the body can move in a step of dt at its velocities, m.
real stepReach(const BodyRecord &r, real dt, const Vector3 &fall) {
    if (r.immovable && !r.moving) return 0;
    return (reachVelocity(r, fall).norm() + r.body.getRotation().norm() * r.boundingRadius) * dt;
}

// How far any point of A can move relative to any point of B in a step of dt, m: two
// bodies falling together reach nothing of each other.
real relativeReach(const BodyRecord &a, const BodyRecord &b, real dt, const Vector3 &fall) {
    const RigidBody &ba = a.body;
    const RigidBody &bb = b.body;
    const real turning = ba.getRotation().norm() * a.boundingRadius + bb.getRotation().norm() * b.boundingRadius;
    return ((ba.getVelocity() - bb.getVelocity()).norm() + fall.norm() + turning) * dt;
}

// How far A and B can close in on each other along `normal` (A to B) within dt, m.
real closing(const BodyRecord &a, const BodyRecord &b, const Vector3 &normal, real dt, const Vector3 &fall) {
    const RigidBody &ba = a.body;
    const RigidBody &bb = b.body;
    const real linear = (ba.getVelocity() - bb.getVelocity()).dot(normal) + std::abs(fall.dot(normal));
    const real turning = ba.getRotation().norm() * a.boundingRadius + bb.getRotation().norm() * b.boundingRadius;
    return (linear + turning) * dt;
}

// The body's pose after dt at its velocities (rotation at constant angular velocity).
Matrix4 poseAfter(const BodyRecord &r, real dt, const Vector3 &fall) {
    const RigidBody &body = r.body;
    Matrix4 pose = body.getTransform();
    pose.translation() += reachVelocity(r, fall) * dt;
    const Vector3 turn = body.getRotation() * dt;
    const real angle = turn.norm();
    if (angle > 0) pose.linear() = Eigen::AngleAxis<real>(angle, turn / angle).toRotationMatrix() * pose.linear();
    return pose;
}

// Whether two shapes apart now touch at some time of the step when each moves at its
// velocities: a speculative contact's normal is only that of their nearest features,
// and a body passing by a corner would be stopped by it without this test.
bool meetWithinStep(const BodyRecord &a, const BodyRecord &b, real dt, const Vector3 &fall) {
    if (a.isPlane || b.isPlane) return true;  // a half-space's normal is exact: closing() is the test
    // A height field's FCL geometry is only its box: its triangles' normals are exact too.
    if (a.shape->shape().type == ShapeType::Heightfield || b.shape->shape().type == ShapeType::Heightfield) return true;
    return meetDuring(sweptShape(*a.shape), a.body.getTransform(), poseAfter(a, dt, fall), sweptShape(*b.shape),
                      b.body.getTransform(), poseAfter(b, dt, fall)) != Impact::None;
}

// B's pose seen from A (the manifold-reuse test compares it with the last narrowphase's):
// A's rotation transposed is its inverse.
RelativePose relativePose(const RigidBody &a, const RigidBody &b) {
    return {a.getTransform().linear().transpose() * (b.getPosition() - a.getPosition()),
            a.getOrientation().conjugate() * b.getOrientation()};
}

// Flags each simulated, then moving kinematic, body by flag(index) on the threads, then
// calls act(index) for the flagged ones in that order on this thread. `flags` is scratch.
template <class Flag, class Act>
void forFlaggedBodies(const BodyStore &bodies, Workers &workers, std::vector<char> &flags, const Flag &flag,
                      const Act &act) {
    const std::size_t simulated = bodies.simulated.size();
    const auto bodyAt = [&](std::size_t k) { return k < simulated ? bodies.simulated[k] : bodies.moving[k - simulated]; };
    workers.forFlagged(simulated + bodies.moving.size(), flags, [&](std::size_t k) { return flag(bodyAt(k)); },
                       [&](std::size_t k) { act(bodyAt(k)); });
}

}  // namespace

void ContactManager::findCandidates(const StepContext &context, BodyStore &bodies, Broadphase &broadphase,
                                    StepStats &stats) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    const real dt = context.dt;
    movedObjects_.clear();
    // A body's box reaches as far as the body can move in the step, so that a pair that
    // can meet within it is a candidate (and gets a speculative contact).
    const Vector3 fall = stepFall(settings, dt);
    const bool counted = fall.squaredNorm() > 0;
    // Each body places its own object (on several threads); the moved ones are listed
    // after, in the bodies' order.
    const auto place = [&](std::uint32_t index) {
        BodyRecord &r = bodies[index];
        r.seen.look(r.body, context.stepCount);
        if (!r.object) return false;
        const bool falls = counted && fallsFreely(r, pairs);
        const real reach = settings.debug.speculativeContacts ? stepReach(r, dt, falls ? fall : Vector3(Vector3::Zero())) : 0;
        return r.object->place(r.body.getTransform(), kBroadphaseMargin, reach >= kMinReach ? reach : 0);
    };
    forFlaggedBodies(bodies, workers, flags_, place,
                     [&](std::uint32_t index) { movedObjects_.push_back(bodies[index].object.get()); });
    broadphase.refitAwake(movedObjects_);

    // Planes stay out of the trees: test each awake body's AABB against each plane (and,
    // for sensors, each moving kinematic body's). The half-space is the compiled one (unit
    // normal, offset along it, as FCL has it), placed by the plane body's pose as the
    // narrowphase places it. They are found first, so that the pair budget never drops a
    // body's floor, and listed after the trees'.
    planePairs_.clear();
    const bool filtering = bodies.filtering();
    for (std::uint32_t plane : bodies.planes) {
        const CollisionShape &p = *bodies[plane].shape;
        const Matrix4 pose = bodies[plane].body.getTransform();
        const Vector3 n = pose.linear() * p.planeNormal();
        const real offset = p.planeOffset() + n.dot(pose.translation());
        const auto below = [&](const BodyRecord &r) {
            const fcl::AABBd &box = r.object->getAABB();
            const Vector3 centre = boxCentre(box);
            const Vector3 half = 0.5 * (box.max_ - box.min_);
            return n.dot(centre) - n.cwiseAbs().dot(half) <= offset + settings.speculativeDistance;
        };
        for (std::uint32_t index : bodies.simulated) {
            const BodyRecord &r = bodies[index];
            if (!r.object || !below(r)) continue;
            if (!filtering) {
                planePairs_.contacts.push_back({plane, index});
                continue;
            }
            switch (bodies.classify(plane, index)) {
                case PairKind::Contact: planePairs_.contacts.push_back({plane, index}); break;
                case PairKind::Sensor: planePairs_.sensors.push_back({plane, index}); break;
                case PairKind::Filtered: ++planePairs_.filtered; break;
            }
        }
        if (bodies.sensorCount == 0) continue;
        for (std::uint32_t index : bodies.moving) {
            const BodyRecord &r = bodies[index];
            if (r.object && below(r) && bodies.classify(plane, index) == PairKind::Sensor)
                planePairs_.sensors.push_back({plane, index});
        }
    }

    // The trees' pairs, within what the budget leaves (WorldSettings::maxPairs).
    found_.clear();
    const std::size_t budget = static_cast<std::size_t>(settings.maxPairs);
    const std::size_t planeCount = planePairs_.contacts.size() + planePairs_.sensors.size();
    const std::size_t treeBudget = budget > planeCount ? budget - planeCount : 0;
    const bool complete = broadphase.findPairs(found_, filtering ? &bodies : nullptr, treeBudget,
                                               [&](int count, const auto &task) { workers.forEachTask(count, task); });
    found_.contacts.insert(found_.contacts.end(), planePairs_.contacts.begin(), planePairs_.contacts.end());
    found_.sensors.insert(found_.sensors.end(), planePairs_.sensors.begin(), planePairs_.sensors.end());
    found_.filtered += planePairs_.filtered;
    if (found_.contacts.size() > budget) found_.contacts.resize(budget);  // more plane pairs than the budget
    if (!complete || planeCount > budget) stats.errors |= StepError::PairBudgetExceeded;
    stats.broadphasePairs = static_cast<int>(found_.contacts.size());
    stats.filteredPairs = found_.filtered;
}

void ContactManager::updateContacts(const StepContext &context, BodyStore &bodies, const JointSet &joints,
                                    BodyTransitions transitions, StepStats &stats) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    const std::uint64_t stepCount = context.stepCount;
    const real dt = context.dt;
    stepPairs_.clear();
    touchingPairs.clear();
    listCandidates(bodies, joints, workers, stats);
    // A body woken by a contact joins this step (Integration::admit), and so do its
    // island's pairs: they were not candidates, the broadphase skipping sleeping bodies.
    // Tested in turn, they may wake further islands.
    const PairTest test{settings, bodies, workers, stepCount, dt};
    for (std::size_t begin = 0; begin < stepPairs_.size();) {
        const std::size_t end = stepPairs_.size();
        const std::size_t simulated = bodies.simulated.size();
        testPairs(test, begin, end);
        countAnchors(stats, begin, end);
        mergePairs(bodies, workers, begin, end);
        wakeTouched(transitions, begin, end);
        begin = end;
        for (std::size_t k = simulated; k < bodies.simulated.size(); ++k) listPairsOf(bodies, joints, bodies.simulated[k]);
    }
    removeUnseenPairs(bodies, workers, stepCount);
}

// The step's pairs, each once, in the broadphase's order.
void ContactManager::listCandidates(BodyStore &bodies, const JointSet &joints, Workers &workers, StepStats &stats) {
    // The broadphase lists a settled scene's pairs in the same order step after step:
    // the slot each candidate had last step is checked first, saving most table look-ups.
    // That check and the look-up of the others are made on several threads (both miss the
    // cache); only the pairs not in the table are then added, one by one.
    const std::vector<CandidatePair> &candidates = found_.contacts;
    candidateSlots_.resize(candidates.size(), kNoSlot);
    candidateKinds_.resize(candidates.size());
    workers.forEach(candidates.size(), [&](std::size_t k) {
        pairs.prefetchAhead(candidateSlots_, k, candidates.size());
        const CandidatePair &c = candidates[k];
        CandidateKind kind = CandidateKind::Held;
        if (joints.excludesContact(c.a, c.b)) kind = CandidateKind::Excluded;  // joined without collideConnected
        else if (bodies[c.a].immovable && bodies[c.b].immovable) kind = CandidateKind::Immovable;
        else if (!pairs.holds(candidateSlots_[k], c.a, c.b)) {
            const long found = pairs.find(c.a, c.b);
            if (found >= 0) candidateSlots_[k] = static_cast<std::uint32_t>(found);
            else kind = CandidateKind::New;
        }
        candidateKinds_[k] = kind;
    });
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        const CandidatePair &c = candidates[k];
        const CandidateKind kind = candidateKinds_[k];
        if (kind == CandidateKind::Excluded) continue;
        if (kind == CandidateKind::Immovable) {
            // A moving kinematic body with a static or kinematic one: neither can push.
            ++stats.immovablePairsSkipped;
            continue;
        }
        std::uint32_t p = candidateSlots_[k];
        if (kind == CandidateKind::New) {  // or listed twice, and added by its first listing
            bool created = false;
            p = findOrAddPair(bodies, c.a, c.b, created);
            candidateSlots_[k] = p;
        }
        listPair(p);
    }
}

void ContactManager::listPair(std::uint32_t p) {
    if (stepIndex_.size() < pairs.slots()) stepIndex_.resize(pairs.slots(), 0);
    if (inStep(p)) return;  // reported twice
    stepIndex_[p] = static_cast<std::uint32_t>(stepPairs_.size());
    eventSlots_.push_back(p);
    stepPairs_.push_back(p);
}

namespace {

// A pair whose manifolds are all gone gives the room of its list to the pairs that begin
// to touch, which take a room given before they allocate one: the rooms held are those
// of the pairs touching at once, not of every pair that ever touched (in a landing pile,
// pairs touch and part many times over, and about half the rooms would lie empty).
void spareRoom(std::vector<ManifoldState> &manifolds, std::vector<std::vector<ManifoldState>> &rooms) {
    if (!manifolds.empty() || manifolds.capacity() == 0) return;
    rooms.emplace_back();
    rooms.back().swap(manifolds);
}

void takeRoom(std::vector<ManifoldState> &manifolds, std::vector<std::vector<ManifoldState>> &rooms) {
    if (manifolds.capacity() > 0 || rooms.empty()) return;
    manifolds.swap(rooms.back());
    rooms.pop_back();
}

}  // namespace

// Only rooms past a thread's share move (and those of threads no longer run), so that
// a steady step moves none.
void ContactManager::dealRooms(int threads) {
    const std::size_t count = std::size_t(threads);
    while (mergeScratch_.size() < count) mergeScratch_.emplace_back();
    for (std::size_t from = count; from < mergeScratch_.size(); ++from) {
        for (std::vector<ManifoldState> &room : mergeScratch_[from].rooms)
            mergeScratch_[0].rooms.emplace_back().swap(room);
        mergeScratch_[from].rooms.clear();
    }
    std::size_t total = 0;
    for (std::size_t t = 0; t < count; ++t) total += mergeScratch_[t].rooms.size();
    const std::size_t share = total / count;
    std::size_t to = 0;  // the next thread short of its share
    for (std::size_t from = 0; from < count; ++from) {
        std::vector<std::vector<ManifoldState>> &rooms = mergeScratch_[from].rooms;
        while (rooms.size() > share) {
            while (to < count && mergeScratch_[to].rooms.size() >= share) ++to;
            if (to == count) break;  // every thread has its share
            mergeScratch_[to].rooms.emplace_back().swap(rooms.back());
            rooms.pop_back();
        }
    }
}

// A woken body's pairs kept from before it slept: with its island's other members (woken
// with it) and with static bodies, each touching as it was when the island fell asleep.
void ContactManager::listPairsOf(const BodyStore &bodies, const JointSet &joints, std::uint32_t index) {
    for (std::uint32_t p : bodies[index].pairs)
        if (!joints.excludesContact(pairs[p].a, pairs[p].b)) listPair(p);
}

// Each pair on its own, in chunks shared between the threads: pairs that hardly moved
// keep their manifolds, the others go through the narrowphase, which appends what it
// finds to its thread's list (ChunkLists). The finds are then merged into the pairs one
// after another in the pairs' order (anchors are numbered in that order), so the results
// do not depend on the thread count (countAnchors, mergePairs). Pairs that touch after it
// are listed, and wake their sleeping bodies (wakeTouched).
void ContactManager::testPairs(const PairTest &test, std::size_t first, std::size_t last) {
    const std::uint64_t stepCount = test.stepCount;
    const std::size_t count = last - first;
    test.workers.forEach(count, [&](std::size_t k) { pairs[stepPairs_[first + k]].lastSeen = stepCount; });
    chunkFinds_.start(test.workers.threads(), Workers::chunksOf(count));
    makeRoom(finds_, last > finds_.size() ? last - finds_.size() : 0);
    finds_.resize(last);
    test.workers.forEachChunkOnThreads(count, [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
        std::vector<Manifold> &out = chunkFinds_.open(chunk, thread);
        const std::size_t base = out.size();
        for (std::size_t k = first + begin; k < first + end; ++k) {
            pairs.prefetchAhead(stepPairs_, k, first + end);
            Find &find = finds_[k];
            find = Find();
            find.reused = reuseManifolds(test.settings, test.bodies, stepPairs_[k]);
            if (find.reused) continue;
            find.still = test.settings.debug.unchangedPairs && standStill(test, stepPairs_[k]);
            find.unchanged = find.still && unchanged(stepPairs_[k], test.bodies);
            if (find.unchanged) continue;
            find.first = static_cast<std::uint32_t>(out.size() - base);
            NormalMemo *memo = endNormal(stepPairs_[k], stepCount - 1);
            find.count = static_cast<std::uint32_t>(detect(test, stepPairs_[k], out, memo));
            pairs[stepPairs_[k]].testedStep = stepCount;
            find.anchors = static_cast<std::uint32_t>(anchorsIssuedBy(test.bodies, stepPairs_[k], find.count));
        }
        chunkFinds_.close(chunk);
    });
    chunkFinds_.finish();
}

// The anchor numbers each merge issues, counted with the tests, are handed out first, in
// the pairs' order, so that each pair gets the same numbers whichever thread merges it.
void ContactManager::countAnchors(StepStats &stats, std::size_t first, std::size_t last) {
    std::uint64_t issued = anchorsIssued_;
    for (std::size_t k = first; k < last; ++k) {
        Find &find = finds_[k];
        if (find.reused) {
            ++stats.pairsReused;
            continue;
        }
        if (find.unchanged) {
            ++stats.pairsUnchanged;
            continue;
        }
        ++stats.pairsTested;
        find.issuedBefore = issued;
        issued += find.anchors;
    }
    anchorsIssued_ = issued;
}

// The finds are merged into their pairs, chunk by chunk: a merge writes only its own pair
// (but the detection reads other pairs' manifolds, so it comes after all of them).
void ContactManager::mergePairs(const BodyStore &bodies, Workers &workers, std::size_t first, std::size_t last) {
    const std::size_t count = last - first;
    dealRooms(workers.threads());
    workers.forEachChunkOnThreads(count, [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
        const Manifold *out = chunkFinds_.items(chunk).begin();
        for (std::size_t k = first + begin; k < first + end; ++k) {
            pairs.prefetchAhead(stepPairs_, k, first + end);
            Find &find = finds_[k];
            const std::uint32_t p = stepPairs_[k];
            if (!find.reused && !find.unchanged) {
                mergeFinds(bodies, p, out + find.first, find.count, find.issuedBefore,
                           mergeScratch_[std::size_t(thread)]);
                pairs[p].testedStill = find.still && !pairs[p].touching();
            }
            const PairState &pair = pairs[p];
            find.touching = pair.touching();
            if (!find.touching) continue;
            const BodyRecord &a = bodies[pair.a];
            const BodyRecord &b = bodies[pair.b];
            find.wakeB = (a.simulated || a.moving) && !b.immovable && !b.simulated;
            find.wakeA = (b.simulated || b.moving) && !a.immovable && !a.simulated;
        }
    });
}

// A contact, touching or speculative, of an awake or moving kinematic body wakes the
// sleeping body it reaches, which joins this step (Integration::admit).
void ContactManager::wakeTouched(BodyTransitions transitions, std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
        const Find &find = finds_[k];
        if (!find.touching) continue;
        const std::uint32_t p = stepPairs_[k];
        touchingPairs.push_back(p);
        if (find.wakeB) transitions.wake(pairs[p].b);
        if (find.wakeA) transitions.wake(pairs[p].a);
    }
}

// Pairs with an awake member that the broadphase no longer reports have separated
// (walked body by body: sleeping bodies' pairs cost nothing). Which bodies have such a pair
// is found on several threads; removing pairs only shortens the lists, so the walk over
// those bodies alone removes the same pairs in the same order.
void ContactManager::removeUnseenPairs(BodyStore &bodies, Workers &workers, std::uint64_t stepCount) {
    const auto unseen = [&](std::uint32_t p) { return pairs[p].lastSeen != stepCount; };
    forFlaggedBodies(
        bodies, workers, flags_,
        [&](std::uint32_t index) { return std::any_of(bodies[index].pairs.begin(), bodies[index].pairs.end(), unseen); },
        [&](std::uint32_t index) {
            std::vector<std::uint32_t> &list = bodies[index].pairs;
            for (std::size_t i = list.size(); i-- > 0;)
                if (unseen(list[i])) removePair(bodies, list[i]);
        });
}

// Unchanged pairs: a test's answer depends only on the two bodies' shapes, poses and
// velocities, the fall between them and the settings. A pair that found no contact with
// both bodies standing still (no velocity, no fall), that stand still now and neither of
// whose poses has changed since (SeenState: a body's pose is looked at before each
// narrowphase that may test it, and when it sleeps or the game moves it; setSettings and
// restoreState renew them all), would find none again.
bool ContactManager::standStill(const PairTest &test, std::uint32_t p) const {
    const PairState &pair = pairs[p];
    const BodyRecord &a = test.bodies[pair.a];
    const BodyRecord &b = test.bodies[pair.b];
    return standsStill(a.body) && standsStill(b.body) &&
           pairFall(a, b, test.bodies, pairs, test.settings, test.dt, test.stepCount).isZero(0);
}

bool ContactManager::unchanged(std::uint32_t p, const BodyStore &bodies) const {
    const PairState &pair = pairs[p];
    return pair.testedStill && bodies[pair.a].seen.since <= pair.testedStep && bodies[pair.b].seen.since <= pair.testedStep;
}

// Only a touching pair is reused: one with no manifold may come into contact within the
// tolerance, and FCL does not see contacts that are apart by a hair. A pair touches only
// through a merge, which kept its relative pose.
bool ContactManager::reuseManifolds(const WorldSettings &settings, const BodyStore &bodies, std::uint32_t p) {
    PairState &pair = pairs[p];
    if (!pair.touching() || settings.debug.manifoldReuseTolerance <= 0) return false;
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const Matrix4 poseA = a.body.getTransform();
    const Matrix4 poseB = b.body.getTransform();
    const RelativePose relative = relativePose(a.body, b.body);
    const RelativePose &tested = pair.manifolds[0].tested;
    const real shift = (relative.position - tested.position).norm();
    const Quaternion turn = relative.orientation * tested.orientation.conjugate();
    const real radius = std::max(a.boundingRadius, b.boundingRadius);
    if (!movedLess(shift, turn, radius, settings.debug.manifoldReuseTolerance)) return false;
    for (ManifoldState &m : pair.manifolds) refreshFromAnchors(m, poseA, poseB);
    return true;
}

std::size_t ContactManager::detect(const PairTest &test, std::uint32_t p, std::vector<Manifold> &out,
                                   NormalMemo *memo) const {
    const BodyStore &bodies = test.bodies;
    const WorldSettings &settings = test.settings;
    const real dt = test.dt;
    const PairState &pair = pairs[p];
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const std::size_t first = out.size();
    NarrowphaseSettings narrowphase;
    narrowphase.speculativeDistance = settings.speculativeDistance;
    // The fall counts against a body that does not fall: two dynamic bodies fall together.
    const Vector3 fall = pairFall(a, b, bodies, pairs, settings, dt, test.stepCount);
    const real reach = settings.debug.speculativeContacts ? relativeReach(a, b, dt, fall) : 0;
    narrowphase.reach = reach >= kMinReach ? reach : 0;
    narrowphase.touchMargin = settings.penetrationSlop;
    narrowphase.wasApart = !pair.touching();
    const int n = collide(*a.shape, a.body.getTransform(), *b.shape, b.body.getTransform(), narrowphase, out, memo);
    if (narrowphase.reach > 0 && n > 0) {
        // Shapes apart that cannot close the gap along their normal in this step, or
        // would pass by each other, have no contact yet.
        // The time of impact is found once per pair, and only if some manifold needs it.
        int meet = -1;
        const auto noContactYet = [&](const Manifold &m) {
            real deepest = -std::numeric_limits<real>::infinity();
            for (int k = 0; k < m.count; ++k) deepest = std::max(deepest, m.points[k].depth);
            if (!(deepest < -narrowphase.touchMargin)) return false;  // touching: a contact
            if (-deepest > closing(a, b, m.normal, dt, fall)) return true;
            if (meet < 0) meet = meetWithinStep(a, b, dt, fall) ? 1 : 0;
            return meet == 0;
        };
        const auto from = out.begin() + static_cast<std::ptrdiff_t>(first);
        out.erase(std::remove_if(from, out.end(), noContactYet), out.end());
    }
    return out.size() - first;
}

std::uint64_t ContactManager::anchorsIssuedBy(const BodyStore &bodies, std::uint32_t p, std::size_t n) const {
    const PairState &pair = pairs[p];
    if (n == 0) return pair.manifolds.size();  // keepNearPoints renumbers each kept manifold
    return keptManifolds(n, bodies[pair.a].shape->isCompound() || bodies[pair.b].shape->isCompound());
}

void ContactManager::mergeFinds(const BodyStore &bodies, std::uint32_t p, const Manifold *found, std::size_t n,
                                std::uint64_t issued, MergeScratch &scratch) {
    PairState &pair = pairs[p];
    // A pair apart that stays apart (most of a pile's pairs) has nothing to merge, and
    // its pose is not kept: only a touching pair is reused.
    if (n == 0 && pair.manifolds.empty()) return;
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    const Matrix4 poseA = a.body.getTransform();
    const Matrix4 poseB = b.body.getTransform();
    const real size = std::min(a.isPlane ? b.boundingRadius : a.boundingRadius,
                               b.isPlane ? a.boundingRadius : b.boundingRadius);
    const real matchDistance = std::clamp(0.1 * size, real(0.001), real(0.05));
    if (n == 0) {
        // FCL sees only overlap: a resting contact that opens by a hair would be lost
        // with its warm-start impulses and found again a step later. Keep its points as
        // speculative contacts while they stay close.
        keepNearPoints(pair.manifolds, poseA, poseB, kContactKeepDistance, issued);
        spareRoom(pair.manifolds, scratch.rooms);
    } else if (a.shape->isCompound() || b.shape->isCompound()) {
        mergeByChildren(pair, found, n, poseA, poseB, *a.shape, *b.shape, matchDistance, issued, scratch);
    } else {
        const std::size_t kept = keptManifolds(n, false);
        takeRoom(pair.manifolds, scratch.rooms);
        pair.manifolds.resize(kept);
        for (std::size_t k = 0; k < kept; ++k)
            mergeManifold(pair.manifolds[k], found[k], poseA, poseB, *a.shape, *b.shape, matchDistance, ++issued);
    }
    const RelativePose tested = relativePose(a.body, b.body);
    for (ManifoldState &m : pair.manifolds) m.tested = tested;
}

// A compound's manifolds belong to pairs of children: each fresh one warm-starts from the
// old one of the same children (the n-th of a child pair from its n-th, for a child on a
// mesh with several normals), wherever it stood in the list.
void ContactManager::mergeByChildren(PairState &pair, const Manifold *found, std::size_t n, const Matrix4 &poseA,
                                     const Matrix4 &poseB, const CollisionShape &shapeA, const CollisionShape &shapeB,
                                     real matchDistance, std::uint64_t issued, MergeScratch &scratch) {
    std::vector<ManifoldState> &previous = scratch.previous;
    std::vector<char> &used = scratch.used;
    previous.swap(pair.manifolds);
    takeRoom(pair.manifolds, scratch.rooms);
    used.assign(previous.size(), 0);
    const std::size_t kept = keptManifolds(n, true);
    pair.manifolds.resize(kept);
    for (std::size_t k = 0; k < kept; ++k) {
        const Manifold &fresh = found[k];
        ManifoldState &state = pair.manifolds[k];
        state = ManifoldState();
        for (std::size_t j = 0; j < previous.size(); ++j) {
            if (used[j] || previous[j].childA != fresh.childA || previous[j].childB != fresh.childB) continue;
            used[j] = 1;
            state = previous[j];
            break;
        }
        mergeManifold(state, fresh, poseA, poseB, shapeA, shapeB, matchDistance, ++issued);
    }
    previous.clear();
}

void ContactManager::keepEndNormal(std::uint32_t p, const NormalMemo &memo, std::uint64_t step) {
    if (endNormalOf_.size() < pairs.slots()) endNormalOf_.resize(pairs.slots(), kNoSlot);
    if (NormalMemo *kept = endNormal(p, step)) {
        *kept = memo;
        return;
    }
    endNormalOf_[p] = static_cast<std::uint32_t>(endNormals_.size());
    makeRoom(endNormals_);
    endNormals_.push_back({p, step, memo});
}

NormalMemo *ContactManager::endNormal(std::uint32_t p, std::uint64_t step) {
    if (p >= endNormalOf_.size() || endNormalOf_[p] >= endNormals_.size()) return nullptr;
    EndNormal &entry = endNormals_[endNormalOf_[p]];
    return entry.pair == p && entry.step == step ? &entry.memo : nullptr;
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
    if (mergeScratch_.empty()) mergeScratch_.emplace_back();
    spareRoom(pairs[p].manifolds, mergeScratch_[0].rooms);
    if (p < endNormalOf_.size()) endNormalOf_[p] = kNoSlot;
    eventSlots_.push_back(p);
}

void ContactManager::removePairsOf(BodyStore &bodies, std::uint32_t index) {
    while (!bodies[index].pairs.empty()) removePair(bodies, bodies[index].pairs.back());
}

// Contact begin and end are found by comparing each pair's touching state with the one
// it had at the end of the last step. The state is kept per pair slot together with the
// two BodyIds it belonged to, so a slot reused by another pair, or a pair whose body was
// removed (its generation moved on), ends the old contact before the new one begins.
void ContactManager::reportContactEvents(const StepContext &context, const BodyStore &bodies, WorldEvents &events) {
    Workers &workers = context.workers;
    tracks_.cover(pairs.slots());
    // Only slots the narrowphase saw or that were removed can have changed. Those whose
    // state did change (few: a resting scene has none) are taken in slot order, so that
    // events come in the same order whichever way they were found.
    const auto stateOf = [&](std::uint32_t p) {
        const PairState *pair = p < pairs.slots() ? &pairs[p] : nullptr;
        const bool touching = pair && pair->alive && pair->touching();
        return ContactTrack{touching ? bodies.idOf(pair->a) : BodyId(), touching ? bodies.idOf(pair->b) : BodyId(), touching};
    };
    // Which slots changed is found on the threads; they are then moved to the front of
    // eventSlots_, in place: a list of their own would allocate the first time a late
    // step changes more than it ever held.
    const auto changedAt = [&](std::size_t k) {
        const ContactTrack &track = tracks_.at(eventSlots_[k]);
        const ContactTrack now = stateOf(eventSlots_[k]);
        return track.touching != now.touching || (now.touching && (track.a != now.a || track.b != now.b));
    };
    std::size_t changed = 0;
    workers.forFlagged(eventSlots_.size(), flags_, changedAt,
                       [&](std::size_t k) { eventSlots_[changed++] = eventSlots_[k]; });
    eventSlots_.resize(changed);
    std::sort(eventSlots_.begin(), eventSlots_.end());
    eventSlots_.erase(std::unique(eventSlots_.begin(), eventSlots_.end()), eventSlots_.end());
    for (std::uint32_t p : eventSlots_) {
        const ContactTrack track = tracks_.at(p);
        ContactTrack now = stateOf(p);
        const bool ended = track.touching && (!now.touching || track.a != now.a || track.b != now.b);
        if (ended) {
            makeRoom(events.contactEnds);
            events.contactEnds.push_back({track.a, track.b, track.userDataA, track.userDataB});
            tracks_.end(p);
        }
        if (!now.touching || (track.touching && !ended)) continue;

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
        begin.userDataA = now.userDataA = ra.userData;
        begin.userDataB = now.userDataB = rb.userData;
        makeRoom(events.contactBegins);
        events.contactBegins.push_back(begin);
        tracks_.begin(p, now);
    }
    eventSlots_.clear();
}

}  // namespace cyclone::detail
