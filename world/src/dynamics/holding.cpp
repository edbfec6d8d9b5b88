#include "dynamics/holding.h"

#include <algorithm>

#include "contacts/pair_cache.h"
#include "dynamics/step_plan.h"
#include "world/body_store.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone::detail {
namespace {

// Rings of bodies that could be held around a held one: with one, no held body touches a
// moving one (two are measured in docs/experiments.md).
constexpr int kRings = 1;

// Closing speed at a contact point between two awake bodies above which the contact is a
// hit, m/s: a hit reaches through touching bodies within the step it lands in, so no body
// of what it touches is held then (held, a box of a row struck end on stood as a wall and
// threw the ball back). Above resting contacts' g dt (0.16 m/s at 60 Hz).
constexpr real kHitSpeed = 0.5;

std::uint32_t other(const PairState &pair, std::uint32_t index) { return pair.a == index ? pair.b : pair.a; }

// How fast the points of manifold m close, B's surface towards A's along the normal, m/s.
real closingSpeed(const ManifoldState &m, const RigidBody &a, const RigidBody &b) {
    real fastest = 0;
    for (int i = 0; i < m.count; ++i) {
        const Vector3 p = a.getPointInWorldSpace(m.points[i].localA);
        const Vector3 va = a.getVelocity() + a.getRotation().cross(p - a.getPosition());
        const Vector3 vb = b.getVelocity() + b.getRotation().cross(p - b.getPosition());
        fastest = std::max(fastest, (va - vb).dot(m.normal));
    }
    return fastest;
}

// Whether the body could be held on its own: it could sleep now, nothing but gravity
// acts on it, and it rests on warm contacts.
bool couldHold(const BodyRecord &r, const PairCache &pairs, const StepContext &context) {
    const RigidBody &body = r.body;
    if (r.isolated || !body.getCanSleep() || !(body.getSleepAverage() < body.getSleepEpsilon())) return false;
    if (!body.getAccumulatedForce().isZero(0) || !body.getAccumulatedTorque().isZero(0)) return false;
    return rests(r, pairs, context.stepCount, context.dt);
}

}  // namespace

void Holding::choose(const StepContext &context, BodyStore &bodies, PairCache &pairs, StepStats &stats) {
    // Last step's marks go first. A body held then is awake and simulated now, or has
    // slept or been removed since, which cleared its mark; a restored state brings its own.
    for (std::uint32_t index : bodies.simulated) bodies[index].held = false;
    held_.clear();
    const WorldSettings &settings = context.settings;
    if (!settings.sleep || !settings.debug.holding || context.activeJoints > 0 || context.activeSprings > 0) return;
    if (!markStill(context, bodies, pairs)) return;
    takeOut(bodies);
    // Manifolds between held and immovable bodies stay as the last solve left them; as
    // solved, they keep the bodies resting next step (a manifold solved afresh takes a
    // new solver slot, whose Jacobians are made again). A pair of two held bodies is
    // stamped by the one of lower index.
    context.workers.forEach(held_.size(), [&](std::size_t k) {
        const std::uint32_t index = held_[k];
        for (std::uint32_t p : bodies[index].pairs) {
            const std::uint32_t o = other(pairs[p], index);
            if (bodies[o].simulated || (bodies[o].held && o < index)) continue;
            for (ManifoldState &m : pairs[p].manifolds) {
                m.solverStep = context.stepCount;
                m.solverSlot = UINT32_MAX;
            }
        }
    });
    stats.heldBodies = static_cast<int>(held_.size());
}

bool Holding::markStill(const StepContext &context, const BodyStore &bodies, const PairCache &pairs) {
    // Each body's marks are its own, made on the threads: only the hit walk is one
    // thread's.
    Workers &workers = context.workers;
    const std::vector<std::uint32_t> &simulated = bodies.simulated;
    still_.assign(bodies.size(), 0);
    workers.forEach(simulated.size(), [&](std::size_t k) {
        still_[simulated[k]] = couldHold(bodies[simulated[k]], pairs, context) ? 1 : 0;
    });
    if (std::none_of(simulated.begin(), simulated.end(), [&](std::uint32_t index) { return still_[index] != 0; }))
        return false;
    clearHit(workers, bodies, pairs);
    // Each ring keeps the bodies whose every pair's other body the last one kept: a
    // moving kinematic body never, a static or sleeping one always.
    for (int ring = 0; ring < kRings; ++ring) {
        ring_.assign(still_.size(), 0);
        workers.forEach(simulated.size(), [&](std::size_t k) {
            const std::uint32_t index = simulated[k];
            if (!still_[index]) return;
            for (std::uint32_t p : bodies[index].pairs) {
                const std::uint32_t o = other(pairs[p], index);
                if (bodies[o].moving || (bodies[o].simulated && !still_[o])) return;
            }
            ring_[index] = 1;
        });
        still_.swap(ring_);
    }
    return true;
}

