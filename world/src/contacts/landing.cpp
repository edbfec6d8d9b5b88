#include "contacts/landing.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "collision/time_of_impact.h"
#include "contacts/contact_manager.h"
#include "contacts/pre_solve.h"
#include "dynamics/islands.h"
#include "dynamics/union_find.h"
#include "joints/joint_set.h"
#include "world/room.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// The deepest a pair may be left at the end of a step, m: 5 mm, or a tenth of the
// smaller body's bounding radius when that is less (a 5 cm box: 4.3 mm), but not below
// twice the slop, which the solver leaves alone. The passes push a point back to half
// of it.
constexpr real kLandingDepth = 0.005;
constexpr real kLandingFraction = 0.1;

// Rounds of testing and pushing: the first tests the pairs of the fast bodies, each later
// one, afresh, those of the bodies the round before pushed farther than a quarter of
// their tolerance (a push may take a body into a third, or, on a round side, off the
// point that was pushed).
constexpr int kRounds = 4;
// A pair the step began deeper in than this times its tolerance has its bodies pushed
// too, though they did not move fast: 8 mm at the 5 mm tolerance, under the 1 cm a pile
// may show; at the tolerance itself a resting pile would be pushed every step and sleep
// later (docs/contacts_and_sleep.md, "Deep contacts in a falling pile").
constexpr real kRestingFactor = 1.6;
// How far the step's pushes between two movable bodies may take one of them down (along
// gravity) in all, times its bounding radius: a body overlapping many others (bodies
// spawned at one point) was pushed by all of them at once through the static floor under
// it, whose pair with the body no round had tested (its broadphase box did not reach the
// floor). Pushes across or up are not bounded: coincident spheres are parted along x.
constexpr real kStepReach = 0.25;
// Nonlinear Gauss-Seidel passes a round makes over its points.
constexpr int kPasses = 8;
// A round in which at least 1 / kWalkShare of the awake bodies moved takes its pairs from
// a walk over the step's whole list; a round of fewer from those bodies' own lists,
// sorted into the step's order (a landing pile's first round moved nearly every body:
// its pairs' sort and the scattered reads of the lists cost 2-4 ms a step on mixed5000).
constexpr std::size_t kWalkShare = 4;

// The unit vector against gravity (zero without gravity).
Vector3 upward(const Vector3 &gravity) {
    return gravity.squaredNorm() > 0 ? Vector3(-gravity.normalized()) : Vector3(Vector3::Zero());
}

// Caps `lower`'s share of a push at `reach` (none when it is negative) and gives the rest
// to `upper`.
void moveShare(real reach, real &lower, real &upper) {
    const real cap = std::max<real>(reach, 0);
    if (!(lower > cap)) return;
    upper += lower - cap;
    lower = cap;
}

real toleranceFor(real radius, real slop) {
    return std::max(std::min(kLandingDepth, kLandingFraction * radius), 2 * slop);
}

// The tolerance of a pair: that of its smaller body (a plane's partner's).
real pairTolerance(const BodyRecord &a, const BodyRecord &b, real slop) {
    const real size = std::min(a.isPlane ? b.boundingRadius : a.boundingRadius,
                               b.isPlane ? a.boundingRadius : b.boundingRadius);
    return toleranceFor(size, slop);
}

// Whether the support point bounds the shape: a convex one, or a compound (whose children
// lie in the hull of their support points).
bool bounded(const CollisionShape &shape) {
    switch (shape.shape().type) {
        case ShapeType::Box:
        case ShapeType::Sphere:
        case ShapeType::Capsule:
        case ShapeType::Cylinder:
        case ShapeType::Convex:
        case ShapeType::Compound: return true;
        default: return false;
    }
}

