// A compound pair's work is bounded (issue 61): five compounds of 300 children spawned at
// one point had 300 x 300 = 90,000 child pairs whose boxes met in each of their 10 pairs
// and took 1.0-1.5 s a step, for a pair that keeps 32 manifolds at most.
#include <gtest/gtest.h>

#include <vector>

#include "collision_test_support.h"

namespace cyclone::test {
namespace {

// 300 cubes of half size 0.05 along a helix (radius 0.5, 0.3 rad and 2 mm of rise apart).
Shape helixCompound(int children) {
    std::vector<CompoundChild> parts;
    for (int i = 0; i < children; ++i) {
        CompoundChild child;
        child.shape = Shape::box(Vector3(0.05, 0.05, 0.05));
        child.position = Vector3(0.5 * std::cos(0.3 * i), 0.002 * i, 0.5 * std::sin(0.3 * i));
        parts.push_back(child);
    }
    return Shape::compound(parts);
}

// Two such compounds at one pose: every child meets itself in the other (boxes
// coincident, overlapping by their full 0.1 m) and its neighbours within 0.1 m, more
// child pairs than the budget. collide() tests at most kMaxChildPairs = 256 of them, each
// giving one manifold; the deepest overlap, 0.1 m, is a child with its own twin.
TEST(CompoundBudget, CoincidentCompoundsTestAtMostTheBudget) {
    const auto a = detail::compileShape(helixCompound(300));
    std::vector<Manifold> out;
    detail::collide(*a, Matrix4::Identity(), *a, Matrix4::Identity(), detail::NarrowphaseSettings(), out);
    EXPECT_GT(out.size(), 0u);
    EXPECT_LE(out.size(), 256u);
    bool twin = false;
    for (const Manifold &m : out) twin = twin || m.childA == m.childB;
    EXPECT_TRUE(twin);
}

// Below the budget nothing changes: 10 children give each child its own twin and at
// most its two neighbours on the helix (0.3 rad x 0.5 m = 0.15 m apart, over the 0.1 m
// box: they do not meet), so 10 child pairs, 10 manifolds, in (i, j) order.
TEST(CompoundBudget, SmallCompoundsTestEveryPairThatMeets) {
    const auto a = detail::compileShape(helixCompound(10));
    std::vector<Manifold> out;
    detail::collide(*a, Matrix4::Identity(), *a, Matrix4::Identity(), detail::NarrowphaseSettings(), out);
    ASSERT_EQ(out.size(), 10u);
    for (std::size_t k = 0; k < out.size(); ++k) {
        EXPECT_EQ(out[k].childA, static_cast<int>(k));
        EXPECT_EQ(out[k].childB, static_cast<int>(k));
    }
}

}  // namespace
}  // namespace cyclone::test
