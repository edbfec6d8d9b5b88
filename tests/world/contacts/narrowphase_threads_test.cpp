// The narrowphase stage shares its pairs between the step's threads (in chunks of
// Workers::kChunk) and merges what each found in the pairs' order: a mixed pile gives
// bit-identical states with 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "../mixed_pile.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr real kPileStep = 1.0 / 60.0;

struct ThreadedPile {
    std::unique_ptr<World> world;
    std::vector<BodyId> ids;

    explicit ThreadedPile(int threads) {
        WorldSettings settings;
        settings.threads = threads;
        world = std::make_unique<World>(settings);
        ids = addMixedPile(*world, 5, 4);  // 100 bodies
    }
};

TEST(NarrowphaseThreads, MixedPileIsBitIdenticalForOneTwoAndThreeThreads) {
    ThreadedPile one(1), two(2), three(3);
    int mostTested = 0;
    long tested = 0;
    for (int step = 0; step < 240; ++step) {
        one.world->step(kPileStep);
        two.world->step(kPileStep);
        three.world->step(kPileStep);
        mostTested = std::max(mostTested, one.world->stats().pairsTested);
        tested += one.world->stats().pairsTested;
        EXPECT_EQ(one.world->stats().pairsTested, two.world->stats().pairsTested) << "step " << step;
        EXPECT_EQ(one.world->stats().pairsReused, three.world->stats().pairsReused) << "step " << step;
        EXPECT_EQ(one.world->stats().contacts, three.world->stats().contacts) << "step " << step;
        for (std::size_t i = 0; i < one.ids.size(); ++i) {
            const RigidBody &body = one.world->body(one.ids[i]);
            ASSERT_TRUE(sameBits(body, two.world->body(two.ids[i]))) << "body " << i << ", step " << step;
            ASSERT_TRUE(sameBits(body, three.world->body(three.ids[i]))) << "body " << i << ", step " << step;
        }
    }
    // More than two chunks of 64 pairs went through the narrowphase in some step, so the
    // threads did share them.
    EXPECT_GT(mostTested, 128);
    EXPECT_GT(tested, 0);
}

}  // namespace
}  // namespace cyclone::test