// Whether the pair's shapes, both bounded, overlap by at most `depth` along an axis: its
// normal at the step's start (turned with A), or the line between the bodies for a pair
// that did not touch. No contact point between them can then be deeper than `depth`: two
// convex shapes' penetration is at most their overlap along any axis (the support points
// give it), and a compound's children lie within its hull.
bool overlapWithin(const PairState &pair, const BodyRecord &a, const Matrix4 &poseA, const BodyRecord &b,
                   const Matrix4 &poseB, real depth) {
    if (!bounded(*a.shape) || !bounded(*b.shape)) return false;
    Vector3 axis = pair.touching() ? Vector3(poseA.linear() * pair.manifolds[0].localNormal)
                                   : Vector3(poseB.translation() - poseA.translation());
    const real length = axis.norm();
    if (!(length > 0)) return false;
    axis /= length;
    const real overlap = axis.dot(a.shape->supportPoint(poseA, axis, -1)) - axis.dot(b.shape->supportPoint(poseB, -axis, -1));
    return overlap <= depth;
}

}  // namespace

// Whether the passes may move the body: awake and moved fast by this step, and, in a
// joint, in a group that may move (buildJointGroups). A body that hardly moved did not
// make the overlap, and its pairs with third bodies (the ground under it) are not
// tested: pushed, it would be driven into them unseen.
bool LandingCorrection::movable(const BodyStore &bodies, std::uint32_t index) const {
    const BodyRecord &r = bodies[index];
    return r.simulated && !r.isolated && index < movedRound_.size() && movedRound_[index] >= 0 &&
           (group_.empty() || group_[index] < 0 || groupMovable_[static_cast<std::size_t>(group_[index])]);
}

void LandingCorrection::markFast(std::uint32_t index) {
    if (movedRound_[index] == 0) return;
    movedRound_[index] = 0;
    activeBodies_.push_back(index);
}

// A group may move when every member is an awake dynamic body with a collision shape and
// no joint holds a member to the world: a push moves all members, so a member that may not
// move (static, kinematic, asleep) holds the group still, as the world does. A group none of
// whose members moved fast does not move either (its members' pairs are not tested); one
// that has such a member has all its members marked fast, so that all their pairs are.
void LandingCorrection::buildJointGroups(const BodyStore &bodies, const JointSet &joints) {
    const std::size_t n = bodies.size();
    group_.assign(n, -1);
    groupMovable_.assign(n, 0);
    groupInverseMass_.assign(n, 0);
    firstMember_.assign(n, -1);
    nextMember_.assign(n, -1);
    // Union-find over the joints' bodies (the others stay at -1): group_ holds each joined
    // body's parent first, then its root.
    const auto join = [&](std::uint32_t index) {
        if (group_[index] < 0) group_[index] = static_cast<int>(index);
    };
    for (const JointRecord &joint : joints.records) {
        if (!joint.alive) continue;
        join(joint.settings.a.index);
        if (!joint.settings.b) continue;
        join(joint.settings.b->index);
        uniteSets(group_, static_cast<int>(joint.settings.a.index), static_cast<int>(joint.settings.b->index));
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (group_[i] < 0) continue;
        const int g = findRoot(group_, static_cast<int>(i));
        group_[i] = g;
        const auto at = static_cast<std::size_t>(g);
        nextMember_[i] = firstMember_[at];
        firstMember_[at] = static_cast<std::int32_t>(i);
    }
    // Movable until a member or a joint to the world says otherwise; the summed mass.
    for (std::size_t i = 0; i < n; ++i)
        if (group_[i] == static_cast<std::int32_t>(i)) groupMovable_[i] = 1;
    for (std::size_t i = 0; i < n; ++i) {
        if (group_[i] < 0) continue;
        const auto g = static_cast<std::size_t>(group_[i]);
        const BodyRecord &r = bodies[i];
        if (!r.simulated || r.isolated || !r.object || !(r.body.getInverseMass() > 0)) groupMovable_[g] = 0;
        else groupInverseMass_[g] += r.body.getMass();
    }
    for (const JointRecord &joint : joints.records)
        if (joint.alive && !joint.settings.b) groupMovable_[static_cast<std::size_t>(group_[joint.settings.a.index])] = 0;
    for (std::size_t g = 0; g < n; ++g) {
        if (!groupMovable_[g]) continue;
        groupInverseMass_[g] = 1 / groupInverseMass_[g];
        bool fast = false;
        for (std::int32_t m = firstMember_[g]; m >= 0 && !fast; m = nextMember_[static_cast<std::size_t>(m)])
            fast = movedRound_[static_cast<std::size_t>(m)] == 0;
        if (!fast) {
            groupMovable_[g] = 0;  // no member moved fast: none of its members' pairs is tested
            continue;
        }
        for (std::int32_t m = firstMember_[g]; m >= 0; m = nextMember_[static_cast<std::size_t>(m)])
            markFast(static_cast<std::uint32_t>(m));
    }
}

