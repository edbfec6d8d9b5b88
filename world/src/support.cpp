#include "support.h"

#include <algorithm>
#include <limits>

namespace cyclone::detail {
namespace {

// The support pass's runs: each carried body's manifolds with its carriers, bodies by
// level (bottom up; all level 0 without `level`), then by their first such manifold in
// `order`.
void buildRuns(const std::vector<SolverManifold> &manifolds, const std::vector<int> &order,
               const std::vector<int> *level, int bodyCount, SupportScratch &scratch, SupportRuns &runs) {
    const auto carried = [](const SolverManifold &m) { return m.support == kASupportsB ? m.b : m.a; };
    std::vector<int> &first = scratch.first;
    first.assign(bodyCount, std::numeric_limits<int>::max());
    std::vector<SupportScratch::Key> &keys = scratch.keys;
    keys.clear();
    for (int rank = 0; rank < static_cast<int>(order.size()); ++rank) {
        const SolverManifold &m = manifolds[order[rank]];
        if (m.support == kNoSupport) continue;
        const int body = carried(m);
        first[body] = std::min(first[body], rank);
        keys.push_back({level ? (*level)[body] : 0, body, rank});
    }
    for (SupportScratch::Key &key : keys) key.body = first[key.body];  // group by first manifold
    std::sort(keys.begin(), keys.end(), [](const SupportScratch::Key &x, const SupportScratch::Key &y) {
        if (x.level != y.level) return x.level < y.level;
        if (x.body != y.body) return x.body < y.body;
        return x.manifold < y.manifold;
    });
    runs.start.clear();
    runs.levelStart.clear();
    runs.manifolds.clear();
    for (std::size_t k = 0; k < keys.size(); ++k) {
        if (k == 0 || keys[k].body != keys[k - 1].body) {
            if (k == 0 || keys[k].level != keys[k - 1].level)
                runs.levelStart.push_back(static_cast<int>(runs.start.size()));
            runs.start.push_back(static_cast<int>(k));
        }
        runs.manifolds.push_back(order[keys[k].manifold]);
    }
    runs.levelStart.push_back(static_cast<int>(runs.start.size()));
    runs.start.push_back(static_cast<int>(keys.size()));
}

}  // namespace

void assignSupport(int bodyCount, const Vector3 &up, std::vector<SolverManifold> &manifolds,
                   const std::vector<int> &order, SupportScratch &scratch, SupportRuns &runs) {
    for (SolverManifold &m : manifolds) {
        m.support = kNoSupport;
        if (m.a == 0) m.support = kASupportsB;  // static or asleep: immovable anyway
        if (m.b == 0) m.support = kBSupportsA;
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

    // Breadth first from the immovable body.
    constexpr int kUnreached = std::numeric_limits<int>::max();
    std::vector<int> &level = scratch.level;
    level.assign(bodyCount, kUnreached);
    std::vector<int> &queue = scratch.queue;
    queue.clear();
    level[0] = 0;
    queue.push_back(0);
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
        if (m.a == 0 || m.b == 0) continue;
        const int la = level[m.a];
        const int lb = level[m.b];
        if (la == lb || la == kUnreached || lb == kUnreached) continue;
        const real rise = m.normal.dot(u);  // > 0: B lies above A
        if (la < lb && rise >= kRestingCosine) m.support = kASupportsB;
        else if (lb < la && rise <= -kRestingCosine) m.support = kBSupportsA;
    }
    buildRuns(manifolds, order, &level, bodyCount, scratch, runs);
}

}  // namespace cyclone::detail
