#include "dynamics/islands.h"

#include <algorithm>
#include <numeric>

#include "contacts/pair_cache.h"
#include "dynamics/springs.h"
#include "dynamics/union_find.h"
#include "joints/joint_set.h"
#include "solver/contact_solver.h"
#include "world/body_store.h"
#include "world/workers.h"

namespace cyclone::detail {

void Islands::build(BodyStore &bodies, const SolverManifolds &manifolds, const SpringSet &springs,
                    const JointSet &joints, const std::vector<std::uint32_t> &held, const PairCache &pairs,
                    Workers &workers, StepStats &stats) {
    const int simulated = static_cast<int>(bodies.simulated.size());
    const int n = simulated + static_cast<int>(held.size());
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
    const auto unite = [&](int x, int y) { uniteSets(parent_, x, y); };
    // What joins what is read on the threads (the manifolds' bodies, the held bodies'
    // pairs: memory far apart), then joined in that order on this one.
    // Static and kinematic bodies (entry 0, entries past the simulated) join no island.
    links_.resize(manifolds.size());
    workers.forEach(manifolds.size(), [&](std::size_t s) {
        const SolverManifold &m = manifolds[s];
        const bool joins = m.a > 0 && m.b > 0 && m.a <= simulated && m.b <= simulated;
        links_[s] = joins ? std::pair(m.a - 1, m.b - 1) : std::pair(-1, -1);
    });
    for (const auto &[x, y] : links_)
        if (x >= 0) unite(x, y);
    // A held body joins the bodies it touches, held or simulated (entry simulated + its
    // place in `held`, kept in BodyRecord::island until the islands are numbered).
    for (std::size_t k = 0; k < held.size(); ++k) bodies[held[k]].island = simulated + static_cast<int>(k);
    const std::size_t chunks = Workers::chunksOf(held.size());
    heldLinks_.start(workers.threads(), chunks);
    workers.forEachChunkOnThreads(held.size(), [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
        std::vector<std::pair<int, int>> &found = heldLinks_.open(chunk, thread);
        for (std::size_t k = begin; k < end; ++k) {
            const int entry = simulated + static_cast<int>(k);
            for (std::uint32_t p : bodies[held[k]].pairs) {
                if (!pairs[p].touching()) continue;
                const BodyRecord &o = bodies[pairs[p].a == held[k] ? pairs[p].b : pairs[p].a];
                if (o.simulated) found.emplace_back(entry, o.solverIndex - 1);
                else if (o.held) found.emplace_back(entry, o.island);
            }
        }
        heldLinks_.close(chunk);
    });
    heldLinks_.finish();
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
        for (const auto &[x, y] : heldLinks_.items(chunk)) unite(x, y);
    for (const SpringRecord &s : springs) {
        if (!s.alive || !s.settings.b) continue;
        const BodyRecord &a = bodies[s.settings.a.index];
        const BodyRecord &b = bodies[s.settings.b->index];
        if (a.simulated && b.simulated) unite(a.solverIndex - 1, b.solverIndex - 1);
    }
    for (const JointRecord &j : joints.records) {
        if (!j.alive || !j.settings.b) continue;
        const BodyRecord &a = bodies[j.settings.a.index];
        const BodyRecord &b = bodies[j.settings.b->index];
        if (a.simulated && b.simulated) unite(a.solverIndex - 1, b.solverIndex - 1);
    }
    // Islands are numbered in the order of their first members. A parent never comes
    // after its child (unite keeps the smaller root), so in one walk each entry's parent
    // already holds its island, stored as ~island to tell it from a parent's index.
    int islands = 0;
    for (int k = 0; k < n; ++k) {
        const int up = parent_[k];
        parent_[k] = up == k ? ~islands++ : parent_[up];
    }
    // Lay the members out island by island. start_ is the cursor, which leaves each
    // island's entry at the next island's start: shifted back at the end.
    start_.assign(islands + 1, 0);
    const auto body = [&](int k) { return k < simulated ? bodies.simulated[k] : held[k - simulated]; };
    for (int k = 0; k < n; ++k) {
        const int island = ~parent_[k];
        bodies[body(k)].island = island;
        ++start_[island + 1];
    }
    for (int i = 0; i < islands; ++i) start_[i + 1] += start_[i];
    members_.resize(n);
    for (int k = 0; k < n; ++k) members_[start_[~parent_[k]]++] = body(k);
    for (int i = islands - 1; i > 0; --i) start_[i] = start_[i - 1];
    start_[0] = 0;
    stats.islands = islands;
}

const std::vector<int> &Islands::still(const WorldSettings &settings, const BodyStore &bodies) {
    still_.clear();
    if (!settings.sleep) return still_;
    const int islands = static_cast<int>(start_.size()) - 1;
    for (int i = 0; i < islands; ++i) {
        const int start = start_[i];
        const int end = start_[i + 1];
        bool still = true;
        for (int k = start; k < end && still; ++k) {
            const BodyRecord &r = bodies[members_[k]];
            still = !r.isolated && r.body.getAwake() && r.body.getCanSleep() &&
                    r.body.getSleepAverage() < r.body.getSleepEpsilon();
        }
        if (still) still_.push_back(i);
    }
    return still_;
}

}  // namespace cyclone::detail
