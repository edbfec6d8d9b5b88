#include "solver/threads/carrier_threads.h"

#include <algorithm>

namespace cyclone::detail {
namespace {

int carriedBody(const SolverManifold &m) { return m.carrier == Carrier::A ? m.b : m.a; }
int carrierBody(const SolverManifold &m) { return m.carrier == Carrier::A ? m.a : m.b; }

// Waits until every carrier of run r that has a run of its own has finished it.
void awaitCarriers(const SolverManifolds &manifolds, const CarrierRuns &runs, const CarrierThreads &threads,
                   int r) {
    for (int k = runs.start[r]; k < runs.start[r + 1]; ++k) {
        const int carrier = carrierBody(manifolds[runs.manifolds[k]]);
        const int carrierRun = threads.runOf[carrier];
        if (carrierRun < 0) continue;
        threads.finished.await(static_cast<std::size_t>(carrierRun));
    }
}

// The end of the group of runs that starts at list[k]: runs of one level never carry each
// other, so up to four of them are swept side by side.
std::size_t groupEnd(const std::vector<int> &list, const CarrierThreads &threads, std::size_t k) {
    std::size_t end = k + 1;
    while (end < list.size() && end - k < kWideLanes && threads.runLevel[list[end]] == threads.runLevel[list[k]]) ++end;
    return end;
}

// Asks for the solver manifolds of runs list[k .. end), whole (the carrier pass reads
// nearly every line of them), so that they arrive while the group before them sweeps.
// Inlined: GCC takes a function that only prefetches for one without effects, and drops
// its calls.
CYCLONE_INLINE void prefetchRuns(const SolverManifolds &manifolds, const CarrierRuns &runs,
                                 const std::vector<int> &list, std::size_t k, std::size_t end) {
    constexpr std::size_t kLine = 64;
    for (; k < end; ++k) {
        for (int i = runs.start[list[k]]; i < runs.start[list[k] + 1]; ++i) {
            const char *m = reinterpret_cast<const char *>(&manifolds[runs.manifolds[i]]);
            for (std::size_t b = 0; b < sizeof(SolverManifold); b += kLine) __builtin_prefetch(m + b);
        }
    }
}

// Copies `from` into `to` sorted by key(r) in [0, keys), stably (a counting sort).
template <class Key>
void countingSort(CarrierThreads &threads, std::vector<int> &from, std::vector<int> &to, int keys, const Key &key) {
    std::vector<int> &count = threads.sortCount;
    count.assign(static_cast<std::size_t>(keys) + 1, 0);
    for (int r : from) ++count[key(r) + 1];
    for (int k = 0; k < keys; ++k) count[k + 1] += count[k];
    to.resize(from.size());
    for (int r : from) to[count[key(r)]++] = r;
}

// A group sweeps until its last run stops: the runs of a level are taken in the order of
// the sweeps they took in the last carrier pass, most first, so that a group's runs stop
// near one another (a run that swept long last pass tends to again; docs/solver.md, "How
// the passes are made fast", says what that saves). Any
// order of a level's runs gives the same numbers: no run reads or writes another of its
// level. `list` holds its runs level by level, and keeps that order.
void orderBySweeps(CarrierThreads &threads, std::vector<int> &list) {
    if (list.empty()) return;
    int most = 0;
    for (int r : list) most = std::max(most, threads.sweepsOf[threads.runBody[r]]);
    countingSort(threads, list, threads.sortScratch, most + 1,
                 [&](int r) { return most - threads.sweepsOf[threads.runBody[r]]; });
    countingSort(threads, threads.sortScratch, list, threads.runLevel[list.back()] + 1,
                 [&](int r) { return threads.runLevel[r]; });
}

}  // namespace

void buildCarrierThreads(const CarrierRuns &runs, const SolverManifolds &manifolds,
                       const std::vector<signed char> *side, int bodyCount, CarrierThreads &threads) {
    const int runCount = static_cast<int>(runs.start.size()) - 1;
    threads.runOf.assign(bodyCount, -1);
    threads.runLevel.resize(runCount);
    threads.runBody.resize(runCount);
    threads.sweepsOf.resize(bodyCount, 0);
    for (int l = 0; l + 1 < static_cast<int>(runs.levelStart.size()); ++l)
        for (int r = runs.levelStart[l]; r < runs.levelStart[l + 1]; ++r) threads.runLevel[r] = l;
    threads.share[0].clear();
    threads.share[1].clear();
    for (int r = 0; r < runCount; ++r) {
        const int body = carriedBody(manifolds[runs.manifolds[runs.start[r]]]);
        threads.runOf[body] = r;
        threads.runBody[r] = body;
        threads.share[side ? (*side)[body] : 0].push_back(r);
    }
    // The sort's keys: a run's sweeps (at most the stop's) and its level.
    const int levels = static_cast<int>(runs.levelStart.size()) - 1;
    threads.sortCount.reserve(static_cast<std::size_t>(std::max(carrierStop(levels).sweeps, levels)) + 2);
    for (std::vector<int> &list : threads.share) orderBySweeps(threads, list);
    threads.finished.reserve(static_cast<std::size_t>(runCount));
}

void solveCarrierShare(std::vector<SolverBody> &bodies, SolverManifolds &manifolds, CarrierRuns &runs,
                      CarrierThreads &threads, int share, bool reverse) {
    const std::vector<int> &list = threads.share[share];
    // Alone, a share holds every run, level by level: each run's carriers have finished
    // before it starts, and nothing need be waited for.
    const bool alone = threads.share[1].empty();
    std::size_t end = list.empty() ? 0 : groupEnd(list, threads, 0);
    for (std::size_t k = 0, next = 0; k < list.size(); k = end, end = next) {
        // The next group is found once: its runs are asked for now and swept next.
        next = end < list.size() ? groupEnd(list, threads, end) : end;
        prefetchRuns(manifolds, runs, list, end, next);
        if (!alone)
            for (std::size_t r = k; r < end; ++r) awaitCarriers(manifolds, runs, threads, list[r]);
        solveCarriedRuns(bodies, manifolds, runs, &list[k], static_cast<int>(end - k), reverse, threads.scratch[share]);
        for (std::size_t r = k; r < end; ++r) {
            threads.sweepsOf[threads.runBody[list[r]]] = threads.scratch[share].laneSweeps[r - k];
            threads.finished.finish(static_cast<std::size_t>(list[r]));
        }
    }
}

}  // namespace cyclone::detail
