// Lanes: a 3-vector held in four doubles (the fourth is zero), the contact solver's
// working type.
//
// Design note. Eigen's Vector3 is not vectorised (three doubles do not fill a SIMD
// register evenly), and the solver's passes are nothing but 3-vector products and sums:
// in lanes each is one instruction where the CPU has 256-bit registers (AVX2), two where
// it has 128-bit ones (SSE2). The passes are compiled for both (CYCLONE_SIMD_CLONES) and
// the loader picks the one the CPU runs. Helpers take and give lanes by reference:
// passing a 32-byte vector by value is an ABI the compiler warns about without AVX.
#pragma once

#include "cyclone/core.h"

namespace cyclone::detail {

// Aligned to 32 bytes whatever the target: without AVX the compiler would give it 16, and
// the AVX2 clone of a pass, which assumes 32, would fault on the baseline's arrays.
using Lanes = double __attribute__((vector_size(4 * sizeof(double)), aligned(32)));
/// Lane indices for __builtin_shuffle, and the masks comparisons of lanes give.
using LaneIndices = long long __attribute__((vector_size(4 * sizeof(long long))));

/// The solver's small helpers are always inlined: a call would pass lanes through memory.
#define CYCLONE_INLINE inline __attribute__((always_inline))

/// out = (v, 0), element by element: building the vector in registers first made GCC go
/// through the stack with a store the next load could not forward from (slow).
inline __attribute__((always_inline)) void setLanes(Lanes &out, const Vector3 &v) {
    out[0] = v.x();
    out[1] = v.y();
    out[2] = v.z();
    out[3] = 0;
}
inline __attribute__((always_inline)) Vector3 toVector3(const Lanes &v) { return Vector3(v[0], v[1], v[2]); }
/// x + y + z.
inline __attribute__((always_inline)) real sum3(const Lanes &v) { return v[0] + v[1] + v[2]; }
inline __attribute__((always_inline)) real dot3(const Lanes &a, const Lanes &b) { return sum3(a * b); }

}  // namespace cyclone::detail

// Compiles a function twice, for x86-64-v3 (AVX2, FMA) and for the baseline, and picks
// one when the program loads (GCC function multi-versioning). Elsewhere: one version.
// ThreadSanitizer instruments the picking function, which runs before it is set up, and
// the program crashes while loading: no clones under it.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(__SANITIZE_THREAD__) && !defined(CYCLONE_NO_SIMD_CLONES)
#define CYCLONE_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define CYCLONE_SIMD_CLONES
#endif
