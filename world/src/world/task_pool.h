// Worker threads that run a step's independent tasks together with the stepping thread.
//
// Design note. A step hands the pool a few dozen small jobs (a solver pass over half the
// contacts, one level of the carrier pass), each a fraction of a millisecond. Waking a
// sleeping thread costs tens of microseconds, so between jobs the workers spin for a
// while before they block. Tasks of a job must be independent (no task reads what
// another writes): which thread runs which task then changes nothing in the results, and
// a world gives the same numbers whatever its thread count. Tasks must not throw.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace cyclone::detail {

/// Tells the CPU that this thread is spinning on a flag another thread will set.
inline void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
}

/// Polls until done() holds: spinning for a few microseconds, then giving up the core
/// between polls. With more runnable threads than cores (other programs, or more
/// threads than cores) the thread waited for may be the one off its core: spinning on
/// would hold the core it needs for the whole time slice.
template <class Done>
void waitUntil(const Done &done) {
    constexpr int kSpinPolls = 2000;
    for (int polls = 0; !done(); ++polls) {
        if (polls < kSpinPolls) cpuRelax();
        else std::this_thread::yield();
    }
}

class TaskPool {
public:
    /// A pool of `threads` threads in all, the caller's included (threads - 1 workers).
    explicit TaskPool(int threads);
    ~TaskPool();
    TaskPool(const TaskPool &) = delete;
    TaskPool &operator=(const TaskPool &) = delete;

    /// Threads that run a job, the caller's included.
    int threads() const { return static_cast<int>(workers_.size()) + 1; }

    /// Runs task(i, thread) for every i in [0, count) and returns when all have run;
    /// `thread` (0 to threads() - 1, the caller's 0) names the thread that runs it. The
    /// caller takes tasks too; with count <= 1 it runs them alone.
    template <class Task>
    void run(int count, const Task &task) {
        if (count <= 1 || workers_.empty()) {
            for (int i = 0; i < count; ++i) task(i, 0);
            return;
        }
        runJob(count, [](const void *context, int i, int thread) { (*static_cast<const Task *>(context))(i, thread); },
               &task);
    }

private:
    using Call = void (*)(const void *context, int index, int thread);

    void runJob(int count, Call call, const void *context);
    void workerLoop(int thread);
    void takeTasks(int thread);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wakeUp_;
    /// Odd while a job is open to workers, even between jobs; bumped under mutex_ to open.
    std::atomic<std::uint64_t> generation_{0};
    std::atomic<int> joined_{0};  ///< Workers inside the open job.
    std::atomic<bool> stopping_{false};
    // The open job: written only while no worker is inside one.
    Call call_ = nullptr;
    const void *context_ = nullptr;
    int count_ = 0;
    std::atomic<int> next_{0};      ///< Next task index to take.
    std::atomic<int> finished_{0};  ///< Tasks done.
};

}  // namespace cyclone::detail
