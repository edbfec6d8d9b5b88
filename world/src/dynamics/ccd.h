// Continuous collision for bodies with BodySettings::ccd, after the sub-steps.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/world/world.h"

namespace cyclone::detail {

struct WorldState;

class ContinuousCollision {
public:
    /// Puts each ccd body that moved further than its inner radius back to where its
    /// motion first touched something (collision/time_of_impact.h), a slop deep.
    void sweep(WorldState &world);

private:
    std::vector<std::uint32_t> candidates_;  ///< Bodies near a sweep.
};

}  // namespace cyclone::detail
