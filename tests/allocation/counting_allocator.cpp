// Counting replacements of the global allocation functions, for the allocation tests'
// binary only. They pair malloc with free; GCC 12 at -O1 inlines a delete expression and
// then flags free() on memory from operator new (-Wmismatched-new-delete), which is
// exactly the pairing intended here.
#include "counting_allocator.h"

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> gAllocations{0};
}  // namespace

long cyclone::test::allocationCount() { return gAllocations.load(); }

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
    return p;
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
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t) noexcept { std::free(p); }
void operator delete(void *p, const std::nothrow_t &) noexcept { std::free(p); }
void operator delete[](void *p, const std::nothrow_t &) noexcept { std::free(p); }
void operator delete(void *p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void *p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void *p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t, std::align_val_t) noexcept { std::free(p); }
#endif
