// Vectors of four manifolds or bodies side by side, one per lane, and the 4 x 4
// transposes that move them between that layout and the one-vector-per-body layout of
// simd/vector4.h. Shared by the batched velocity pass (velocity_pass.h) and the batched carrier pass
// (carrier_pass.h).
#pragma once

#include "solver/simd/vector4.h"

namespace cyclone::detail {

inline constexpr int kWideLanes = 4;

/// Four 3-vectors, one per lane.
struct WideVector {
    Lanes x, y, z;
};

/// Lanes where a comparison held: all bits set.
using LaneMask = LaneIndices;

/// Whether the comparison held in any lane.
CYCLONE_INLINE bool anyLane(const LaneMask &mask) { return (mask[0] | mask[1] | mask[2] | mask[3]) != 0; }

/// Lanes r0..r3 as their columns: out[j] holds lane j of each. The first shuffles pair
/// lanes within each 128-bit half (vunpcklpd, vunpckhpd), the last swap halves
/// (vperm2f128): eight instructions with AVX. Pairing lanes across the halves first
/// took twice as many, and the passes make several transposes per group.
CYCLONE_INLINE void transpose(const Lanes &r0, const Lanes &r1, const Lanes &r2, const Lanes &r3,
                              Lanes out[kWideLanes]) {
    const LaneIndices even = {0, 4, 2, 6}, odd = {1, 5, 3, 7}, low = {0, 1, 4, 5}, high = {2, 3, 6, 7};
    const Lanes xz01 = __builtin_shuffle(r0, r1, even);  // x0 x1 z0 z1
    const Lanes yw01 = __builtin_shuffle(r0, r1, odd);   // y0 y1 w0 w1
    const Lanes xz23 = __builtin_shuffle(r2, r3, even);
    const Lanes yw23 = __builtin_shuffle(r2, r3, odd);
    out[0] = __builtin_shuffle(xz01, xz23, low);
    out[1] = __builtin_shuffle(yw01, yw23, low);
    out[2] = __builtin_shuffle(xz01, xz23, high);
    out[3] = __builtin_shuffle(yw01, yw23, high);
}

/// The 3-vectors of four bodies or manifolds (x, y, z, 0 each) as x, y and z of four lanes.
CYCLONE_INLINE void transposeIn(const Lanes &r0, const Lanes &r1, const Lanes &r2, const Lanes &r3,
                                WideVector &out) {
    Lanes columns[kWideLanes];
    transpose(r0, r1, r2, r3, columns);
    out.x = columns[0];
    out.y = columns[1];
    out.z = columns[2];
}

/// The inverse of transposeIn: lane k of v as (x, y, z, 0).
CYCLONE_INLINE void transposeOut(const WideVector &v, Lanes out[kWideLanes]) {
    const Lanes zero{};
    transpose(v.x, v.y, v.z, zero, out);
}

CYCLONE_INLINE void addScaled(WideVector &out, const Lanes &s, const WideVector &v) {
    out.x += s * v.x;
    out.y += s * v.y;
    out.z += s * v.z;
}

CYCLONE_INLINE void subtractScaled(WideVector &out, const Lanes &s, const WideVector &v) {
    out.x -= s * v.x;
    out.y -= s * v.y;
    out.z -= s * v.z;
}

/// Four symmetric 3 x 3 matrices, one per lane: the lower triangle column by column.
struct WideSymmetric {
    Lanes xx, yx, zx, yy, zy, zz;
};

/// Per lane: out = m v, each row summed left to right (x, then y, then z terms).
CYCLONE_INLINE void multiply(const WideSymmetric &m, const WideVector &v, WideVector &out) {
    out.x = m.xx * v.x + m.yx * v.y + m.zx * v.z;
    out.y = m.yx * v.x + m.yy * v.y + m.zy * v.z;
    out.z = m.zx * v.x + m.zy * v.y + m.zz * v.z;
}

// Lanes are given back through a reference, as in simd/vector4.h.

/// Per lane: out = a . b, summed x + y + z.
CYCLONE_INLINE void dotLanes(const WideVector &a, const WideVector &b, Lanes &out) {
    out = a.x * b.x + a.y * b.y + a.z * b.z;
}

/// Per lane: out = the square root of v (one instruction where math errno is off).
CYCLONE_INLINE void sqrtLanes(const Lanes &v, Lanes &out) {
    for (int l = 0; l < kWideLanes; ++l) out[l] = __builtin_sqrt(v[l]);
}

}  // namespace cyclone::detail
