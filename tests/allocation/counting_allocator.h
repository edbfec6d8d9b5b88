// The allocation tests' counting allocator: this test binary replaces the global
// operator new and delete (counting_allocator.cpp) and counts every allocation.
#pragma once

namespace cyclone::test {

/// Whether allocations are counted. Under AddressSanitizer they are not: ASan has its
/// own allocator, and memory FCL allocates through it would come back to our free() (an
/// alloc-dealloc mismatch); the tests skip themselves there and run in normal builds.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kCountingAllocator = false;
#else
inline constexpr bool kCountingAllocator = true;
#endif

/// Calls to operator new (any form) since the program started.
long allocationCount();

/// Bytes allocated through operator new and not yet freed (malloc's usable sizes).
long liveBytes();
/// The most liveBytes() has been since the last resetPeakBytes() (or the start).
long peakBytes();
/// Starts a new peak from what is live now.
void resetPeakBytes();

}  // namespace cyclone::test
