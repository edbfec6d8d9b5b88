#include "solver/carriers.h"

#include <algorithm>
#include <limits>

namespace cyclone::detail {
namespace {

constexpr real kRestingCosine = 0.5;     // a normal within 60 degrees of up
constexpr real kStandingCosine = 0.866;  // a normal within 30 degrees of up
constexpr int kUnreached = std::numeric_limits<int>::max();

// The carrier pass's runs: each carried body's manifolds with its carriers, bodies by
// level (bottom up; all level 0 without `level`), then by their first such manifold in
// `order`, each body's manifolds in `order`; and the manifolds without a carrier, in
// `order`. Bucketed, not sorted: the bodies are met in the order of their first
// manifolds, and a stable count by level keeps that order.
void buildRuns(const SolverManifolds &manifolds, const std::vector<int> &order,
               const std::vector<int> *level, int bodyCount, CarrierScratch &scratch, CarrierRuns &runs) {
    const auto carried = [](const SolverManifold &m) { return m.carrier == Carrier::A ? m.b : m.a; };
    const auto levelOf = [&](int body) { return level ? (*level)[body] : 0; };
    // The carried bodies by first manifold, and how many manifolds each has.
    std::vector<int> &count = scratch.count;
    count.assign(bodyCount, 0);
    std::vector<int> &met = scratch.met;
    met.clear();
    runs.uncarried.clear();
    int levels = 0;
    for (int index : order) {
        const SolverManifold &m = manifolds[index];
        if (m.carrier == Carrier::None) {
            runs.uncarried.push_back(index);
            continue;
        }
        const int body = carried(m);
        if (count[body]++ == 0) {
            met.push_back(body);
            levels = std::max(levels, levelOf(body) + 1);
        }
    }
    // The bodies by level, each level's in the order met.
    std::vector<int> &levelStart = runs.levelStart;
    levelStart.assign(levels + 1, 0);
    for (int body : met) ++levelStart[levelOf(body) + 1];
    for (int l = 0; l < levels; ++l) levelStart[l + 1] += levelStart[l];
    std::vector<int> &bodies = scratch.bodies;
    bodies.resize(met.size());
    std::vector<int> &cursor = scratch.cursor;  // per level, then per body
    cursor.assign(levelStart.begin(), levelStart.end() - 1);
    for (int body : met) bodies[cursor[levelOf(body)]++] = body;
    // Each body's run: its manifolds in order.
    runs.start.resize(bodies.size() + 1);
    cursor.assign(bodyCount, 0);
    int next = 0;
    for (std::size_t r = 0; r < bodies.size(); ++r) {
        runs.start[r] = next;
        cursor[bodies[r]] = next;
        next += count[bodies[r]];
    }
    runs.start[bodies.size()] = next;
    runs.manifolds.resize(next);
    for (int index : order) {
        const SolverManifold &m = manifolds[index];
        if (m.carrier != Carrier::None) runs.manifolds[cursor[carried(m)]++] = index;
    }
    // Levels without a carried body have no runs: levelStart lists those that have.
    levelStart.erase(std::unique(levelStart.begin(), levelStart.end()), levelStart.end());
}

// Adjacency of the contact graph (counting sort by body), each entry marked when the
// neighbour stands on the body (the normal within 30 degrees of up `u`, the neighbour above):
// scratch.start, adjacent, carries.
void linkContacts(int bodyCount, const Vector3 &u, const SolverManifolds &manifolds,
                  CarrierScratch &scratch) {
    std::vector<int> &start = scratch.start;
    std::vector<int> &adjacent = scratch.adjacent;
    std::vector<char> &carries = scratch.carries;
    start.assign(bodyCount + 1, 0);
    for (const SolverManifold &m : manifolds) {
        ++start[m.a + 1];
        ++start[m.b + 1];
    }
    for (int k = 0; k < bodyCount; ++k) start[k + 1] += start[k];
    adjacent.resize(start[bodyCount]);
    carries.resize(start[bodyCount]);
    std::vector<int> &cursor = scratch.queue;  // reused below as the queue
    cursor.assign(start.begin(), start.end() - 1);
    for (const SolverManifold &m : manifolds) {
        const real rise = m.normal.dot(u);  // > 0: B lies above A
        carries[cursor[m.a]] = rise >= kStandingCosine;
        adjacent[cursor[m.a]++] = m.b;
        carries[cursor[m.b]] = rise <= -kStandingCosine;
        adjacent[cursor[m.b]++] = m.a;
    }
}

// Each body's level in scratch.level (scratch.start, adjacent and carries as linkContacts
// left them): entry 0 and the moving kinematic bodies, from firstKinematic on, are level 0.
void levelBodies(int bodyCount, int firstKinematic, CarrierScratch &scratch) {
    const std::vector<int> &start = scratch.start;
    const std::vector<int> &adjacent = scratch.adjacent;
    const std::vector<char> &carries = scratch.carries;
    // Levels, breadth first from the immovable bodies. First only up the contacts a body
    // stands on, so that a body's level counts the bodies under it (a box of a column
    // that touches a wall is not carried by the wall). A body on a steeper face would
    // slide off it at the default friction (0.6, tan 31 degrees): its other contacts hold
    // it too, and the carrier pass, which leaves out those with moving bodies, must not
    // carry it on that face alone. Such bodies, and those that stand on nothing reached,
    // get their levels in a second search over every contact, each from its lowest
    // neighbour, so that every touching body has a level (the carrier pass's runs are
    // ordered by it). docs/solver.md, "The carrier pass".
    std::vector<int> &level = scratch.level;
    level.assign(bodyCount, kUnreached);
    std::vector<int> &queue = scratch.queue;
    queue.clear();
    level[0] = 0;
    queue.push_back(0);
    for (int body = firstKinematic; body < bodyCount; ++body) {
        level[body] = 0;
        queue.push_back(body);
    }
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const int body = queue[head];
        for (int e = start[body]; e < start[body + 1]; ++e) {
            const int next = adjacent[e];
            if (level[next] != kUnreached || !carries[e]) continue;
            level[next] = level[body] + 1;
            queue.push_back(next);
        }
    }
    // The second search takes the bodies in the order of their levels: those of the
    // first (in `queue`, by level) merged with those it reaches (in `later`, by level).
    std::vector<int> &later = scratch.later;
    later.clear();
    for (std::size_t head = 0, next = 0; head < queue.size() || next < later.size();) {
        const bool first = next == later.size() || (head < queue.size() && level[queue[head]] <= level[later[next]]);
        const int body = first ? queue[head++] : later[next++];
        for (int e = start[body]; e < start[body + 1]; ++e) {
            const int neighbour = adjacent[e];
            if (level[neighbour] != kUnreached) continue;
            level[neighbour] = level[body] + 1;
            later.push_back(neighbour);
        }
    }
}

}  // namespace

