// The bodies' velocities a wide manifold's passes work on, four lanes at a time: the
// velocity pass (velocity_pass.h) and the penetration pass (penetration_pass.h).
#pragma once

#include <vector>

#include "solver/velocity_pass.h"

namespace cyclone::detail {

/// The velocities of a wide manifold's bodies, held in registers over its rows: with
/// kPseudo, their pseudo-velocities (SolverBody::pv, pw).
template <bool kPseudo = false>
struct WideVelocities {
    WideVector va, wa, vb, wb;

    CYCLONE_INLINE WideVelocities(const std::vector<SolverBody> &bodies, const ManifoldBatch &m) {
        const SolverBody &a0 = bodies[m.a[0]], &a1 = bodies[m.a[1]], &a2 = bodies[m.a[2]], &a3 = bodies[m.a[3]];
        const SolverBody &b0 = bodies[m.b[0]], &b1 = bodies[m.b[1]], &b2 = bodies[m.b[2]], &b3 = bodies[m.b[3]];
        transposeIn(linear(a0), linear(a1), linear(a2), linear(a3), va);
        transposeIn(angular(a0), angular(a1), angular(a2), angular(a3), wa);
        transposeIn(linear(b0), linear(b1), linear(b2), linear(b3), vb);
        transposeIn(angular(b0), angular(b1), angular(b2), angular(b3), wb);
    }

    // Writes the lanes in use back. Never the immovable world (entry 0), which they leave
    // unchanged: two threads may hold it at once (threads/partition.h).
    CYCLONE_INLINE void store(std::vector<SolverBody> &bodies, const ManifoldBatch &m) const {
        storeSide(bodies, m.a, m.size, va, wa);
        storeSide(bodies, m.b, m.size, vb, wb);
    }

private:
    static CYCLONE_INLINE const Lanes &linear(const SolverBody &b) { return kPseudo ? b.pv : b.v; }
    static CYCLONE_INLINE const Lanes &angular(const SolverBody &b) { return kPseudo ? b.pw : b.w; }

    // One side's bodies (A's or B's) of the first `size` lanes.
    static CYCLONE_INLINE void storeSide(std::vector<SolverBody> &bodies, const int *index, int size,
                                         const WideVector &v, const WideVector &w) {
        Lanes vOut[kWideLanes], wOut[kWideLanes];
        transposeOut(v, vOut);
        transposeOut(w, wOut);
        for (int k = 0; k < size; ++k) {
            if (index[k] == 0) continue;
            SolverBody &body = bodies[index[k]];
            (kPseudo ? body.pv : body.v) = vOut[k];
            (kPseudo ? body.pw : body.w) = wOut[k];
        }
    }
};

}  // namespace cyclone::detail