real LandingCorrection::pushedInverseMass(const BodyStore &bodies, std::uint32_t index) const {
    if (!group_.empty() && group_[index] >= 0) return groupInverseMass_[static_cast<std::size_t>(group_[index])];
    return bodies[index].body.getInverseMass();
}

void LandingCorrection::translate(BodyStore &bodies, std::uint32_t index, const Vector3 &delta, real length) {
    ++pushes_;
    if (group_.empty() || group_[index] < 0) {
        RigidBody &body = bodies[index].body;
        body.setPosition(body.getPosition() + delta);
        noteMove(index, length);
        shifts_[index] += delta;
        return;
    }
    for (std::int32_t m = firstMember_[static_cast<std::size_t>(group_[index])]; m >= 0;
         m = nextMember_[static_cast<std::size_t>(m)]) {
        RigidBody &body = bodies[static_cast<std::size_t>(m)].body;
        body.setPosition(body.getPosition() + delta);
        noteMove(static_cast<std::uint32_t>(m), length);
    }
}

void LandingCorrection::correct(const StepContext &context, BodyStore &bodies, ContactManager &contacts,
                                const PreSolve &preSolve, const JointSet &joints, const Islands &islands,
                                StepStats &stats) {
    const WorldSettings &settings = context.settings;
    Workers &workers = context.workers;
    const real deepest = context.deepest;
    const std::uint64_t stepCount = context.stepCount;
    if (!settings.debug.landingCorrection) return;
    markFastBodies(settings, bodies, contacts, preSolve, workers, deepest);
    contacts.clearEndNormals();
    if (activeBodies_.empty()) return;
    group_.clear();
    if (!joints.empty()) buildJointGroups(bodies, joints);

    points_.clear();
    nextOrder_ = 0;
    for (int round = 1; round <= kRounds; ++round) {
        const int last = round - 1;
        listRoundPairs(bodies, contacts, preSolve, workers, last);
        if (pairs_.empty()) break;
        const auto retested = [&](const Point &x) { return movedIn(x.a, last) || movedIn(x.b, last); };
        points_.erase(std::remove_if(points_.begin(), points_.end(), retested), points_.end());
        stats.landingPairs += static_cast<int>(pairs_.size());
        const std::size_t before = points_.size();
        const bool deep = detect(settings, bodies, contacts, workers, stepCount);
        // The first round acts only where some point is deeper than its tolerance; a later
        // one wherever its fresh points lie deeper than their targets.
        if (round == 1 ? !deep : points_.size() == before) break;
        orderPoints(before);
        stats.landingPushes += push(settings, bodies, round);
    }

    for (std::uint32_t index : activeBodies_) {
        payForLift(bodies, islands, settings.gravity, index);
        movedRound_[index] = -1;
        sunk_[index] = 0;
        shifts_[index].setZero();
    }
    activeBodies_.clear();
}

bool LandingCorrection::movedIn(std::uint32_t index, int round) const {
    return index < movedRound_.size() && movedRound_[index] == round;
}

