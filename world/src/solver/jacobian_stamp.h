// What a solver manifold's Jacobians were made from, so that a later step can tell
// whether they still hold and skip making them again.
//
// Design note. The Jacobians of a contact (lever arms, inverse inertias along them,
// effective masses, the friction block's inverse) depend on its anchors and normal and
// on its bodies' poses and masses, not on velocities. In a resting stack none of these
// change from one step to the next by more than the manifold-reuse tolerance, and making
// them again is a quarter of the solve of a resting stack. A slot keeps them while it holds a manifold with
// the same anchors (ManifoldState::anchorsId: new contacts found by the narrowphase are new
// anchors, and a number belongs to one manifold, so to one pair of bodies), its bodies in
// the same roles (movable or not in the solver), and neither body moved more than
// DebugSettings::manifoldReuseTolerance (translation plus rotation times its bounding
// radius) since they were made: the error is then of the order of what manifold reuse
// accepts. Manifolds keep their slots from step to step (ConstraintSolver::assignSlots) for
// this.
#pragma once

#include <cstdint>
#include <optional>

#include "solver/contact_solver.h"
#include "cyclone/core.h"

namespace cyclone::detail {

/// One body of a stamped manifold as it was when the Jacobians were made.
struct StampedBody {
    bool movable = false;  ///< Simulated (a solver body of its own) or immovable (entry 0).
    Vector3 position = Vector3::Zero();
    Quaternion orientation = Quaternion::Identity();
};

/// Per solver slot (ConstraintSolver::stamps_).
struct JacobianStamp {
    /// The anchors they were made for (ManifoldState::anchorsId; 0: none, no manifold has it).
    std::uint64_t anchorsId = 0;
    /// Where each point's normal row is among the slot's points, by PersistentPoint::id.
    signed char rowOf[kMaxManifoldPoints] = {0, 1, 2, 3};
    StampedBody body[2];  ///< A and B.
    /// The SolverManifold::carrier the carried masses were made for (none: not yet).
    std::optional<Carrier> carrier;
    /// This step: the slot's Jacobians still hold, and prepareSolver keeps them.
    bool kept = false;
};

}  // namespace cyclone::detail
