// ManifoldState's record of the step it was last solved in.
#include <gtest/gtest.h>

#include "contacts/pair_cache.h"

namespace cyclone::test {
namespace {

using detail::ManifoldState;

TEST(ManifoldState, NeverSolvedCountsAsSolvedInNoStepBefore) {
    // A manifold never solved keeps solverStep at ~0. In the World's first step
    // (stepCount 0) "the step before" is stepCount - 1, which wraps around to that same
    // ~0: the test must still say no.
    ManifoldState m;
    EXPECT_FALSE(m.solvedInStepBefore(0));
    EXPECT_FALSE(m.solvedInStepBefore(1));
    EXPECT_FALSE(m.solvedInStepBefore(1000));
}

TEST(ManifoldState, SolvedInStepFiveIsSolvedInTheStepBeforeSixOnly) {
    ManifoldState m;
    m.solverStep = 5;
    EXPECT_TRUE(m.solvedInStepBefore(6));
    EXPECT_FALSE(m.solvedInStepBefore(5));  // solved in this step, not the one before
    EXPECT_FALSE(m.solvedInStepBefore(7));  // two steps ago
    EXPECT_FALSE(m.solvedInStepBefore(0));
}

}  // namespace
}  // namespace cyclone::test