// The fast bodies: those that moved (their collision object still holds the step's start)
// more than half their own tolerance, and the bodies of deep resting pairs. They count as
// moved in round 0 (activeBodies_, movedRound_, sunk_).
void LandingCorrection::markFastBodies(const WorldSettings &settings, const BodyStore &bodies,
                                       const ContactManager &contacts, const PreSolve &preSolve, Workers &workers,
                                       real deepest) {
    const real slop = settings.penetrationSlop;
    activeBodies_.clear();
    if (movedRound_.size() < bodies.size()) {
        movedRound_.resize(bodies.size(), -1);
        sunk_.resize(bodies.size(), 0);
        shifts_.resize(bodies.size(), Vector3::Zero());
        pushedAt_.resize(bodies.size(), 0);
    }
    // Each test below is made on the threads, and the bodies it picks are marked after,
    // in order.
    const auto movedFast = [&](std::size_t k) {
        const BodyRecord &r = bodies[bodies.simulated[k]];
        if (r.isolated || !r.object) return false;
        const real tolerance = toleranceFor(r.boundingRadius, slop);
        const Matrix4 &from = r.object->getTransform();
        const Matrix4 &to = r.body.getTransform();
        if (travelWithin(from, to, r.boundingRadius, 0.5 * tolerance)) return false;
        return travel(from, to, r.boundingRadius) > 0.5 * tolerance;
    };
    workers.forFlagged(bodies.simulated.size(), flags_, movedFast,
                             [&](std::size_t k) { markFast(bodies.simulated[k]); });
    // The bodies of a pair the step began deeper in than kRestingFactor times its
    // tolerance (a body sunk under a pile's load, which the solver does not carry).
    const std::vector<std::uint32_t> &touching = contacts.touchingPairs;
    const auto deepPair = [&](std::size_t k) {
        if (preSolve.anyDisabled() && preSolve.disabled(touching[k])) return false;  // passing through, as asked
        const PairState &pair = contacts.pairs[touching[k]];
        const real deepest = kRestingFactor * pairTolerance(bodies[pair.a], bodies[pair.b], slop);
        for (const ManifoldState &m : pair.manifolds)
            for (int i = 0; i < m.count; ++i)
                if (m.points[i].depth > deepest) return true;
        return false;
    };
    // None can be when no contact point of the step is deeper than that at the least
    // tolerance (StepStats::maxPenetration: the deepest point the step solved), as in a
    // resting stack: the pairs' points are then not read again.
    const bool anyDeep = deepest > kRestingFactor * toleranceFor(0, slop);
    if (anyDeep) workers.forFlagged(touching.size(), flags_, deepPair, [&](std::size_t k) {
        const PairState &pair = contacts.pairs[touching[k]];
        for (const std::uint32_t index : {pair.a, pair.b}) {
            const BodyRecord &r = bodies[index];
            if (r.simulated && !r.isolated && r.object) {
                markFast(index);
                sunk_[index] = 1;
            }
        }
    });
}

// The step's pairs with a body that moved in round `last` (or, in the first round, moved
// fast in the step), into pairs_: they are tested afresh and their old points go. They
// are taken in the step's order (ContactManager::stepPairs): from a walk over that list
// when many bodies moved, else from those bodies' own pairs (a pair of two such bodies
// once), sorted. Pairs the pre-solve stage disabled are left out.
void LandingCorrection::listRoundPairs(const BodyStore &bodies, const ContactManager &contacts,
                                       const PreSolve &preSolve, Workers &workers, int last) {
    pairs_.clear();
    const std::size_t movers = static_cast<std::size_t>(std::count_if(
        activeBodies_.begin(), activeBodies_.end(), [&](std::uint32_t i) { return movedRound_[i] == last; }));
    if (movers * kWalkShare >= bodies.simulated.size()) {
        // Most bodies moved (a landing pile's first round): the step's list is walked
        // on the threads, in order, its pairs' states asked for ahead.
        const std::vector<std::uint32_t> &step = contacts.stepPairs();
        const auto picked = [&](std::size_t k) {
            contacts.pairs.prefetchAhead(step, k, step.size());
            const PairState &pair = contacts.pairs[step[k]];
            return (movedIn(pair.a, last) || movedIn(pair.b, last)) &&
                   (movable(bodies, pair.a) || movable(bodies, pair.b));
        };
        workers.forFlagged(step.size(), flags_, picked, [&](std::size_t k) { pairs_.push_back(step[k]); });
    } else {
        for (const std::uint32_t index : activeBodies_) {
            if (movedRound_[index] != last) continue;
            for (const std::uint32_t p : bodies[index].pairs) {
                if (!contacts.inStep(p)) continue;
                const PairState &pair = contacts.pairs[p];
                const std::uint32_t other = pair.a == index ? pair.b : pair.a;
                if (movedIn(other, last) && other < index) continue;  // listed from `other`
                if (movable(bodies, pair.a) || movable(bodies, pair.b)) pairs_.push_back(p);
            }
        }
        std::sort(pairs_.begin(), pairs_.end(),
                  [&](std::uint32_t x, std::uint32_t y) { return contacts.stepIndex(x) < contacts.stepIndex(y); });
    }
    if (preSolve.anyDisabled())
        pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(), [&](std::uint32_t p) { return preSolve.disabled(p); }),
                     pairs_.end());
}

