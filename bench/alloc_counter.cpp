// Replacement of every global operator new and delete. Sizes are taken from
// malloc_usable_size so that a free needs no header in front of the block, and memory
// from new, Bullet's hook and plain malloc can be freed by any of them.
#include "alloc_counter.h"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace cyclone::bench {
namespace {

std::atomic<long long> gLive{0};
std::atomic<long long> gPeak{0};
std::atomic<long long> gCalls{0};

void noteAllocation(void *pointer) {
    const long long size = static_cast<long long>(malloc_usable_size(pointer));
    const long long live = gLive.fetch_add(size, std::memory_order_relaxed) + size;
    gCalls.fetch_add(1, std::memory_order_relaxed);
    long long peak = gPeak.load(std::memory_order_relaxed);
    while (live > peak && !gPeak.compare_exchange_weak(peak, live, std::memory_order_relaxed)) {
    }
}

void *allocate(std::size_t size, std::size_t alignment) {
    if (size == 0) size = 1;
    void *pointer = nullptr;
    if (alignment <= alignof(std::max_align_t)) {
        pointer = std::malloc(size);
    } else if (posix_memalign(&pointer, alignment, size) != 0) {
        pointer = nullptr;
    }
    if (pointer) noteAllocation(pointer);
    return pointer;
}

void *allocateOrThrow(std::size_t size, std::size_t alignment) {
    void *pointer = allocate(size, alignment);
    if (!pointer) throw std::bad_alloc();
    return pointer;
}

}  // namespace

AllocCounters allocCounters() {
    AllocCounters counters;
    counters.liveBytes = gLive.load(std::memory_order_relaxed);
    counters.peakBytes = gPeak.load(std::memory_order_relaxed);
    counters.allocations = gCalls.load(std::memory_order_relaxed);
    return counters;
}

void resetAllocPeak() { gPeak.store(gLive.load(std::memory_order_relaxed), std::memory_order_relaxed); }

void *countedMalloc(std::size_t size) { return allocate(size, alignof(std::max_align_t)); }

void countedFree(void *pointer) {
    if (!pointer) return;
    gLive.fetch_sub(static_cast<long long>(malloc_usable_size(pointer)), std::memory_order_relaxed);
    std::free(pointer);
}

}  // namespace cyclone::bench

using cyclone::bench::allocate;
using cyclone::bench::allocateOrThrow;
using cyclone::bench::countedFree;

void *operator new(std::size_t size) { return allocateOrThrow(size, alignof(std::max_align_t)); }
void *operator new[](std::size_t size) { return allocateOrThrow(size, alignof(std::max_align_t)); }
void *operator new(std::size_t size, const std::nothrow_t &) noexcept { return allocate(size, alignof(std::max_align_t)); }
void *operator new[](std::size_t size, const std::nothrow_t &) noexcept { return allocate(size, alignof(std::max_align_t)); }
void *operator new(std::size_t size, std::align_val_t alignment) {
    return allocateOrThrow(size, static_cast<std::size_t>(alignment));
}
void *operator new[](std::size_t size, std::align_val_t alignment) {
    return allocateOrThrow(size, static_cast<std::size_t>(alignment));
}
void *operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t &) noexcept {
    return allocate(size, static_cast<std::size_t>(alignment));
}
void *operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t &) noexcept {
    return allocate(size, static_cast<std::size_t>(alignment));
}

void operator delete(void *pointer) noexcept { countedFree(pointer); }
void operator delete[](void *pointer) noexcept { countedFree(pointer); }
void operator delete(void *pointer, std::size_t) noexcept { countedFree(pointer); }
void operator delete[](void *pointer, std::size_t) noexcept { countedFree(pointer); }
void operator delete(void *pointer, const std::nothrow_t &) noexcept { countedFree(pointer); }
void operator delete[](void *pointer, const std::nothrow_t &) noexcept { countedFree(pointer); }
void operator delete(void *pointer, std::align_val_t) noexcept { countedFree(pointer); }
void operator delete[](void *pointer, std::align_val_t) noexcept { countedFree(pointer); }
void operator delete(void *pointer, std::size_t, std::align_val_t) noexcept { countedFree(pointer); }
void operator delete[](void *pointer, std::size_t, std::align_val_t) noexcept { countedFree(pointer); }
void operator delete(void *pointer, std::align_val_t, const std::nothrow_t &) noexcept { countedFree(pointer); }
void operator delete[](void *pointer, std::align_val_t, const std::nothrow_t &) noexcept { countedFree(pointer); }
