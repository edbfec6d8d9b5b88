// A steady step of a mixed pile (boxes, spheres, capsules, cylinders and hulls resting
// on each other: FCL's contact test, libccd's MPR and GJK distance, the speculative
// contacts' distances) allocates nothing, on one thread or two.
#include <gtest/gtest.h>

#include <string>

#include "../world/mixed_pile.h"
#include "counting_allocator.h"

namespace cyclone::test {
namespace {

constexpr real kPileStep = 1.0 / 60.0;

// At the default manifold reuse (the time of impact's box-box test, which a pair opening
// by a hair goes through, is counted in Allocation.TimeOfImpactOfTwoBoxesAllocatesNothing).
TEST(StepAllocation, SettledMixedPileAllocatesNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    for (const int threads : {1, 2}) {
        const std::string what = "threads " + std::to_string(threads);
        WorldSettings settings;
        settings.sleep = false;
        settings.threads = threads;
        World world(settings);
        addMixedPile(world, 4, 3);  // 48 bodies
        // Falls and settles: with landing points (manifold_clipping.cpp) a body of the 48
        // still moved at step 300; by step 600 all rest.
        for (int i = 0; i < 600; ++i) world.step(kPileStep);
        long allocations = 0;
        long visited = 0;
        for (int i = 0; i < 120; ++i) {
            const long before = allocationCount();
            world.step(kPileStep);
            allocations += allocationCount() - before;
            visited += world.stats().pairsTested + world.stats().pairsReused;
        }
        EXPECT_EQ(allocations, 0) << what;
        // 48 bodies resting on each other, the ground and the walls: at least one
        // contact point each.
        EXPECT_GT(world.stats().contacts, 48) << what;
        EXPECT_GT(visited, 0) << what << ": the counted steps must go through the narrowphase stage";
    }
}

}  // namespace
}  // namespace cyclone::test
