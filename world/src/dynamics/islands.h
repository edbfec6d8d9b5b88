// Islands: the groups of simulated bodies joined by contacts or springs this step, and
// the islands asleep. An island sleeps as a whole once every body in it is still.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "cyclone/world/world.h"
#include "solver/contact_solver.h"
#include "world/chunk_lists.h"

namespace cyclone::detail {

struct BodyStore;
class PairCache;
class JointSet;
class SpringSet;

class Islands {
public:
    friend struct StateFields;  ///< Saves and restores the state (snapshot/world_state_io.cpp).
    /// Sleeping islands' members, by BodyRecord::sleepingIsland (cleared when woken).
    std::vector<std::vector<std::uint32_t>> sleeping;
    std::vector<int> freeSleeping;  ///< Entries of `sleeping` free for reuse.

    /// The islands stage: joins the simulated bodies by the solver's manifolds, the
    /// springs and the joints, and the held bodies (Holding::held) by their touching
    /// pairs with held or simulated bodies; writes each such body's BodyRecord::island
    /// and stats.islands.
    void build(BodyStore &bodies, const SolverManifolds &manifolds, const SpringSet &springs,
               const JointSet &joints, const std::vector<std::uint32_t> &held, const PairCache &pairs,
               Workers &workers, StepStats &stats);
    /// This step's islands whose bodies are all still (RigidBody's sleep average below its
    /// sleep epsilon), in order; none when settings.sleep is off. The step puts each to
    /// sleep (WorldState::sleepIsland).
    const std::vector<int> &still(const WorldSettings &settings, const BodyStore &bodies);
    /// The bodies of this step's island `island` (BodyRecord::island).
    const std::uint32_t *members(int island) const { return members_.data() + start_[island]; }
    int size(int island) const { return start_[island + 1] - start_[island]; }

private:
    std::vector<std::pair<int, int>> links_;          ///< By solver manifold: the entries it joins, or -1s.
    ChunkLists<std::pair<int, int>> heldLinks_;       ///< The held bodies' links, as their chunks found them.
    std::vector<int> parent_;  ///< Union-find over the simulated bodies, by solver index - 1, then the held ones.
    std::vector<int> start_;   ///< Island i's members are members_[start_[i], start_[i + 1]).
    std::vector<std::uint32_t> members_;
    std::vector<int> still_;  ///< What still() returned.
};

}  // namespace cyclone::detail