void Holding::clearHit(Workers &workers, const BodyStore &bodies, const PairCache &pairs) {
    // The bodies of each hit, found on the threads, then everything that touches them,
    // body by body.
    const auto hit = [&](const PairState &pair) {
        if (!bodies[pair.a].simulated || !bodies[pair.b].simulated) return false;
        for (const ManifoldState &m : pair.manifolds)
            if (closingSpeed(m, bodies[pair.a].body, bodies[pair.b].body) > kHitSpeed) return true;
        return false;
    };
    // No point of a body moves faster than |v| + |w| r (r: its bounding radius): one body
    // of a hit at least moves faster than kHitSpeed / 2 so, and its pairs are all looked at.
    const auto struck = [&](std::uint32_t index) {
        const RigidBody &body = bodies[index].body;
        const real fastest = body.getVelocity().norm() + body.getRotation().norm() * bodies[index].boundingRadius;
        if (fastest <= kHitSpeed / 2) return false;
        return std::any_of(bodies[index].pairs.begin(), bodies[index].pairs.end(),
                           [&](std::uint32_t p) { return hit(pairs[p]); });
    };
    walk_.clear();
    const std::vector<std::uint32_t> &simulated = bodies.simulated;
    workers.forFlagged(simulated.size(), flags_, [&](std::size_t k) { return struck(simulated[k]); },
                       [&](std::size_t k) {
                           const std::uint32_t index = simulated[k];
                           walk_.push_back(index);
                           for (std::uint32_t p : bodies[index].pairs)
                               if (hit(pairs[p])) walk_.push_back(other(pairs[p], index));
                       });
    if (walk_.empty()) return;
    // Then the flood through touching pairs, ring by ring on the threads. Each body goes
    // to the one test that marks it reached (PassFlags::take): what the flood decides is
    // the set reached, the same whichever thread comes first.
    reached_.reserve(bodies.size());
    reached_.begin();
    front_.clear();
    for (std::uint32_t index : walk_)
        if (reached_.take(index)) front_.push_back(index);
    while (!front_.empty()) {
        const std::size_t count = front_.size();
        const std::size_t chunks = Workers::chunksOf(count);
        next_.start(workers.threads(), chunks);
        workers.forEachChunkOnThreads(count, [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
            std::vector<std::uint32_t> &found = next_.open(chunk, thread);
            for (std::size_t k = begin; k < end; ++k) {
                const std::uint32_t index = front_[k];
                still_[index] = 0;
                for (std::uint32_t p : bodies[index].pairs) {
                    const std::uint32_t o = other(pairs[p], index);
                    if (pairs[p].touching() && bodies[o].simulated && reached_.take(o)) found.push_back(o);
                }
            }
            next_.close(chunk);
        });
        next_.finish();
        front_.clear();
        for (std::size_t chunk = 0; chunk < chunks; ++chunk)
            for (std::uint32_t index : next_.items(chunk)) front_.push_back(index);
    }
}

void Holding::takeOut(BodyStore &bodies) {
    std::size_t kept = 0;
    for (std::uint32_t index : bodies.simulated) {
        BodyRecord &r = bodies[index];
        if (!still_[index]) {
            r.solverIndex = static_cast<int>(kept) + 1;
            bodies.simulated[kept++] = index;
            continue;
        }
        held_.push_back(index);
        r.held = true;
        r.simulated = false;
        r.solverIndex = 0;
        r.body.setVelocity(Vector3::Zero());
        r.body.setRotation(Vector3::Zero());
    }
    bodies.simulated.resize(kept);
}

}  // namespace cyclone::detail
