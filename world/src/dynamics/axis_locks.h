// Locked axes (LockedAxes): what keeps a body from moving along or turning about them.
//
// Design note. Three parts, each where the motion it stops is made:
// - the solver sees a locked body through a projected inverse inertia, P I^-1 P (P: the
//   unlocked rotation axes), so that no impulse, of a contact or a joint, turns it about
//   a locked axis and every row's effective mass is the one it really has; and through a
//   zero inverse mass when all three translations are locked;
// - the velocities the solver starts from lose their locked components (forces, springs
//   and gravity along a locked axis never reach the body);
// - after each sub-step's integration and penetration recovery, and once more at the
//   end of the step (after continuous collision and the landing correction), the
//   velocity loses its locked components and the pose is put back, along and about the
//   locked axes, to where the step began: no drift, whatever moved it.
// With one or two translations locked, the solver's rows still use the scalar inverse
// mass, so a contact whose normal has a locked component is solved as if the body could
// move along it, and the last part takes that motion away.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/world/world.h"

namespace cyclone::detail {

struct BodyStore;
struct SolverBody;

/// `v` without its components along the locked translation axes.
Vector3 freeLinear(const LockedAxes &locks, const Vector3 &v);
/// `w` without its components about the locked rotation axes.
Vector3 freeAngular(const LockedAxes &locks, const Vector3 &w);
/// The part of `turn` (a world-frame rotation) about the axes not locked: itself with no
/// rotation axis locked, its twist about the free axis with two, its swing (the turn less
/// its twist about the locked axis) with one, none with three.
Quaternion freeTurn(const LockedAxes &locks, const Quaternion &turn);
/// Gives a solver body the inverse mass and inertia its locks leave.
void lockSolverBody(const LockedAxes &locks, SolverBody &body);

/// Holds the locked bodies on their axes through a step.
class AxisLocks {
public:
    /// Records where each simulated body with locked axes begins the step.
    void beginStep(const BodyStore &bodies);
    /// Puts each of them back on its locked axes (velocity and pose).
    void hold(BodyStore &bodies) const;

private:
    struct Start {
        std::uint32_t body = 0;
        Vector3 position = Vector3::Zero();
        Quaternion orientation = Quaternion::Identity();
    };
    std::vector<Start> starts_;
};

}  // namespace cyclone::detail
