#include "solver/threads/carrier_threads.h"

#include "world/task_pool.h"

namespace cyclone::detail {
namespace {

int carriedBody(const SolverManifold &m) { return m.support == kASupportsB ? m.b : m.a; }
int carrierBody(const SolverManifold &m) { return m.support == kASupportsB ? m.a : m.b; }

// Waits until every carrier of run r that has a run of its own has finished it.
void awaitCarriers(const std::vector<SolverManifold> &manifolds, const CarrierRuns &runs, const CarrierThreads &lanes,
                   int r) {
    for (int k = runs.start[r]; k < runs.start[r + 1]; ++k) {
        const int carrier = carrierBody(manifolds[runs.manifolds[k]]);
        const int carrierRun = lanes.runOf[carrier];
        if (carrierRun < 0) continue;
        while (lanes.finished[carrierRun].load(std::memory_order_acquire) != lanes.pass) cpuRelax();
    }
}

}  // namespace

void buildCarrierThreads(const CarrierRuns &runs, const std::vector<SolverManifold> &manifolds,
                       const std::vector<signed char> *side, int bodyCount, CarrierThreads &lanes) {
    const int runCount = static_cast<int>(runs.start.size()) - 1;
    lanes.runOf.assign(bodyCount, -1);
    lanes.runLevel.resize(runCount);
    for (int l = 0; l + 1 < static_cast<int>(runs.levelStart.size()); ++l)
        for (int r = runs.levelStart[l]; r < runs.levelStart[l + 1]; ++r) lanes.runLevel[r] = l;
    lanes.lane[0].clear();
    lanes.lane[1].clear();
    for (int r = 0; r < runCount; ++r) {
        const int body = carriedBody(manifolds[runs.manifolds[runs.start[r]]]);
        lanes.runOf[body] = r;
        lanes.lane[side ? (*side)[body] : 0].push_back(r);
    }
    if (static_cast<std::size_t>(runCount) > lanes.capacity) {
        lanes.capacity = static_cast<std::size_t>(runCount) * 2;
        lanes.finished = std::make_unique<std::atomic<std::uint32_t>[]>(lanes.capacity);
        lanes.pass = 0;
    }
}

void beginCarrierPass(CarrierThreads &lanes) {
    if (++lanes.pass == 0) {  // wrapped: no flag may look finished in this pass
        for (std::size_t r = 0; r < lanes.capacity; ++r) lanes.finished[r].store(0, std::memory_order_relaxed);
        lanes.pass = 1;
    }
}

void solveCarrierShare(std::vector<SolverBody> &bodies, std::vector<SolverManifold> &manifolds, CarrierRuns &runs,
                      CarrierThreads &lanes, int lane, bool reverse) {
    const std::vector<int> &list = lanes.lane[lane];
    for (std::size_t k = 0; k < list.size();) {
        // Runs of one level never carry each other: up to four are swept side by side.
        std::size_t end = k + 1;
        while (end < list.size() && end - k < kWideLanes && lanes.runLevel[list[end]] == lanes.runLevel[list[k]]) ++end;
        for (std::size_t r = k; r < end; ++r) awaitCarriers(manifolds, runs, lanes, list[r]);
        solveCarriedRuns(bodies, manifolds, runs, &list[k], static_cast<int>(end - k), reverse, lanes.scratch[lane]);
        for (std::size_t r = k; r < end; ++r) lanes.finished[list[r]].store(lanes.pass, std::memory_order_release);
        k = end;
    }
}

}  // namespace cyclone::detail
