#include "solver/threads/carrier_threads.h"

#include "world/task_pool.h"

namespace cyclone::detail {
namespace {

int carriedBody(const SolverManifold &m) { return m.carrier == Carrier::A ? m.b : m.a; }
int carrierBody(const SolverManifold &m) { return m.carrier == Carrier::A ? m.a : m.b; }

// Waits until every carrier of run r that has a run of its own has finished it.
void awaitCarriers(const std::vector<SolverManifold> &manifolds, const CarrierRuns &runs, const CarrierThreads &threads,
                   int r) {
    for (int k = runs.start[r]; k < runs.start[r + 1]; ++k) {
        const int carrier = carrierBody(manifolds[runs.manifolds[k]]);
        const int carrierRun = threads.runOf[carrier];
        if (carrierRun < 0) continue;
        waitUntil([&] { return threads.finished[carrierRun].load(std::memory_order_acquire) == threads.pass; });
    }
}

}  // namespace

void buildCarrierThreads(const CarrierRuns &runs, const std::vector<SolverManifold> &manifolds,
                       const std::vector<signed char> *side, int bodyCount, CarrierThreads &threads) {
    const int runCount = static_cast<int>(runs.start.size()) - 1;
    threads.runOf.assign(bodyCount, -1);
    threads.runLevel.resize(runCount);
    for (int l = 0; l + 1 < static_cast<int>(runs.levelStart.size()); ++l)
        for (int r = runs.levelStart[l]; r < runs.levelStart[l + 1]; ++r) threads.runLevel[r] = l;
    threads.share[0].clear();
    threads.share[1].clear();
    for (int r = 0; r < runCount; ++r) {
        const int body = carriedBody(manifolds[runs.manifolds[runs.start[r]]]);
        threads.runOf[body] = r;
        threads.share[side ? (*side)[body] : 0].push_back(r);
    }
    if (static_cast<std::size_t>(runCount) > threads.capacity) {
        threads.capacity = static_cast<std::size_t>(runCount) * 2;
        threads.finished = std::make_unique<std::atomic<std::uint32_t>[]>(threads.capacity);
        threads.pass = 0;
    }
}

void beginCarrierPass(CarrierThreads &threads) {
    if (++threads.pass == 0) {  // wrapped: no flag may look finished in this pass
        for (std::size_t r = 0; r < threads.capacity; ++r) threads.finished[r].store(0, std::memory_order_relaxed);
        threads.pass = 1;
    }
}

void solveCarrierShare(std::vector<SolverBody> &bodies, std::vector<SolverManifold> &manifolds, CarrierRuns &runs,
                      CarrierThreads &threads, int share, bool reverse) {
    const std::vector<int> &list = threads.share[share];
    for (std::size_t k = 0; k < list.size();) {
        // Runs of one level never carry each other: up to four are swept side by side.
        std::size_t end = k + 1;
        while (end < list.size() && end - k < kWideLanes && threads.runLevel[list[end]] == threads.runLevel[list[k]]) ++end;
        for (std::size_t r = k; r < end; ++r) awaitCarriers(manifolds, runs, threads, list[r]);
        solveCarriedRuns(bodies, manifolds, runs, &list[k], static_cast<int>(end - k), reverse, threads.scratch[share]);
        for (std::size_t r = k; r < end; ++r) threads.finished[list[r]].store(threads.pass, std::memory_order_release);
        k = end;
    }
}

}  // namespace cyclone::detail
