#include "contacts/pre_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contacts/pair_cache.h"
#include "world/body_store.h"
#include "world/validation.h"

namespace cyclone::detail {

static_assert(Manifold::kMaxPoints <= kMaxContactPoints, "PreSolveContact holds every point of a manifold");

namespace {

// The contact as the listener sees it, set up from the materials and the built-in rules.
PreSolveContact describe(const BodyStore &bodies, const PairState &pair, const ManifoldState &m) {
    const BodyRecord &a = bodies[pair.a];
    const BodyRecord &b = bodies[pair.b];
    PreSolveContact c;
    c.a = bodies.idOf(pair.a);
    c.b = bodies.idOf(pair.b);
    c.normal = m.normal;
    c.pointCount = m.count;
    for (int i = 0; i < m.count; ++i) {
        const PersistentPoint &p = m.points[i];
        c.points[i] = 0.5 * (a.body.getPointInWorldSpace(p.localA) + b.body.getPointInWorldSpace(p.localB));
        c.depths[i] = p.depth;
    }
    c.friction = std::sqrt(a.material.friction * b.material.friction);
    c.restitution = std::max(a.material.restitution, b.material.restitution);
    c.surfaceVelocity = b.body.getOrientation() * b.surfaceVelocity - a.body.getOrientation() * a.surfaceVelocity;
    return c;
}

void requireListenerValues(const PreSolveContact &c) {
    static const char *function = "ContactListener::preSolve";
    if (!(c.friction >= 0) || !std::isfinite(c.friction))
        refuse(function, "friction", "must be finite and >= 0, got " + show(c.friction));
    if (!(c.restitution >= 0 && c.restitution <= 1))
        refuse(function, "restitution", "must be in [0, 1], got " + show(c.restitution));
    requireFinite(function, "surfaceVelocity", c.surfaceVelocity);
}

}  // namespace

bool PreSolve::active(const BodyStore &bodies) const { return listener || bodies.ruledCount > 0; }

void PreSolve::skip() {
    ran_ = false;
    overrides_.clear();
    disabledPairs_.clear();
    oneWay_.clear();
    oneWayBefore_.clear();
}

bool PreSolve::disabled(std::uint32_t pair) const {
    return std::binary_search(disabledPairs_.begin(), disabledPairs_.end(), pair);
}

// Whether the one-way bodies of the pair let its manifold be solved (see the design note),
// recording the pair's decision for the next step.
bool PreSolve::oneWayAllows(const BodyStore &bodies, const PairCache &pairs, std::uint32_t p,
                            const ManifoldRef &ref) {
    const PairState &pair = pairs[p];
    const OneWayPair key{pair.a, pair.b, false};
    const auto before = std::lower_bound(oneWayBefore_.begin(), oneWayBefore_.end(), key);
    bool passing;
    if (before != oneWayBefore_.end() && before->a == pair.a && before->b == pair.b) {
        passing = before->passing;
    } else {
        const ManifoldState &m = pairs[ref.pair].manifolds[ref.index];
        real deepest = -std::numeric_limits<real>::infinity();
        for (int i = 0; i < m.count; ++i) deepest = std::max(deepest, m.points[i].depth);
        passing = deepest > kOneWayEntryDepth;
        for (const std::uint32_t index : {pair.a, pair.b}) {
            const BodyRecord &r = bodies[index];
            if (r.oneWay.isZero(0)) continue;
            const Vector3 away = index == pair.a ? m.normal : Vector3(-m.normal);  // from it to the other body
            if (!((r.body.getOrientation() * r.oneWay).dot(away) >= kOneWayCosine)) passing = true;
        }
    }
    oneWay_.push_back({pair.a, pair.b, passing});
    return !passing;
}

void PreSolve::run(const BodyStore &bodies, const PairCache &pairs, std::vector<ManifoldKey> &keys) {
    ran_ = true;
    overrides_.clear();
    disabledPairs_.clear();
    oneWay_.clear();
    std::size_t kept = 0;
    for (const ManifoldKey &key : keys) {
        const std::uint32_t p = key.manifold.pair;
        const PairState &pair = pairs[p];
        const ManifoldState &m = pairs[p].manifolds[key.manifold.index];
        PreSolveContact contact = describe(bodies, pair, m);
        if (!bodies[pair.a].oneWay.isZero(0) || !bodies[pair.b].oneWay.isZero(0))
            contact.enabled = oneWayAllows(bodies, pairs, p, key.manifold);
        if (listener) {
            listener->preSolve(contact);
            requireListenerValues(contact);
        }
        if (!contact.enabled) {
            disabledPairs_.push_back(p);
            continue;
        }
        keys[kept++] = key;
        overrides_.push_back({contact.friction, contact.restitution, contact.surfaceVelocity});
    }
    keys.resize(kept);
    std::sort(disabledPairs_.begin(), disabledPairs_.end());
    disabledPairs_.erase(std::unique(disabledPairs_.begin(), disabledPairs_.end()), disabledPairs_.end());
    // A pair with several manifolds passes if one of them does (std::sort: a stable sort
    // would allocate every step).
    std::sort(oneWay_.begin(), oneWay_.end(), [](const OneWayPair &x, const OneWayPair &y) {
        return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.passing > y.passing;
    });
    oneWay_.erase(std::unique(oneWay_.begin(), oneWay_.end(),
                              [](const OneWayPair &x, const OneWayPair &y) { return x.a == y.a && x.b == y.b; }),
                  oneWay_.end());
    oneWayBefore_.swap(oneWay_);
}

}  // namespace cyclone::detail
