#include "solver/carriers.h"

#include <algorithm>
#include <limits>

namespace cyclone::detail {
namespace {

// The carrier pass's runs: each carried body's manifolds with its carriers, bodies by
// level (bottom up; all level 0 without `level`), then by their first such manifold in
// `order`, each body's manifolds in `order`. Bucketed, not sorted: the bodies are met in
// the order of their first manifolds, and a stable count by level keeps that order.
void buildRuns(const std::vector<SolverManifold> &manifolds, const std::vector<int> &order,
               const std::vector<int> *level, int bodyCount, CarrierScratch &scratch, CarrierRuns &runs) {
    const auto carried = [](const SolverManifold &m) { return m.carrier == Carrier::A ? m.b : m.a; };
    const auto levelOf = [&](int body) { return level ? (*level)[body] : 0; };
    // The carried bodies by first manifold, and how many manifolds each has.
    std::vector<int> &count = scratch.count;
    count.assign(bodyCount, 0);
    std::vector<int> &met = scratch.met;
    met.clear();
    int levels = 0;
    for (int index : order) {
        const SolverManifold &m = manifolds[index];
        if (m.carrier == Carrier::None) continue;
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

}  // namespace

void assignCarriers(int bodyCount, int firstKinematic, const Vector3 &up, std::vector<SolverManifold> &manifolds,
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
    constexpr real kRestingCosine = 0.5;  // normal within 60 degrees of up

    // Adjacency of the contact graph (counting sort by body).
    std::vector<int> &start = scratch.start;
    std::vector<int> &adjacent = scratch.adjacent;
    start.assign(bodyCount + 1, 0);
    for (const SolverManifold &m : manifolds) {
        ++start[m.a + 1];
        ++start[m.b + 1];
    }
    for (int k = 0; k < bodyCount; ++k) start[k + 1] += start[k];
    adjacent.resize(start[bodyCount]);
    std::vector<int> &cursor = scratch.queue;  // reused below as the queue
    cursor.assign(start.begin(), start.end() - 1);
    for (const SolverManifold &m : manifolds) {
        adjacent[cursor[m.a]++] = m.b;
        adjacent[cursor[m.b]++] = m.a;
    }

    // Breadth first from the immovable bodies.
    constexpr int kUnreached = std::numeric_limits<int>::max();
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
            if (level[next] != kUnreached) continue;
            level[next] = level[body] + 1;
            queue.push_back(next);
        }
    }

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