void assignCarriers(int bodyCount, int firstKinematic, const Vector3 &up, SolverManifolds &manifolds,
                   const std::vector<int> &order, CarrierScratch &scratch, CarrierRuns &runs) {
    // Entry 0 (static or asleep) and the moving kinematic bodies are immovable anyway.
    const auto immovable = [&](int body) { return body == 0 || body >= firstKinematic; };
    for (SolverManifold &m : manifolds) {
        m.carrier = Carrier::None;
        if (immovable(m.a)) m.carrier = Carrier::A;
        if (immovable(m.b)) m.carrier = Carrier::B;
    }
    if (up.isZero(0) || manifolds.empty()) {
        buildRuns(manifolds, order, nullptr, bodyCount, scratch, runs);
        return;
    }
    const Vector3 u = up.normalized();
    linkContacts(bodyCount, u, manifolds, scratch);
    levelBodies(bodyCount, firstKinematic, scratch);
    const std::vector<int> &level = scratch.level;
    for (SolverManifold &m : manifolds) {
        if (immovable(m.a) || immovable(m.b)) continue;
        const int la = level[m.a];
        const int lb = level[m.b];
        if (la == lb || la == kUnreached || lb == kUnreached) continue;
        const real rise = m.normal.dot(u);  // > 0: B lies above A
        if (la < lb && rise >= kRestingCosine) m.carrier = Carrier::A;
        else if (lb < la && rise <= -kRestingCosine) m.carrier = Carrier::B;
    }
    buildRuns(manifolds, order, &level, bodyCount, scratch, runs);
}

}  // namespace cyclone::detail
