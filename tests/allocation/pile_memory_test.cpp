// Unit boxes spawned at one point: every box overlaps every other, so the broadphase
// pairs grow as n^2 / 2. The pair budget (WorldSettings::maxPairs) keeps the step's
// memory proportional to the budget, not to the pairs (issue 34: 1,000 such boxes took
// 4.2 GB before the budget; 10,000 were killed at 21-24 GB).
#include <gtest/gtest.h>

#include <string>

#include "counting_allocator.h"
#include "cyclone/world/world.h"

namespace cyclone::test {
namespace {

// The budget of these tests and the bound on what one kept pair may cost, bytes. A
// touching pair holds at most (docs/hostile_input.md, "Bytes per pair"): its
// SolverManifold (2,304), a ManifoldBatch (3,584) and a PenetrationBatch (1,120) of its
// own when no other manifold can share its group (in a pile at one point few can), the
// batches reserved 1.125 times over (loadBatches), its ManifoldState (408) and PairState
// (112), and some 100 bytes of lists: less than 11,510 bytes. Vectors that grow by doubling hold
// the old and the new array while they move, so up to twice that: 24 KB.
constexpr int kBudget = 2000;
constexpr long kBytesPerPair = 24 * 1024;
// And per body (its record, solver body, tree leaf and lists): far below this.
constexpr long kBytesPerBody = 8 * 1024;

// The bound holds at 300 and at 600 boxes, whose 45,150 and 180,300 pairs (n (n - 1) / 2
// box pairs and n with the floor) would need at least 104 MB and 415 MB for their
// SolverManifolds alone: the budget, not the pile, sets the memory.
TEST(PileMemory, BoxesAtOnePointStayWithinThePairBudgetsMemory) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    for (const int boxes : {300, 600}) {
        const std::string what = std::to_string(boxes) + " boxes";
        WorldSettings settings;
        settings.sleep = false;
        settings.maxPairs = kBudget;
        // The landing correction would push the boxes out of one another within a few
        // steps (they all move fast), leaving fewer overlapping pairs than the budget:
        // what is measured here is a pile that keeps more.
        settings.debug.landingCorrection = false;
        World world(settings);
        BodySettings ground;
        ground.motion = Motion::Static;
        ground.shape = Shape::plane(Vector3::UnitY(), 0);
        world.addBody(ground);
        BodySettings box;
        box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
        box.position = Vector3(0, 0.5, 0);
        for (int i = 0; i < boxes; ++i) world.addBody(box);

        const long before = liveBytes();
        resetPeakBytes();
        bool warned = true;
        for (int step = 0; step < 10; ++step) {
            world.step(1.0 / 60.0);
            EXPECT_EQ(world.stats().broadphasePairs, kBudget) << what << ", step " << step;
            warned = warned && (world.stats().errors & StepError::PairBudgetExceeded) != 0;
        }
        EXPECT_TRUE(warned) << what << ": every step has more overlapping pairs than the budget";
        const long grown = peakBytes() - before;
        EXPECT_LT(grown, kBudget * kBytesPerPair + boxes * kBytesPerBody) << what;
        // And the budget's pairs are in use: the SolverManifolds of the touching pairs kept.
        EXPECT_GT(grown, kBudget / 2 * 2304L) << what;
    }
}

}  // namespace
}  // namespace cyclone::test
