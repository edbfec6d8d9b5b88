// Sensors (BodySettings::sensor): the bodies that overlap each sensor, and the begin and
// end events. Sensor pairs never become contact pairs: no manifold, no impulse, no island.
//
// Design note. An overlap is kept (in `overlaps_`, which holds overlapping pairs only)
// until a test finds it over, and a pair is tested only when the broadphase reports it
// (one of its bodies awake, or a moving kinematic body) or a call asked for it: a sensor
// added, a body added not awake while there are sensors, a static or kinematic body moved
// by a call, a filter changed. An overlap that the step's broadphase no longer reports
// although one of its bodies was in the walk has ended (their boxes parted). So a body
// asleep in a static sensor costs one look per step and no test, and a pair whose boxes
// do not overlap costs nothing. Tests use the poses at the start of the step, as contacts
// do: the events of step N tell what the poses after step N - 1 show.
#pragma once

#include <cstdint>
#include <vector>

#include "collision/broadphase.h"
#include "contacts/pair_cache.h"
#include "cyclone/world/events.h"
#include "cyclone/world/stats.h"

namespace cyclone::detail {

struct BodyStore;
struct StepContext;

class Sensors {
public:
    friend struct StateFields;  ///< Saves and restores the state (snapshot/world_state_io.cpp).
    /// Body `index` was just added: a sensor, or a body not awake while there are sensors,
    /// is tested against every body its box overlaps in the next step.
    void added(const BodyStore &bodies, std::uint32_t index);
    /// Body `index` was moved by a call: a static or kinematic one (which the broadphase
    /// may not see against sleeping bodies) is tested again in the next step.
    void moved(const BodyStore &bodies, std::uint32_t index);
    /// Body `index` leaves collision (removed or isolated): its overlaps end now, each an
    /// end event in `events`.
    void removed(const BodyStore &bodies, WorldEvents &events, std::uint32_t index);
    /// Body `index`'s layers or pair rules changed: the overlaps they now forbid end now
    /// (end events in `events`), and the body is tested again in the next step.
    void filterChanged(const BodyStore &bodies, WorldEvents &events, std::uint32_t index);
    /// The sensor stage (run only while there are sensors): tests the
    /// broadphase's sensor pairs (`candidates`) and the rechecked bodies against what the
    /// broadphase finds around them, records the begin and end events in `events` and
    /// counts the tests in stats.sensorPairs.
    void update(const StepContext &context, const BodyStore &bodies, Broadphase &broadphase,
                const std::vector<CandidatePair> &candidates, WorldEvents &events, StepStats &stats);

private:
    /// Queues body `index` for a test against every body its box overlaps.
    void recheck(std::uint32_t index) { rechecks_.push_back(index); }
    /// Appends (sensor, other) for every body that `index` may overlap and that is its
    /// sensor or that it sees, from the trees and the planes.
    void gatherAround(const BodyStore &bodies, Broadphase &broadphase, std::uint32_t index);
    /// Ends the overlap in slot `slot`: an end event in `events`, and the slot freed.
    void end(const BodyStore &bodies, WorldEvents &events, std::uint32_t slot);

    PairCache overlaps_;                     ///< The overlapping pairs (nothing else).
    std::vector<std::uint32_t> rechecks_;    ///< Bodies to test in the next step.
    std::vector<std::uint64_t> checkedStep_; ///< By body index: the step in which it was last rechecked.
    std::vector<CandidatePair> candidates_;  ///< The step's pairs, as (sensor, other).
    std::vector<std::uint32_t> found_;       ///< Scratch of gatherAround().
};

}  // namespace cyclone::detail
