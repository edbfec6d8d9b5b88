#include "solver_schedule.h"

#include <algorithm>

namespace cyclone::detail {
namespace {

// True when the two manifolds share no moving body (solver body 0 is immovable).
bool independent(const SolverManifold &x, const SolverManifold &y) {
    const auto shares = [&](int body) { return body != 0 && (body == y.a || body == y.b); };
    return !shares(x.a) && !shares(x.b);
}

}  // namespace

void buildSchedule(const std::vector<SolverManifold> &manifolds, const std::vector<int> &order,
                   std::vector<SolverGroup> &groups, std::vector<char> &taken) {
    const int n = static_cast<int>(order.size());
    groups.clear();
    taken.assign(n, 0);
    const auto at = [&](int k) -> const SolverManifold & { return manifolds[order[k]]; };
    for (int i = 0; i < n; ++i) {
        if (taken[i]) continue;
        taken[i] = 1;
        SolverGroup group;
        int members[kGroupSize];  // positions in `order` of the group's manifolds
        members[group.size] = i;
        group.manifold[group.size++] = order[i];
        const int end = std::min(n, i + 1 + kScheduleWindow);
        for (int j = i + 1; j < end && group.size < kGroupSize; ++j) {
            if (taken[j]) continue;
            // j may move up to the group only past manifolds it commutes with: those
            // still waiting between i and j, and the group's members.
            bool movable = true;
            for (int k = i; k < j && movable; ++k)
                movable = (taken[k] && !std::count(members, members + group.size, k)) || independent(at(k), at(j));
            if (!movable) continue;
            taken[j] = 1;
            members[group.size] = j;
            group.manifold[group.size++] = order[j];
        }
        groups.push_back(group);
    }
}

}  // namespace cyclone::detail
