// A counting allocator: the harness replaces the global operator new/delete with one that
// counts bytes and calls, and hands the same functions to Bullet (whose btAlignedAlloc
// calls malloc directly). Memory that a library takes with malloc itself (Eigen's
// dynamic matrices, libccd, qhull) is not counted; the peak-RSS figure covers it.
#pragma once

#include <cstddef>

namespace cyclone::bench {

struct AllocCounters {
    long long liveBytes = 0;    ///< Bytes allocated and not yet freed (usable sizes).
    long long peakBytes = 0;    ///< Highest liveBytes since the last resetPeak().
    long long allocations = 0;  ///< Allocation calls since the program started.
};

/// The counters now.
AllocCounters allocCounters();
/// Sets the peak to the bytes live now.
void resetAllocPeak();

/// malloc and free that keep the counters; for libraries with an allocator hook.
void *countedMalloc(std::size_t size);
void countedFree(void *pointer);

}  // namespace cyclone::bench
