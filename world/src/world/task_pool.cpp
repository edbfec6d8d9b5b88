#include "world/task_pool.h"

#include <chrono>

namespace cyclone::detail {
namespace {

// How long an idle worker polls for the next job before it blocks: longer than the gaps
// between the jobs of one step, far shorter than the gap between a game's frames.
constexpr std::chrono::microseconds kSpinTime(200);

bool isOpen(std::uint64_t generation) { return (generation & 1) != 0; }

}  // namespace

TaskPool::TaskPool(int threads) {
    for (int k = 1; k < threads; ++k) workers_.emplace_back([this, k] { workerLoop(k); });
}

TaskPool::~TaskPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wakeUp_.notify_all();
    for (std::thread &worker : workers_) worker.join();
}

// A job is opened, run, then closed; the caller waits until every worker that joined it
// has left before the next job's fields are written. A worker joins, then checks that
// the job it saw is still open: either the caller's wait sees it inside, or it sees the
// job closed and leaves without touching it.
void TaskPool::runJob(int count, Call call, const void *context) {
    call_ = call;
    context_ = context;
    count_ = count;
    next_.store(0);
    finished_.store(0);
    {
        std::lock_guard<std::mutex> lock(mutex_);  // a worker about to block cannot miss it
        generation_.fetch_add(1);                  // open
    }
    wakeUp_.notify_all();
    takeTasks(0);
    waitUntil([&] { return finished_.load() >= count; });
    generation_.fetch_add(1);  // closed
    waitUntil([&] { return joined_.load() == 0; });
}

void TaskPool::takeTasks(int thread) {
    for (;;) {
        const int i = next_.fetch_add(1);
        if (i >= count_) return;
        call_(context_, i, thread);
        finished_.fetch_add(1);
    }
}

void TaskPool::workerLoop(int thread) {
    std::uint64_t seen = 0;
    const auto fresh = [&](std::uint64_t g) { return isOpen(g) && g != seen; };
    for (;;) {
        // Poll, then block, until a job this worker has not seen opens.
        const auto until = std::chrono::steady_clock::now() + kSpinTime;
        for (int polls = 0; !fresh(generation_.load()) && !stopping_.load(); ++polls) {
            if ((polls & 63) == 63 && std::chrono::steady_clock::now() > until) {
                std::unique_lock<std::mutex> lock(mutex_);
                wakeUp_.wait(lock, [&] { return fresh(generation_.load()) || stopping_.load(); });
            }
            cpuRelax();
        }
        if (stopping_.load()) return;
        // The job seen open may have closed since: joining a closed job, this worker
        // could read the next job's fields while the caller writes them.
        const std::uint64_t current = generation_.load();
        if (!isOpen(current)) continue;
        seen = current;
        joined_.fetch_add(1);
        if (generation_.load() == seen) takeTasks(thread);
        joined_.fetch_sub(1);
    }
}

}  // namespace cyclone::detail
