// Bodies placed in a broadphase tree wait until the tree is read, then go in one by one or
// by a top-down rebuild (Broadphase::flush): adding n boxes at one point used to chain
// them into a tree n deep and rebalance it at every add (issue 34, item 6: 20,000 took
// 57 s).
#include <gtest/gtest.h>

#include <fcl/fcl.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "collision/broadphase.h"

namespace cyclone {
namespace {

using detail::Broadphase;
using detail::Tree;

struct Boxes {
    std::shared_ptr<fcl::Boxd> geometry = std::make_shared<fcl::Boxd>(1, 1, 1);
    std::vector<std::unique_ptr<detail::BodyObject>> objects;

    fcl::CollisionObjectd *add(const fcl::Vector3d &at) {
        fcl::Transform3d pose = fcl::Transform3d::Identity();
        pose.translation() = at;
        auto object = std::make_unique<detail::BodyObject>(geometry, pose);
        object->setUserData(reinterpret_cast<void *>(static_cast<std::uintptr_t>(objects.size())));
        object->place(pose, detail::kBroadphaseMargin);
        objects.push_back(std::move(object));
        return objects.back().get();
    }
};

int height(const fcl::detail::NodeBase<fcl::AABBd> *node) {
    if (node == nullptr) return 0;
    if (node->isLeaf()) return 1;
    return 1 + std::max(height(node->children[0]), height(node->children[1]));
}

// 5,000 boxes at one point: the first read rebuilds the tree from all of them at once.
// FCL's top-down build halves the leaves at the median while more than 16 remain
// (ceil(log2(5000 / 16)) = 9 levels) and joins the last 16 or fewer bottom-up (at most 15
// more levels), so the tree is at most 1 + 9 + 15 = 25 deep, where inserting them one by
// one chains them 5,000 deep.
TEST(BroadphaseArrivals, ManyBoxesAtOnePointMakeAShallowTree) {
    Broadphase broadphase;
    Boxes boxes;
    for (int i = 0; i < 5000; ++i) broadphase.place(boxes.add(fcl::Vector3d(0, 0.5, 0)), Tree::None, Tree::Awake);
    const auto *root = broadphase.root(Tree::Awake);
    EXPECT_EQ(broadphase.rebuiltLeaves(), 5000u);
    EXPECT_EQ(broadphase.insertedLeaves(), 0u);
    EXPECT_LE(height(root), 25);
    // Fewer than half the tree's leaves arriving go in one by one: 10 more, each at most
    // one level deeper.
    for (int i = 0; i < 10; ++i) broadphase.place(boxes.add(fcl::Vector3d(0, 0.5, 0)), Tree::None, Tree::Awake);
    root = broadphase.root(Tree::Awake);
    EXPECT_EQ(broadphase.rebuiltLeaves(), 0u);
    EXPECT_EQ(broadphase.insertedLeaves(), 10u);
    EXPECT_LE(height(root), 35);
    // As many again as the tree holds: rebuilt, shallow again (5,010 + 5,010 leaves:
    // ceil(log2(10020 / 16)) = 10 levels, at most 1 + 10 + 15 = 26).
    for (int i = 0; i < 5010; ++i) broadphase.place(boxes.add(fcl::Vector3d(0, 0.5, 0)), Tree::None, Tree::Awake);
    root = broadphase.root(Tree::Awake);
    EXPECT_EQ(broadphase.rebuiltLeaves(), 10020u);
    EXPECT_LE(height(root), 26);
}

// Every pair of 100 coincident boxes is found (100 x 99 / 2 = 4,950), one of them moved
// to the static tree still pairs with the 99 awake ones, and a box removed while waiting
// leaves no pair.
TEST(BroadphaseArrivals, WaitingBoxesAreFoundRemovedAndMoved) {
    Broadphase broadphase;
    Boxes boxes;
    std::vector<fcl::CollisionObjectd *> placed;
    for (int i = 0; i < 101; ++i) {
        placed.push_back(boxes.add(fcl::Vector3d(0, 0.5, 0)));
        broadphase.place(placed.back(), Tree::None, Tree::Awake);
    }
    broadphase.place(placed[100], Tree::Awake, Tree::None);
    detail::BroadphasePairs pairs;
    EXPECT_TRUE(broadphase.findPairs(pairs, nullptr, 1u << 20));
    EXPECT_EQ(pairs.contacts.size(), 4950u);
    for (const detail::CandidatePair &pair : pairs.contacts) {
        EXPECT_NE(pair.a, 100u);
        EXPECT_NE(pair.b, 100u);
    }
    broadphase.place(placed[0], Tree::Awake, Tree::Static);
    pairs.clear();
    EXPECT_TRUE(broadphase.findPairs(pairs, nullptr, 1u << 20));
    EXPECT_EQ(pairs.contacts.size(), 4950u);  // 99 x 98 / 2 awake pairs + 99 with the static one
    // A box far away overlaps none of them.
    broadphase.place(boxes.add(fcl::Vector3d(10, 0.5, 0)), Tree::None, Tree::Awake);
    pairs.clear();
    EXPECT_TRUE(broadphase.findPairs(pairs, nullptr, 1u << 20));
    EXPECT_EQ(pairs.contacts.size(), 4950u);
}

}  // namespace
}  // namespace cyclone
