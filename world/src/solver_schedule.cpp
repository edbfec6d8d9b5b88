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

void buildSchedule(const std::vector<SolverManifold> &manifolds, std::vector<SolverGroup> &groups,
                   std::vector<char> &taken) {
    const int n = static_cast<int>(manifolds.size());
    groups.clear();
    taken.assign(n, 0);
    for (int i = 0; i < n; ++i) {
        if (taken[i]) continue;
        taken[i] = 1;
        SolverGroup group;
        group.manifold[group.size++] = i;
        const int end = std::min(n, i + 1 + kScheduleWindow);
        for (int j = i + 1; j < end && group.size < kGroupSize; ++j) {
            if (taken[j]) continue;
            // j may move up to the group only past manifolds it commutes with: those
            // still waiting between i and j, and the group's members.
            bool movable = true;
            for (int k = i; k < j && movable; ++k)
                movable = (taken[k] && !std::count(group.manifold, group.manifold + group.size, k)) ||
                          independent(manifolds[k], manifolds[j]);
            if (!movable) continue;
            taken[j] = 1;
            group.manifold[group.size++] = j;
        }
        groups.push_back(group);
    }
}

}  // namespace cyclone::detail
