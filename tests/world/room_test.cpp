// makeRoom and resizeAnew: a short list's room grows by an eighth (plus 16), or to what
// is asked if that is more; a list with room enough is left alone.
#include <gtest/gtest.h>

#include <vector>

#include "world/room.h"

namespace cyclone::test {
namespace {

TEST(MakeRoom, GrowsAShortListByAnEighth) {
    std::vector<int> list;
    list.reserve(800);
    list.resize(800);
    detail::makeRoom(list);
    EXPECT_EQ(list.capacity(), 800u + 100u + 16u);
    EXPECT_EQ(list.size(), 800u);  // the items stay
    const int *data = list.data();
    detail::makeRoom(list, 116);  // 916 fit: nothing moves
    EXPECT_EQ(list.data(), data);
    EXPECT_EQ(list.capacity(), 916u);
    detail::makeRoom(list, 500);  // 1,300 asked: more than an eighth
    EXPECT_EQ(list.capacity(), 1300u);
    std::vector<int> empty;
    detail::makeRoom(empty);
    EXPECT_EQ(empty.capacity(), 16u);
}

// An empty list with room for 800 asked for 900: 800 + 100 + 16. resizeAnew grows the
// same way and keeps its room when it shrinks.
TEST(MakeRoom, AnEmptyListAndAResizedOneGrowByAnEighth) {
    std::vector<double> list;
    list.reserve(800);
    detail::makeRoom(list, 900);
    EXPECT_EQ(list.capacity(), 916u);
    EXPECT_TRUE(list.empty());
    std::vector<double> slots(100, 1.0);
    detail::resizeAnew(slots, 200);
    EXPECT_EQ(slots.size(), 200u);
    EXPECT_EQ(slots.capacity(), 200u);  // 100 + 12 + 16 is less than asked
    detail::resizeAnew(slots, 201);
    EXPECT_EQ(slots.capacity(), 200u + 25u + 16u);
    detail::resizeAnew(slots, 50);
    EXPECT_EQ(slots.size(), 50u);
    EXPECT_EQ(slots.capacity(), 241u);
}

}  // namespace
}  // namespace cyclone::test
