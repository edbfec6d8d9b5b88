#include "solver_schedule.h"

#include <algorithm>

namespace cyclone::detail {

void buildSchedule(const std::vector<SolverManifold> &manifolds, const std::vector<int> &order,
                   std::vector<SolverGroup> &groups, ScheduleScratch &scratch) {
    const int n = static_cast<int>(order.size());
    groups.clear();
    std::vector<char> &taken = scratch.taken;
    taken.assign(n, 0);
    // blockedFor[body] == i: the body is blocked for the group that starts at i (below).
    int bodies = 0;
    for (int index : order) bodies = std::max({bodies, manifolds[index].a + 1, manifolds[index].b + 1});
    std::vector<int> &blockedFor = scratch.blockedFor;
    blockedFor.assign(bodies, -1);
    for (int i = 0; i < n; ++i) {
        if (taken[i]) continue;
        taken[i] = 1;
        SolverGroup group;
        group.manifold[group.size++] = order[i];
        // The moving bodies of the manifolds a later one would have to move past to join
        // the group: the group's members and those still waiting between i and it.
        const auto block = [&](const SolverManifold &m) {
            blockedFor[m.a] = i;
            blockedFor[m.b] = i;
        };
        const auto isBlocked = [&](int body) { return body != 0 && blockedFor[body] == i; };
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
