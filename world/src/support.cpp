#include "support.h"

#include <algorithm>
#include <limits>

namespace cyclone::detail {

void assignSupport(int bodyCount, const Vector3 &up, std::vector<SolverManifold> &manifolds,
                   SupportScratch &scratch) {
    for (SolverManifold &m : manifolds) {
        m.support = kNoSupport;
        if (m.a == 0) m.support = kASupportsB;  // static or asleep: immovable anyway
        if (m.b == 0) m.support = kBSupportsA;
    }
    if (up.isZero(0) || manifolds.empty()) return;
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
}

}  // namespace cyclone::detail
