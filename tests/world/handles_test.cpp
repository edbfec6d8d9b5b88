// Handles as keys: BodyId, JointId and SpringId hash (std::unordered_map) and order
// (std::map), and a handle of a reused slot is a different key from the old one.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

template <typename Id>
Id handle(std::uint32_t index, std::uint32_t generation) {
    Id id;
    id.index = index;
    id.generation = generation;
    return id;
}

// Slot first, then generation: (1, 3) < (1, 5) < (2, 0).
template <typename Id>
void expectOrderedBySlotThenGeneration() {
    std::vector<Id> ids = {handle<Id>(2, 0), handle<Id>(1, 5), handle<Id>(1, 3)};
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(ids, (std::vector<Id>{handle<Id>(1, 3), handle<Id>(1, 5), handle<Id>(2, 0)}));
    EXPECT_FALSE(handle<Id>(1, 3) < handle<Id>(1, 3));
    // Same slot, other generation: different keys, with different hashes here.
    const std::hash<Id> hash;
    EXPECT_EQ(hash(handle<Id>(7, 1)), hash(handle<Id>(7, 1)));
    EXPECT_NE(hash(handle<Id>(7, 1)), hash(handle<Id>(7, 2)));
    std::unordered_set<Id> set = {handle<Id>(7, 1), handle<Id>(7, 2), handle<Id>(7, 1)};
    EXPECT_EQ(set.size(), 2u);
}

TEST(Handles, AllOrderBySlotThenGenerationAndHash) {
    expectOrderedBySlotThenGeneration<BodyId>();
    expectOrderedBySlotThenGeneration<JointId>();
    expectOrderedBySlotThenGeneration<SpringId>();
}

// A game's table of its bodies: a removed body's slot is reused by the next one added, and
// the new handle is a new key (its generation differs), so the old entry is not taken for it.
TEST(Handles, BodiesAreKeysOfMapsAcrossRemoval) {
    WorldFixture f;
    const BodyId crate = f.box(Vector3(0, 1, 0));
    const BodyId ball = f.sphere(Vector3(3, 1, 0));
    std::unordered_map<BodyId, std::string> names = {{crate, "crate"}, {ball, "ball"}};
    std::map<BodyId, int> hits = {{crate, 1}, {ball, 2}};
    f.world.removeBody(crate);
    const BodyId barrel = f.box(Vector3(0, 1, 0));
    EXPECT_EQ(barrel.index, crate.index);  // the slot is reused ...
    EXPECT_NE(barrel, crate);              // ... under a new generation
    EXPECT_EQ(names.count(barrel), 0u);
    EXPECT_EQ(hits.count(barrel), 0u);
    names[barrel] = "barrel";
    EXPECT_EQ(names.size(), 3u);
    EXPECT_EQ(names.at(ball), "ball");
}

}  // namespace
}  // namespace cyclone::test
