#include "dynamics/holding.h"

#include <algorithm>

#include "contacts/pair_cache.h"
#include "dynamics/step_plan.h"
#include "world/body_store.h"
#include "world/step_context.h"

namespace cyclone::detail {
namespace {

// Rings of still bodies around a held one. With one, the bodies next to a moving one
// were held and let go step after step, and mixed1000's pile woke in bursts (20-110 bodies
// above their sleep threshold at a time); docs/contacts_and_sleep.md, "Held bodies".
constexpr int kRings = 2;

std::uint32_t other(const PairState &pair, std::uint32_t index) { return pair.a == index ? pair.b : pair.a; }

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
    // Last step's marks go first: a body held then may since sleep, wake or be removed.
    for (std::uint32_t index : held_)
        if (index < bodies.size()) bodies[index].held = false;
    held_.clear();
    const WorldSettings &settings = context.settings;
    if (!settings.sleep || !settings.debug.holding || context.activeJoints > 0 || context.activeSprings > 0) return;
    if (!markStill(context, bodies, pairs)) return;
    takeOut(bodies);
    // Manifolds between held and immovable bodies stay as the last solve left them; as
    // solved, they keep the bodies resting next step (a manifold solved afresh takes a
    // new solver slot, whose Jacobians are made again).
    for (std::uint32_t index : held_) {
        for (std::uint32_t p : bodies[index].pairs) {
            if (bodies[other(pairs[p], index)].simulated) continue;
            for (ManifoldState &m : pairs[p].manifolds) {
                m.solverStep = context.stepCount;
                m.solverSlot = UINT32_MAX;
            }
        }
    }
    stats.heldBodies = static_cast<int>(held_.size());
}

bool Holding::markStill(const StepContext &context, const BodyStore &bodies, const PairCache &pairs) {
    const auto could = [&](std::uint32_t index) { return couldHold(bodies[index], pairs, context); };
    const auto first = std::find_if(bodies.simulated.begin(), bodies.simulated.end(), could);
    if (first == bodies.simulated.end()) return false;
    still_.assign(bodies.size(), 0);
    for (auto it = first; it != bodies.simulated.end(); ++it) still_[*it] = could(*it);
    // Each ring keeps the bodies whose every pair's other body the last one kept: a
    // moving kinematic body never, a static or sleeping one always.
    for (int ring = 0; ring < kRings; ++ring) {
        ring_ = still_;
        for (std::uint32_t index : bodies.simulated) {
            if (!ring_[index]) continue;
            for (std::uint32_t p : bodies[index].pairs) {
                const std::uint32_t o = other(pairs[p], index);
                if (bodies[o].moving || (bodies[o].simulated && !still_[o])) {
                    ring_[index] = 0;
                    break;
                }
            }
        }
        still_.swap(ring_);
    }
    return true;
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