// Lowest first: a push up out of what is below is not undone by the one below it. Small
// keys are sorted and the points then put in their order: moving whole points about in
// the sort cost more. The points kept from the last round are in order already (a point's
// height is that of its finding): only the new ones are sorted, then merged with them.
// Keys differ in `order`, so any sort gives the one order.
void LandingCorrection::orderPoints(std::size_t kept) {
    sortKeys_.clear();
    makeRoom(sortKeys_, points_.size());
    for (std::size_t i = 0; i < points_.size(); ++i)
        sortKeys_.push_back({points_[i].height, points_[i].order, static_cast<std::uint32_t>(i)});
    const auto lower = [](const SortKey &x, const SortKey &y) {
        return x.height < y.height || (x.height == y.height && x.order < y.order);
    };
    const auto fresh = sortKeys_.begin() + static_cast<std::ptrdiff_t>(kept);
    std::sort(fresh, sortKeys_.end(), lower);
    if (kept > 0) {
        mergedKeys_.clear();
        std::merge(sortKeys_.begin(), fresh, fresh, sortKeys_.end(), std::back_inserter(mergedKeys_), lower);
        sortKeys_.swap(mergedKeys_);
    }
    placeInOrder();
}

// Each cycle of the permutation is followed once, a point held aside at its start; a key
// whose point is in place is marked with kPlaced.
void LandingCorrection::placeInOrder() {
    constexpr std::uint32_t kPlaced = ~std::uint32_t(0);
    for (std::size_t start = 0; start < sortKeys_.size(); ++start) {
        if (sortKeys_[start].index == kPlaced) continue;
        const Point held = points_[start];
        std::size_t at = start;
        while (sortKeys_[at].index != start) {
            const std::size_t from = sortKeys_[at].index;
            points_[at] = points_[from];
            sortKeys_[at].index = kPlaced;
            at = from;
        }
        points_[at] = held;
        sortKeys_[at].index = kPlaced;
    }
}

// The points of the manifolds `out` of `pair`, held by anchors on both bodies at the
// poses they were found at, into `found`; whether one is deeper than `tolerance`.
bool LandingCorrection::appendPoints(const std::vector<Manifold> &out, const PairState &pair,
                                     const Matrix4 &poseA, const Matrix4 &poseB, real tolerance, const Vector3 &up,
                                     std::vector<Point> &found) {
    bool deep = false;
    const Matrix3 toA = poseA.linear().transpose();
    const Matrix3 toB = poseB.linear().transpose();
    for (const Manifold &m : out) {
        for (int i = 0; i < m.count; ++i) {
            const ContactPoint &c = m.points[static_cast<std::size_t>(i)];
            deep = deep || c.depth > tolerance;
            Point point;
            point.a = pair.a;
            point.b = pair.b;
            point.localA = toA * (c.pointA - poseA.translation());
            point.localB = toB * (c.pointB - poseB.translation());
            point.localNormal = toA * m.normal;
            point.target = 0.5 * tolerance;
            point.height = up.dot(0.5 * (c.pointA + c.pointB));
            found.push_back(point);
        }
    }
    return deep;
}

