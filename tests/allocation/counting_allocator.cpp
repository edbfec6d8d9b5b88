// Counting replacements of the global allocation functions, for the allocation tests'
// binary only. They pair malloc with free; GCC 12 at -O1 inlines a delete expression and
// then flags free() on memory from operator new (-Wmismatched-new-delete), which is
// exactly the pairing intended here.
#include "counting_allocator.h"

#include <malloc.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> gAllocations{0};
std::atomic<long> gLiveBytes{0};
std::atomic<long> gPeakBytes{0};

// Counts a block's usable size in or out of the live bytes, and raises the peak.
[[maybe_unused]] void countBytes(void *p, long sign) {
    if (!p) return;
    const long live = gLiveBytes.fetch_add(sign * static_cast<long>(malloc_usable_size(p))) +
                      sign * static_cast<long>(malloc_usable_size(p));
    long peak = gPeakBytes.load();
    while (live > peak && !gPeakBytes.compare_exchange_weak(peak, live)) {
    }
}
}  // namespace

long cyclone::test::allocationCount() { return gAllocations.load(); }
long cyclone::test::liveBytes() { return gLiveBytes.load(); }
long cyclone::test::peakBytes() { return gPeakBytes.load(); }
void cyclone::test::resetPeakBytes() { gPeakBytes.store(gLiveBytes.load()); }

#if !defined(__SANITIZE_ADDRESS__)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

namespace {

void *allocate(std::size_t size, std::size_t alignment) {
    ++gAllocations;
    if (size == 0) size = 1;
    void *p = nullptr;
    if (alignment <= alignof(std::max_align_t)) {
        p = std::malloc(size);
    } else if (posix_memalign(&p, alignment, size) != 0) {
        p = nullptr;
    }
    countBytes(p, 1);
    return p;
}

void release(void *p) {
    countBytes(p, -1);
    std::free(p);
}

void *allocateOrThrow(std::size_t size, std::size_t alignment) {
    if (void *p = allocate(size, alignment)) return p;
    throw std::bad_alloc();
}

constexpr std::size_t kPlain = alignof(std::max_align_t);

}  // namespace

void *operator new(std::size_t size) { return allocateOrThrow(size, kPlain); }
void *operator new[](std::size_t size) { return allocateOrThrow(size, kPlain); }
void *operator new(std::size_t size, const std::nothrow_t &) noexcept { return allocate(size, kPlain); }
void *operator new[](std::size_t size, const std::nothrow_t &) noexcept { return allocate(size, kPlain); }
void *operator new(std::size_t size, std::align_val_t a) { return allocateOrThrow(size, static_cast<std::size_t>(a)); }
void *operator new[](std::size_t size, std::align_val_t a) { return allocateOrThrow(size, static_cast<std::size_t>(a)); }
void operator delete(void *p) noexcept { release(p); }
void operator delete[](void *p) noexcept { release(p); }
void operator delete(void *p, std::size_t) noexcept { release(p); }
void operator delete[](void *p, std::size_t) noexcept { release(p); }
void operator delete(void *p, const std::nothrow_t &) noexcept { release(p); }
void operator delete[](void *p, const std::nothrow_t &) noexcept { release(p); }
void operator delete(void *p, std::align_val_t) noexcept { release(p); }
void operator delete[](void *p, std::align_val_t) noexcept { release(p); }
void operator delete(void *p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void *p, std::size_t, std::align_val_t) noexcept { release(p); }
#endif
