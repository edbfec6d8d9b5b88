// Continuous collision for bodies with BodySettings::ccd, after the sub-steps.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/world/world.h"

namespace cyclone::detail {

class Broadphase;
struct BodyStore;
class PairCache;
struct StepContext;

class ContinuousCollision {
public:
    /// Puts each ccd body that moved further than its inner radius back to where its
    /// motion first touched something (collision/time_of_impact.h), a slop deep
    /// (settings.penetrationSlop). Reads the bodies' collision objects (their poses at the
    /// step's start), the pairs touching in this step and the broadphase; writes the
    /// stopped bodies' poses and velocities, and stats.ccdSweeps and ccdHits.
    void sweep(const StepContext &context, BodyStore &bodies, Broadphase &broadphase, const PairCache &pairs,
               StepStats &stats);

private:
    /// Where a body's motion stops: a fraction of it (1: nowhere), and the body whose core
    /// stopped it (-1: none, or a plane or a shape's surface did).
    struct Stop {
        real fraction = 1;
        long core = -1;
    };
    Stop earliestStop(const BodyStore &bodies, Broadphase &broadphase, const PairCache &pairs, std::uint64_t stepCount,
                      std::uint32_t index, const Matrix4 &start, const Matrix4 &end, real travel, real depth);
    static void stopAt(BodyStore &bodies, std::uint32_t index, const Matrix4 &start, const Matrix4 &end,
                       const Stop &at);

    std::vector<std::uint32_t> candidates_;  ///< Bodies near a sweep.
};

}  // namespace cyclone::detail
