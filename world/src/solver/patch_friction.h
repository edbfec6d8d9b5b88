// A contact patch's friction for four manifolds in lanes (simd/batch4.h), as
// ManifoldSweep::friction (contact_solver.cpp) solves it for one: the tangents and the
// twist as a block through its inverse, the twist limited to the points' summed normal
// impulse times the twist radius (the tangents then taking what it could not), the
// tangents to the cone of that sum.
// Shared by the batched velocity pass (velocity_pass.cpp) and the batched carrier pass
// (carrier_pass.cpp).
#pragma once

#include "solver/simd/batch4.h"

namespace cyclone::detail {

/// The friction rows' state in lanes: accumulated impulses, N s (tangents) and N m s
/// (twist), and their changes in the last solve.
struct WideFrictionRows {
    Lanes &tangent0, &tangent1, &twist;
    Lanes change0{}, change1{}, change2{};
};

/// Points of a patch (contact_solver.h's kMaxManifoldPoints).
inline constexpr int kWidePatchPoints = 4;

/// Solves the lanes of `rubs` towards relative velocities v0, v1 along the tangents (m/s)
/// and v2 about the normal (rad/s), with the block inverse k[6] (upper triangle row by
/// row), the points' summed normal impulse `load`, the friction coefficient and the twist
/// radius (0: no twist row); the other lanes keep their impulses. Each row's change then
/// reaches the points' normal velocities `vn` through its couplings (RowCouplings::friction).
CYCLONE_INLINE void solveWideFriction(const Lanes &v0, const Lanes &v1, const Lanes &v2, const Lanes k[6],
                                      const Lanes &load, const Lanes &coefficient, const Lanes &twistRadius,
                                      const LaneMask &rubs, const Lanes coupling[3][kWidePatchPoints],
                                      Lanes vn[kWidePatchPoints], WideFrictionRows &rows) {
    const Lanes zero{};
    const Lanes one{1, 1, 1, 1};
    const LaneMask turns = twistRadius > zero;
    const Lanes limit = coefficient * load;
    const Lanes spin = turns ? v2 : zero;
    const Lanes old0 = rows.tangent0, old1 = rows.tangent1, old2 = rows.twist;
    Lanes new0 = old0 - (k[0] * v0 + k[1] * v1 + k[2] * spin);
    Lanes new1 = old1 - (k[1] * v0 + k[3] * v1 + k[4] * spin);
    const Lanes twistLimit = limit * twistRadius;
    const Lanes free2 = old2 - (k[2] * v0 + k[4] * v1 + k[5] * spin);
    Lanes new2 = free2 < -twistLimit ? -twistLimit : free2 > twistLimit ? twistLimit : free2;
    // A twist held at its limit: the tangents take the block's solution with the twist's
    // change fixed there (twistHeld in contact_solver.cpp).
    const LaneMask held = (free2 != new2) & (k[5] > zero);  // a singular block's inverse is all zeros
    if (anyLane(held)) {
        const Lanes excess = held ? new2 - free2 : zero;
        const Lanes diagonal = held ? k[5] : one;
        new0 += k[2] / diagonal * excess;
        new1 += k[4] / diagonal * excess;
    }
    const Lanes magnitude2 = new0 * new0 + new1 * new1;
    const LaneMask outside = magnitude2 > limit * limit;
    // Resting contacts stick: their lanes are all inside the cone, and the root and the
    // division (some 40 cycles on the chain to the normal rows) are skipped.
    if (anyLane(outside)) {
        const Lanes rooted = outside ? magnitude2 : one;  // lanes inside the cone take no root (theirs may be 0)
        Lanes length{};
        sqrtLanes(rooted, length);
        const Lanes scale = outside ? limit / length : one;
        new0 *= scale;
        new1 *= scale;
    }
    new0 = rubs ? new0 : old0;
    new1 = rubs ? new1 : old1;
    new2 = (rubs & turns) ? new2 : old2;
    rows.tangent0 = new0;
    rows.tangent1 = new1;
    rows.twist = new2;
    rows.change0 = new0 - old0, rows.change1 = new1 - old1, rows.change2 = new2 - old2;
    for (int j = 0; j < kWidePatchPoints; ++j) vn[j] += rows.change0 * coupling[0][j];
    for (int j = 0; j < kWidePatchPoints; ++j) vn[j] += rows.change1 * coupling[1][j];
    for (int j = 0; j < kWidePatchPoints; ++j) vn[j] += rows.change2 * coupling[2][j];
}

}  // namespace cyclone::detail
