// Held bodies: the part of an awake island that is already still. An island sleeps as a
// whole, so while one ball rolls over a resting pile every body of the pile would be
// solved, four sub-steps a step: mixed1000 spends its median steps so, 995 bodies solved
// for the 1 to 40 that move (docs/contacts_and_sleep.md, "Held bodies").
//
// A body is held for the step when it could sleep (its sleep average below its sleep
// epsilon, sleep allowed, no force or torque of the user's), it rests (as in a resting
// step: it touches something, on contacts solved last step, one carrying a load, and
// moves less than kRestingReach), every body it shares a pair with could too or is static
// or asleep, and no hit reaches it: a contact closing faster than kHitSpeed frees the two
// bodies and all the awake bodies that touch them, in turn, as a hit wakes a sleeping
// island whole. A held body is left out of the solve as a sleeping
// body is: its velocity zeroed, the bodies it touches solved against it as immovable, its
// manifolds with held or immovable bodies counted as solved with their impulses kept. It
// stays awake and in its island, which sleeps as before once all of it is still; what
// wakes a sleeping body wakes a held one alike (WorldState::wake), so that it is solved
// for about a second.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/world/world.h"
#include "solver/threads/pass_flags.h"
#include "world/chunk_lists.h"

namespace cyclone::detail {

struct BodyStore;
class PairCache;
struct StepContext;

class Holding {
public:
    /// Chooses the step's held bodies: takes them out of `bodies.simulated` (the others
    /// keep their order and are numbered again), zeroes their velocities, marks each
    /// BodyRecord::held, and stamps their manifolds with held or immovable bodies as
    /// solved this step. Called after the narrowphase, before the step's bodies are
    /// closed. None with sleep off, joints or springs in the step, or
    /// DebugSettings::holding off.
    void choose(const StepContext &context, BodyStore &bodies, PairCache &pairs, StepStats &stats);
    /// The bodies held this step, in the order they had in `simulated`.
    const std::vector<std::uint32_t> &held() const { return held_; }

private:
    /// Marks in still_ the simulated bodies that may be held, rings and all; false when
    /// none could be held on its own (still_ is then left as it was).
    bool markStill(const StepContext &context, const BodyStore &bodies, const PairCache &pairs);
    /// Clears the marks of every body a hit reaches: the two bodies of a contact closing
    /// faster than kHitSpeed and all the awake bodies that touch them, in turn.
    void clearHit(Workers &workers, const BodyStore &bodies, const PairCache &pairs);
    /// Moves the marked bodies from `bodies.simulated` to held_ (see choose).
    void takeOut(BodyStore &bodies);

    std::vector<char> still_;  ///< By body index: could be held on its own, then ring by ring.
    std::vector<char> ring_;   ///< The next ring's marks.
    PassFlags reached_;          ///< By body index: reached from a hit, in this step's flood.
    std::vector<char> flags_;    ///< By place in `simulated`: struck by a hit (scratch).
    std::vector<std::uint32_t> walk_;   ///< The bodies of the hits.
    std::vector<std::uint32_t> front_;  ///< The flood's last ring.
    ChunkLists<std::uint32_t> next_;    ///< The flood's next ring, as its chunks found it.
    std::vector<std::uint32_t> held_;
};

}  // namespace cyclone::detail
