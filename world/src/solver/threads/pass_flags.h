// The hand-over both shared passes use: each entry of a pass (a row or manifold of an
// ordered share, a carrier run) is marked finished when its thread has solved it, and an
// entry that reads what an entry of the other thread writes waits for that mark. A mark
// holds the number of the pass that set it, so a new pass needs no clearing (but when the
// number wraps). A walk shared by threads (the held bodies' hit flood) takes each entry
// once: the one call of take() that marks it.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "world/task_pool.h"

namespace cyclone::detail {

class PassFlags {
public:
    /// Makes room for `count` entries (twice that when it grows); a new pass follows.
    void reserve(std::size_t count) {
        if (count <= capacity_) return;
        capacity_ = count * 2;
        flags_ = std::make_unique<std::atomic<std::uint32_t>[]>(capacity_);
        pass_ = 0;
    }
    /// Opens a pass: no entry is finished in it yet.
    void begin() {
        if (++pass_ == 0) {  // wrapped: no entry may look finished in this pass
            for (std::size_t k = 0; k < capacity_; ++k) flags_[k].store(0, std::memory_order_relaxed);
            pass_ = 1;
        }
    }
    void finish(std::size_t entry) { flags_[entry].store(pass_, std::memory_order_release); }
    bool finished(std::size_t entry) const { return flags_[entry].load(std::memory_order_acquire) == pass_; }
    /// Marks `entry` finished; true for the one call that marked it first in this pass.
    bool take(std::size_t entry) { return flags_[entry].exchange(pass_, std::memory_order_relaxed) != pass_; }
    /// Waits until the other thread has finished `entry` in this pass.
    void await(std::size_t entry) const {
        waitUntil([&] { return finished(entry); });
    }

private:
    std::unique_ptr<std::atomic<std::uint32_t>[]> flags_;
    std::size_t capacity_ = 0;
    std::uint32_t pass_ = 0;
};

}  // namespace cyclone::detail