// The points of the pair's manifolds from the step's start, held by their anchors: a pair
// the passes need not test gives them so that no push drives a body into the other.
void LandingCorrection::appendAnchored(const PairState &pair, const Matrix4 &poseA, const Matrix4 &poseB,
                                       real tolerance, const Vector3 &up, std::vector<Point> &found) {
    for (const ManifoldState &m : pair.manifolds) {
        for (int i = 0; i < m.count; ++i) {
            const PersistentPoint &p = m.points[i];
            Point point;
            point.a = pair.a;
            point.b = pair.b;
            point.localA = p.localA;
            point.localB = p.localB;
            point.localNormal = m.localNormal;
            point.target = 0.5 * tolerance;
            point.height = up.dot(0.5 * (poseA * p.localA + poseB * p.localB));
            found.push_back(point);
        }
    }
}

bool LandingCorrection::detect(const WorldSettings &settings, const BodyStore &bodies, ContactManager &contacts,
                               Workers &workers, std::uint64_t stepCount) {
    const PairCache &pairs = contacts.pairs;
    const real slop = settings.penetrationSlop;
    NarrowphaseSettings narrowphase;
    narrowphase.speculativeDistance = settings.speculativeDistance;
    // Shapes a hair apart (a box just above the ground) get points too, so that a push
    // towards them is held; only the pairs with a test of their own give them, at no cost.
    narrowphase.touchMargin = settings.speculativeDistance;
    const Vector3 up = upward(settings.gravity);
    // Each pair on its own, in chunks shared between the threads, each thread's points in
    // a list of its own; the chunks' points are then joined in the pairs' order, so that
    // the points do not depend on the thread count.
    const std::size_t count = pairs_.size();
    const std::size_t chunks = Workers::chunksOf(count);
    const int threads = workers.threads();
    // A thread's list holds one pair's manifolds at a time (a convex pair finds at most one).
    while (threadFinds_.size() < std::size_t(threads)) threadFinds_.emplace_back().reserve(1);
    chunkMemos_.start(threads, chunks);
    chunkPoints_.start(threads, chunks);
    chunkDeep_.resize(chunks);
    workers.forEachChunkOnThreads(count, [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
        std::vector<Manifold> &out = threadFinds_[std::size_t(thread)];
        std::vector<Memo> &memos = chunkMemos_.open(chunk, thread);
        std::vector<Point> &found = chunkPoints_.open(chunk, thread);
        bool deep = false;
        for (std::size_t k = begin; k < end; ++k) {
            // The pairs lie scattered in the pair cache: their states are asked for ahead.
            pairs.prefetchAhead(pairs_, k, end);
            const PairState &pair = pairs[pairs_[k]];
            const BodyRecord &a = bodies[pair.a];
            const BodyRecord &b = bodies[pair.b];
            const Matrix4 poseA = a.body.getTransform();
            const Matrix4 poseB = b.body.getTransform();
            const real tolerance = pairTolerance(a, b, slop);
            // A pair that overlaps by no more than the passes' target has no point to push:
            // it is not tested again, and its start points stand guard.
            if (overlapWithin(pair, a, poseA, b, poseB, 0.5 * tolerance)) {
                appendAnchored(pair, poseA, poseB, tolerance, up, found);
                continue;
            }
            out.clear();
            NormalMemo memo;
            collide(*a.shape, poseA, *b.shape, poseB, narrowphase, out, &memo);
            if (memo.a) memos.push_back({static_cast<std::uint32_t>(k), memo.touching, memo.normal});
            deep = appendPoints(out, pair, poseA, poseB, tolerance, up, found) || deep;
        }
        chunkDeep_[chunk] = deep ? 1 : 0;
        chunkMemos_.close(chunk);
        chunkPoints_.close(chunk);
    });
    chunkMemos_.finish();
    chunkPoints_.finish();
    // What FCL found goes on to the next step's narrowphase (ContactManager's end normals),
    // with the poses it was found at: the bodies' own still.
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
        for (const Memo &m : chunkMemos_.items(chunk)) {
            const PairState &pair = pairs[pairs_[m.k]];
            const BodyRecord &a = bodies[pair.a];
            const BodyRecord &b = bodies[pair.b];
            NormalMemo memo;
            memo.keep(*a.shape, a.body.getTransform(), *b.shape, b.body.getTransform(), m.touching, m.normal);
            contacts.keepEndNormal(pairs_[m.k], memo, stepCount);
        }
    }
    bool deep = false;
    makeRoom(points_, chunkPoints_.found());
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
        deep = deep || chunkDeep_[chunk] != 0;
        for (Point point : chunkPoints_.items(chunk)) {
            point.order = nextOrder_++;
            points_.push_back(point);
        }
    }
    return deep;
}

