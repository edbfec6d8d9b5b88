// A solver slot's kept Jacobians in a saved state: made again on restore from what they
// were made from, rather than copied (about 2.3 KB a slot).
//
// Design note. A slot keeps its Jacobians while its manifold has the same anchors and its
// bodies hardly moved since they were made (solver/jacobian_stamp.h). They are a function
// of the stamp (the bodies' poses and roles then), the anchors of the slot's rows (those
// of the manifold that last took the slot: a set of anchors belongs to one manifold), the
// normal they were made with, the bodies' masses and locks, and, for the carried terms,
// the carrier they were made for. A state holds those (about 150 bytes) and a restore
// makes the Jacobians again through the very functions the step uses
// (prepareJacobians, as ConstraintSolver::prepareManifold). The save makes them too and compares them bit for
// bit with the slot's; a slot where they differ (a mass changed since, a moving kinematic
// body whose lever arms turned with it) is copied whole. A slot whose stamp names anchors
// no manifold has cannot keep its Jacobians: the next step makes them anew, and the state
// holds nothing of it.
#pragma once

#include <cstring>

#include "dynamics/axis_locks.h"
#include "solver/jacobian_stamp.h"
#include "world/body_store.h"

namespace cyclone::detail {

/// How a slot is saved.
enum class SlotForm : std::uint8_t {
    Unkept,  ///< Its Jacobians cannot be kept: nothing of it is read.
    Remade,  ///< Its stamp, normal and carrier: the Jacobians are made again.
    Copied,  ///< Its stamp and manifold as they are.
};

/// The solver body a stamped side had when its Jacobians were made: `posed` is its body at
/// the stamped pose (an immovable side is the solver's entry 0).
inline SolverBody stampedSolverBody(const StampedBody &stamped, const BodyRecord &r, const RigidBody &posed) {
    SolverBody sb;
    if (!stamped.movable) return sb;
    sb.invMass = posed.getInverseMass();
    sb.invInertia = posed.getInverseInertiaTensorWorld();
    if (r.locked.any()) lockSolverBody(r.locked, sb);
    return sb;
}

/// Makes the Jacobians of `m` (its normal, count, rows' anchors, sides a and b (0:
/// immovable) and carrier set) as ConstraintSolver::prepareManifold makes them, for bodies
/// `posedA` and `posedB` at their stamped poses (`scratch`: room for the carried terms'
/// solver bodies).
__attribute__((noinline)) inline void remakeJacobians(SolverManifold &m, const std::optional<Carrier> &carrier,
                                                      const SolverBody &sa, const SolverBody &sb,
                                                      const RigidBody &posedA, const RigidBody &posedB,
                                                      std::vector<SolverBody> &scratch) {
    tangentBasis(m.normal, m.tangent[0], m.tangent[1]);
    prepareJacobians(sa, sb, posedA, posedB, m);
    if (carrier) {
        m.carrier = *carrier;
        scratch.assign({SolverBody(), sa, sb});
        prepareCarriedMasses(scratch, m);
    }
}

/// Whether two slots' Jacobians hold the same bits where a later step reads them: the
/// carried terms only when `carried` (the stamp names a carrier they were made for).
inline bool sameJacobians(const SolverManifold &x, const SolverManifold &y, bool carried) {
    const auto same = [](const auto &u, const auto &v) { return std::memcmp(&u, &v, sizeof u) == 0; };
    const auto sameRow = [&](const SolverRow &u, const SolverRow &v, bool masses) {
        return same(u.rAxd, v.rAxd) && same(u.rBxd, v.rBxd) && same(u.angA, v.angA) && same(u.angB, v.angB) &&
               (!masses || same(u.mass, v.mass)) && (!masses || !carried || same(u.carriedMass, v.carriedMass));
    };
    if (x.count != y.count || !same(x.normal, y.normal) || !same(x.tangent, y.tangent) ||
        !same(x.direction, y.direction) || !same(x.twistRadius, y.twistRadius) ||
        !same(x.frictionInverse, y.frictionInverse) || !same(x.couplings, y.couplings))
        return false;
    if (!sameRow(x.frictionRow[0], y.frictionRow[0], false) || !sameRow(x.frictionRow[1], y.frictionRow[1], false) ||
        !sameRow(x.twist, y.twist, false))
        return false;
    if (carried && (!same(x.carriedFrictionInverse, y.carriedFrictionInverse) || !same(x.carriedCouplings, y.carriedCouplings)))
        return false;
    for (int i = 0; i < x.count; ++i)
        if (!sameRow(x.points[i].normal, y.points[i].normal, true)) return false;
    return true;
}

}  // namespace cyclone::detail
