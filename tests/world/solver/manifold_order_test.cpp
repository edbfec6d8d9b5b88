// The solve order of a step's manifolds: by contact height, equal heights in the order
// they were listed (world/src/solver/manifold_order.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "solver/manifold_order.h"

namespace cyclone::test {
namespace {

// Keys listed in the order of `heights`, each with its place in that list as its pair.
std::vector<ManifoldKey> listed(const std::vector<real> &heights) {
    std::vector<ManifoldKey> keys;
    for (std::size_t k = 0; k < heights.size(); ++k) keys.push_back({heights[k], {static_cast<std::uint32_t>(k), 0}});
    return keys;
}

// The places in the list the keys came from, in their order now.
std::vector<std::uint32_t> listedOrder(const std::vector<ManifoldKey> &keys) {
    std::vector<std::uint32_t> order;
    for (const ManifoldKey &k : keys) order.push_back(k.manifold.pair);
    return order;
}

TEST(ManifoldOrder, LowestFirstAndEqualHeightsAsListed) {
    const real inf = std::numeric_limits<real>::infinity();
    // By hand: -inf (a static body's side), then -2, the tiny negative, both zeros as
    // equals (+0 listed before -0), the tiny positive, and the two 1s as listed.
    std::vector<ManifoldKey> keys = listed({1.0, -2.0, 0.0, -0.0, 1.0, -inf, 3e-300, -3e-300, 0.5});
    std::vector<ManifoldKey> scratch;
    detail::sortByHeight(keys, scratch);
    EXPECT_EQ(listedOrder(keys), (std::vector<std::uint32_t>{5, 1, 7, 2, 3, 6, 8, 0, 4}));
    // Each key moved whole: its height went with its manifold.
    const std::vector<real> heights = {1.0, -2.0, 0.0, -0.0, 1.0, -inf, 3e-300, -3e-300, 0.5};
    for (const ManifoldKey &k : keys) EXPECT_EQ(k.height, heights[k.manifold.pair]);
}

TEST(ManifoldOrder, HeightsApartByOneUlpKeepTheirOrder) {
    // A layer of a stack: heights equal but for rounding, the differences in the last
    // bits of the mantissa, which a sort on fewer bits would tie.
    const real h = 2.5;
    const real up = std::nextafter(h, real(10));
    const real down = std::nextafter(h, real(-10));
    std::vector<ManifoldKey> keys = listed({up, h, down, h, up, down});
    std::vector<ManifoldKey> scratch;
    detail::sortByHeight(keys, scratch);
    EXPECT_EQ(listedOrder(keys), (std::vector<std::uint32_t>{2, 5, 1, 3, 0, 4}));
}

TEST(ManifoldOrder, SameAsAStableSortOnManyHeights) {
    // Heights on a few levels with rounding-sized offsets, many equal: against
    // std::stable_sort by height.
    std::vector<real> heights;
    std::uint32_t state = 12345;
    for (int k = 0; k < 1000; ++k) {
        state = state * 1664525u + 1013904223u;
        const int level = static_cast<int>(state >> 28) - 4;  // -4 .. 11
        const int ulps = static_cast<int>((state >> 20) & 7) - 3;
        real h = 0.5 + level;
        for (int u = 0; u < std::abs(ulps); ++u) h = std::nextafter(h, ulps > 0 ? real(100) : real(-100));
        heights.push_back(h);
    }
    std::vector<ManifoldKey> keys = listed(heights);
    std::vector<ManifoldKey> expected = keys;
    std::stable_sort(expected.begin(), expected.end(),
                     [](const ManifoldKey &x, const ManifoldKey &y) { return x.height < y.height; });
    std::vector<ManifoldKey> scratch;
    detail::sortByHeight(keys, scratch);
    EXPECT_EQ(listedOrder(keys), listedOrder(expected));
}

TEST(ManifoldOrder, EmptyAndSingleListsAreLeftAsTheyAre) {
    std::vector<ManifoldKey> none;
    std::vector<ManifoldKey> scratch;
    detail::sortByHeight(none, scratch);
    EXPECT_TRUE(none.empty());
    std::vector<ManifoldKey> one = listed({-7.0});
    detail::sortByHeight(one, scratch);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].height, -7.0);
}

}  // namespace
}  // namespace cyclone::test