int LandingCorrection::push(const WorldSettings &settings, BodyStore &bodies, int round) {
    const Vector3 up = upward(settings.gravity);
    int pushed = 0;
    moved_.clear();
    for (int pass = 0; pass < kPasses; ++pass) {
        bool any = false;
        for (Point &point : points_) {
            // Neither body pushed since the point was found shallow: it still is.
            if (point.shallowAt != 0 && pushedAt_[point.a] <= point.shallowAt && pushedAt_[point.b] <= point.shallowAt)
                continue;
            BodyRecord &a = bodies[point.a];
            BodyRecord &b = bodies[point.b];
            const Matrix4 &poseA = a.body.getTransform();
            const Matrix4 &poseB = b.body.getTransform();
            const Vector3 normal = poseA.linear() * point.localNormal;
            const real depth = (poseA * point.localA - poseB * point.localB).dot(normal);
            if (!(depth > point.target)) {
                point.shallowAt = pushes_;
                continue;
            }
            point.shallowAt = 0;
            bool moveA = movable(bodies, point.a);
            bool moveB = movable(bodies, point.b);
            // Two members of one joint group move together: no push parts them.
            if (!group_.empty() && group_[point.a] >= 0 && group_[point.a] == group_[point.b]) continue;
            if (moveA != moveB && liftAbove(bodies, point, moveA, normal.dot(up), round)) moveA = moveB = true;
            // The bodies (or their joint groups) move along the normal only, split by their
            // inverse masses.
            const real massA = moveA ? pushedInverseMass(bodies, point.a) : 0;
            const real massB = moveB ? pushedInverseMass(bodies, point.b) : 0;
            const real k = massA + massB;
            if (!(k > 0)) continue;
            // How far each moves along the normal: A back along it, B forward.
            const real lambda = (depth - point.target) / k;
            real shareA = lambda * massA;
            real shareB = lambda * massB;
            if (massA > 0 && massB > 0) {
                // Only a push down is bounded, and what the lower body may no longer take
                // the upper one does (without, a cylinder in mixed1000 landing on one that
                // had used up its reach stayed 45 mm in it through the first round's
                // passes and 11.7 mm after the last round).
                const real down = normal.dot(up);
                if (down > 0) moveShare(reachLeft(bodies, point.a, down, up), shareA, shareB);
                if (down < 0) moveShare(reachLeft(bodies, point.b, -down, up), shareB, shareA);
            }
            if (shareA > 0) translate(bodies, point.a, -shareA * normal, shareA);
            if (shareB > 0) translate(bodies, point.b, shareB * normal, shareB);
            if (pass == 0) ++pushed;
            any = true;
        }
        if (!any) break;
    }
    // A body pushed farther than a quarter of its tolerance in all has its pairs tested
    // again in the next round (it moved fast, so it is in activeBodies_ already).
    const real slop = settings.penetrationSlop;
    for (const Move &move : moved_)
        if (move.length > 0.25 * toleranceFor(bodies[move.body].boundingRadius, slop)) movedRound_[move.body] = round;
    for (const Move &move : moved_) moveSlot_[move.body] = -1;
    return pushed;
}

