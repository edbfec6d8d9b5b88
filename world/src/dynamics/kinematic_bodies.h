// Kinematic bodies: infinite mass, moved only at the velocities the game sets.
//
// A kinematic body that moves this step is in the awake tree (so that it meets sleeping
// bodies) and has a solver entry of its own after the simulated bodies' (zero inverse
// mass, its velocity): contacts see its surface move, so it pushes what it meets and its
// friction carries what rests on it, but no impulse changes it. A still one is in the
// static tree and maps to the solver's immovable entry 0, like a static body. Kinematic
// bodies join no island and never sleep while they move.
#pragma once

#include "cyclone/world/world.h"
#include "world/body_transitions.h"

namespace cyclone::detail {

struct BodyStore;
class PairCache;

class KinematicBodies {
public:
    /// At the start of a step, after the simulated bodies are listed: lists the moving
    /// kinematic bodies (BodyStore::moving) and puts each in the tree its motion asks for
    /// (`transitions`), waking what a body that starts moving touches (its `pairs`).
    static void beginStep(BodyStore &bodies, const PairCache &pairs, BodyTransitions transitions);
    /// Gives the moving kinematic bodies their solver indices, after the simulated
    /// bodies' (once the step's simulated bodies are final).
    static void number(BodyStore &bodies);
    /// Moves each moving kinematic body over h seconds at its velocity and rotation
    /// (the rotation exactly: a turn of |w| h about w).
    static void integrate(BodyStore &bodies, real h);
    /// Puts a kinematic body that just got a velocity in motion: its collision object to
    /// the awake tree, and what it touches (its `pairs`) woken.
    static void startMoving(BodyStore &bodies, const PairCache &pairs, BodyTransitions transitions,
                            std::uint32_t index);
};

/// Whether a kinematic body with these velocities moves.
inline bool movesAt(const Vector3 &velocity, const Vector3 &rotation) {
    return !velocity.isZero(0) || !rotation.isZero(0);
}

}  // namespace cyclone::detail
