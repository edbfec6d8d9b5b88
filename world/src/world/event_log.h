// The World's events. Calls between steps record into `pending`; a step moves those into
// `events` and records its own there (`sink` says which list is open).
#pragma once

#include <utility>

#include "cyclone/world/events.h"

namespace cyclone::detail {

struct EventLog {
    WorldEvents events;   ///< The last step's, as World::events() shows them.
    WorldEvents pending;  ///< Recorded by calls since the last step.
    WorldEvents *sink = &pending;

    /// A step's list starts with what calls recorded since the last step.
    void openStep() {
        std::swap(events, pending);
        pending.clear();
        sink = &events;
    }
    void closeStep() { sink = &pending; }
};

}  // namespace cyclone::detail