// A sunk body (in a pair the step began deep in) pushed down by a body above it that may
// not move would be driven back into what carries it: a column's bottom box, pushed up out
// of the ground by the point before, then down again by the box it carries, would end the
// passes deeper than it began. The body
// above is lifted instead: it becomes movable and sunk, and as a body moved in this round
// its pairs are tested in the next, so that a column is lifted box by box (kRounds of
// them). Only an awake dynamic body outside joints, and only up (the normal within 60
// degrees of gravity's opposite), so that it goes into no ground unseen; only above a
// sunk body, as a fast one lifting what rests on it keeps piles rocking
// (docs/contacts_and_sleep.md, "Deep contacts in a falling pile").
bool LandingCorrection::liftAbove(const BodyStore &bodies, const Point &point, bool moveA, real normalUp, int round) {
    constexpr real kSteepest = 0.5;  // cos 60 degrees
    const std::uint32_t moving = moveA ? point.a : point.b;
    const std::uint32_t still = moveA ? point.b : point.a;
    // The still body must lie above the moving one (B lies along the normal).
    if (!sunk_[moving] || (moveA ? normalUp : -normalUp) < kSteepest) return false;
    const BodyRecord &r = bodies[still];
    if (!r.simulated || r.isolated || !r.object || (!group_.empty() && group_[still] >= 0)) return false;
    movedRound_[still] = round;
    sunk_[still] = 1;
    activeBodies_.push_back(still);
    return true;
}

real LandingCorrection::reachLeft(const BodyStore &bodies, std::uint32_t index, real down, const Vector3 &up) const {
    if (!group_.empty() && group_[index] >= 0) return std::numeric_limits<real>::infinity();  // joints hold it
    const real limit = kStepReach * bodies[index].boundingRadius;
    const real lowered = -shifts_[index].dot(up);
    const real step = (limit - std::max<real>(lowered, 0)) / down;
    if (moveSlot_.size() <= index || moveSlot_[index] < 0) return std::min(limit, step);
    return std::min(limit - moved_[static_cast<std::size_t>(moveSlot_[index])].length, step);
}

// A push is a position change only: a body pushed up out of the floor it fell into keeps
// the speed it hit the floor with and gains the push's height in potential energy (a rod
// landing tilted on its rim, unseen by the step's contacts: up to 2 % of its energy). The
// contact the step missed would have taken that speed: the push takes from the body's
// speed against it the potential energy it gave (m |g| h), and no more, so that a bounce
// keeps the rest. Only a body that touched no other movable body in the step (an island
// of its own): in a pile the lifts are the passes' answer to the solver's load, which
// the next step's contacts carry, and paying for them there left piles deeper and awake
// (docs/experiments.md). Members of joint groups and bodies with locked axes are left.
void LandingCorrection::payForLift(BodyStore &bodies, const Islands &islands, const Vector3 &gravity,
                                   std::uint32_t index) {
    BodyRecord &r = bodies[index];
    const Vector3 &shift = shifts_[index];
    const real length = shift.norm();
    if (!(length > 0) || r.island < 0 || islands.size(r.island) != 1 || r.locked.any()) return;
    if (!group_.empty() && group_[index] >= 0) return;
    const real lift = -(r.gravityScale * gravity).dot(shift);  // |g| h, J/kg
    if (!(lift > 0)) return;
    const Vector3 along = shift / length;
    const Vector3 velocity = r.body.getVelocity();
    const real against = velocity.dot(along);
    if (!(against < 0)) return;
    const real kept = -std::sqrt(std::max<real>(against * against - 2 * lift, 0));
    r.body.setVelocity(velocity + (kept - against) * along);
}

void LandingCorrection::noteMove(std::uint32_t body, real length) {
    pushedAt_[body] = pushes_;
    if (moveSlot_.size() <= body) moveSlot_.resize(movedRound_.size(), -1);
    int &slot = moveSlot_[body];
    if (slot < 0) {
        slot = static_cast<int>(moved_.size());
        moved_.push_back({body, 0});
    }
    moved_[static_cast<std::size_t>(slot)].length += length;
}

}  // namespace cyclone::detail
