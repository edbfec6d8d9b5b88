#include "solver/schedule.h"

#include <algorithm>

namespace cyclone::detail {
namespace {

// Groups the manifolds listed in `order`. A manifold joins the group that starts at
// order[i] when it shares no moving body with the group's members, nor with a manifold it
// would move past (one still waiting between i and it), unless `passes(lower, upper)`
// allows it to pass that one: `lower` is the waiting manifold, `upper` the joining one.
// Rewrites `order` as the groups list it.
template <class Passes>
void schedule(const SolverManifolds &manifolds, std::vector<int> &order, std::vector<SolverGroup> &groups,
              ScheduleScratch &scratch, const Passes &passes) {
    const int n = static_cast<int>(order.size());
    groups.clear();
    std::vector<char> &taken = scratch.taken;
    taken.assign(n, 0);
    int bodies = 0;
    for (int index : order) bodies = std::max({bodies, manifolds[index].a + 1, manifolds[index].b + 1});
    // joinedFor[body] == i: a member of the group that starts at i moves the body.
    // waitingFor[body] == i: a manifold passed over while filling that group moves it;
    // firstWaiting[body] is the first such (in `order`).
    std::vector<int> &joinedFor = scratch.joinedFor;
    std::vector<int> &waitingFor = scratch.waitingFor;
    std::vector<int> &firstWaiting = scratch.firstWaiting;
    joinedFor.assign(bodies, -1);
    waitingFor.assign(bodies, -1);
    firstWaiting.resize(bodies);
    for (int i = 0; i < n; ++i) {
        if (taken[i]) continue;
        taken[i] = 1;
        SolverGroup group;
        group.manifold[group.size++] = order[i];
        const auto join = [&](const SolverManifold &m) {
            joinedFor[m.a] = i;
            joinedFor[m.b] = i;
        };
        const auto wait = [&](const SolverManifold &m, int index) {
            for (int body : {m.a, m.b}) {
                if (waitingFor[body] == i) continue;
                waitingFor[body] = i;
                firstWaiting[body] = index;
            }
        };
        const auto unblocked = [&](int body, int index) {
            if (body == 0) return true;  // the static world: never moved
            if (joinedFor[body] == i) return false;
            return waitingFor[body] != i || passes(firstWaiting[body], index);
        };
        join(manifolds[order[i]]);
        const int end = std::min(n, i + 1 + kScheduleWindow);
        for (int j = i + 1; j < end && group.size < kGroupSize; ++j) {
            if (taken[j]) continue;  // in an earlier group: solved before all of these
            const SolverManifold &m = manifolds[order[j]];
            if (unblocked(m.a, order[j]) && unblocked(m.b, order[j])) {
                taken[j] = 1;
                group.manifold[group.size++] = order[j];
                join(m);
            } else {
                wait(m, order[j]);
            }
        }
        groups.push_back(group);
    }
    order.clear();
    for (const SolverGroup &g : groups) order.insert(order.end(), g.manifold, g.manifold + g.size);
}

}  // namespace

void buildSchedule(const SolverManifolds &manifolds, std::vector<int> &order,
                   std::vector<SolverGroup> &groups, ScheduleScratch &scratch) {
    schedule(manifolds, order, groups, scratch, [](int, int) { return false; });
}

void buildLevelSchedule(const SolverManifolds &manifolds, const std::vector<real> &heights,
                        std::vector<int> &order, std::vector<SolverGroup> &groups, ScheduleScratch &scratch) {
    // A static body's side sits at -inf (contactHeight, constraint_builder.cpp): level
    // with nothing, as the difference is then infinite or NaN.
    schedule(manifolds, order, groups, scratch,
             [&](int lower, int upper) { return heights[upper] - heights[lower] <= kLevelBand; });
}

}  // namespace cyclone::detail
