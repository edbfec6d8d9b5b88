// How a step shares its independent work between threads: a TaskPool when
// WorldSettings::threads > 1, the stepping thread alone otherwise.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

#include "world/task_pool.h"

namespace cyclone::detail {

class Workers {
public:
    /// Starts or stops threads to match `threads` (WorldSettings::threads).
    void match(int threads) {
        if (threads <= 1) pool_.reset();
        else if (!pool_ || pool_->threads() != threads) pool_ = std::make_unique<TaskPool>(threads);
    }
    bool parallel() const { return pool_ != nullptr; }
    /// Threads that run a job, the stepping thread's included.
    int threads() const { return pool_ ? pool_->threads() : 1; }

    /// Runs task(i) for i in [0, count), on the pool's threads when there is one; the
    /// tasks must be independent. A job of more than one task adds its time to shared().
    template <class Task>
    void forEachTask(int count, const Task &task) {
        runTasks(count, [&](int i, int) { task(i); });
    }

    /// Milliseconds, since resetTimes(), in jobs of more than one task: the work that
    /// threads share (on one thread, the work two would share).
    double shared() const { return shared_; }
    void resetTimes() { shared_ = 0; }

    /// Items handed to a thread at once: enough to outweigh the handing (a microsecond).
    static constexpr std::size_t kChunk = 64;

    /// How many chunks of kChunk items `count` items make.
    static std::size_t chunksOf(std::size_t count) { return (count + kChunk - 1) / kChunk; }

    /// Runs task(chunk, begin, end) for each chunk [begin, end) of kChunk items of
    /// [0, count): for work that keeps something per chunk (a list of finds, counters).
    template <class Task>
    void forEachChunk(std::size_t count, const Task &task) {
        forEachTask(static_cast<int>(chunksOf(count)), [&](int chunk) {
            const std::size_t begin = std::size_t(chunk) * kChunk;
            task(std::size_t(chunk), begin, std::min(count, begin + kChunk));
        });
    }

    /// Runs task(thread, chunk, begin, end) for each chunk as forEachChunk does, telling
    /// each which of threads() threads runs it: for work that appends to a list of its
    /// thread's own (ChunkLists).
    template <class Task>
    void forEachChunkOnThreads(std::size_t count, const Task &task) {
        runTasks(static_cast<int>(chunksOf(count)), [&](int chunk, int thread) {
            const std::size_t begin = std::size_t(chunk) * kChunk;
            task(thread, std::size_t(chunk), begin, std::min(count, begin + kChunk));
        });
    }

    /// Runs task(i) for every i in [0, count), in chunks of kChunk.
    template <class Task>
    void forEach(std::size_t count, const Task &task) {
        forEachChunk(count, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) task(i);
        });
    }

    /// Tests flag(i) for every i in [0, count) on the threads, then calls act(i) for the
    /// flagged ones in order on this thread: an ordered walk that visits only what the
    /// shared tests picked. `flags` is the caller's scratch.
    template <class Flag, class Act>
    void forFlagged(std::size_t count, std::vector<char> &flags, const Flag &flag, const Act &act) {
        flags.resize(count);
        forEach(count, [&](std::size_t i) { flags[i] = flag(i) ? 1 : 0; });
        for (std::size_t i = 0; i < count; ++i)
            if (flags[i]) act(i);
    }

private:
    /// Runs task(i, thread) for i in [0, count): forEachTask, telling each task its thread.
    template <class Task>
    void runTasks(int count, const Task &task) {
        if (count <= 1) {
            if (count == 1) task(0, 0);
            return;
        }
        const auto start = std::chrono::steady_clock::now();
        if (pool_) pool_->run(count, task);
        else for (int i = 0; i < count; ++i) task(i, 0);
        shared_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }

    std::unique_ptr<TaskPool> pool_;
    double shared_ = 0;
};

}  // namespace cyclone::detail
