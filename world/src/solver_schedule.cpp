#include "solver_schedule.h"

#include <algorithm>

namespace cyclone::detail {

void buildSchedule(const std::vector<SolverManifold> &manifolds, const std::vector<int> &order,
                   std::vector<SolverGroup> &groups, std::vector<char> &taken) {
    const int n = static_cast<int>(order.size());
    groups.clear();
    taken.assign(n, 0);
    for (int i = 0; i < n; ++i) {
        if (taken[i]) continue;
        taken[i] = 1;
        SolverGroup group;
        group.manifold[group.size++] = order[i];
        // The moving bodies of the manifolds a later one would have to move past to join
        // the group: the group's members and those still waiting between i and it.
        int blocked[2 * (kScheduleWindow + 1)];
        int blockedCount = 0;
        const auto block = [&](const SolverManifold &m) {
            if (m.a != 0) blocked[blockedCount++] = m.a;
            if (m.b != 0) blocked[blockedCount++] = m.b;
        };
        const auto isBlocked = [&](int body) {
            return body != 0 && std::find(blocked, blocked + blockedCount, body) != blocked + blockedCount;
        };
        block(manifolds[order[i]]);
        const int end = std::min(n, i + 1 + kScheduleWindow);
        for (int j = i + 1; j < end && group.size < kGroupSize; ++j) {
            if (taken[j]) continue;  // in an earlier group: solved before all of these
            const SolverManifold &m = manifolds[order[j]];
            if (!isBlocked(m.a) && !isBlocked(m.b)) {
                taken[j] = 1;
                group.manifold[group.size++] = order[j];
            }
            block(m);
        }
        groups.push_back(group);
    }
}

}  // namespace cyclone::detail
