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
#include "world/task_pool.h"

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

// An 8 x 8 x 8 grid of awake unit boxes 0.9 m apart over a layer of 8 x 8 static ones:
// boxes overlap where their grid places differ by at most one along every axis (0.9 m
// apart along an axis, 1.04 m across with the margin; 1.8 m apart, not). In a grid of n
// along an axis, the offsets d in {-1, 0, 1} give n - |d| places each, so the awake pairs
// are ((n + 2 (n - 1))^3 - n^3) / 2 = (22^3 - 512) / 2 = 5,068 and the static layer's with
// the bottom layer (n + 2 (n - 1))^2 = 484.
struct Grid {
    Boxes boxes;
    Broadphase broadphase;
    Grid() {
        for (int x = 0; x < 8; ++x)
            for (int z = 0; z < 8; ++z) {
                for (int y = 0; y < 8; ++y)
                    broadphase.place(boxes.add(fcl::Vector3d(0.9 * x, 0.9 * y, 0.9 * z)), Tree::None, Tree::Awake);
                broadphase.place(boxes.add(fcl::Vector3d(0.9 * x, -0.9, 0.9 * z)), Tree::None, Tree::Static);
            }
    }
};

bool samePairs(const std::vector<detail::CandidatePair> &x, const std::vector<detail::CandidatePair> &y) {
    return x.size() == y.size() && std::equal(x.begin(), x.end(), y.begin(), [](const auto &p, const auto &q) {
               return p.a == q.a && p.b == q.b;
           });
}

// The walk cut into pieces finds every pair once, and the same list in the same order
// whether its pieces run in order, backwards, or on two threads.
TEST(BroadphaseWalk, PiecesOnAnyThreadsGiveOneWalksPairsInItsOrder) {
    Grid grid;
    detail::BroadphasePairs inOrder;
    EXPECT_TRUE(grid.broadphase.findPairs(inOrder, nullptr, 1u << 20));
    EXPECT_GE(grid.broadphase.walkPieces(), 32);  // cut until there are 32 or more
    EXPECT_EQ(inOrder.contacts.size(), 5068u + 484u);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> unique;
    for (const detail::CandidatePair &pair : inOrder.contacts)
        unique.emplace_back(std::min(pair.a, pair.b), std::max(pair.a, pair.b));
    std::sort(unique.begin(), unique.end());
    EXPECT_EQ(std::unique(unique.begin(), unique.end()), unique.end());

    grid.broadphase.invalidate();
    detail::BroadphasePairs backwards;
    EXPECT_TRUE(grid.broadphase.findPairs(backwards, nullptr, 1u << 20, [](int count, const auto &task) {
        for (int i = count - 1; i >= 0; --i) task(i);
    }));
    EXPECT_TRUE(samePairs(backwards.contacts, inOrder.contacts));

    detail::TaskPool pool(2);
    grid.broadphase.invalidate();
    detail::BroadphasePairs threaded;
    EXPECT_TRUE(grid.broadphase.findPairs(threaded, nullptr, 1u << 20,
                                          [&](int count, const auto &task) { pool.run(count, [&](int i, int) { task(i); }); }));
    EXPECT_TRUE(samePairs(threaded.contacts, inOrder.contacts));
}

// Past the limit the walk keeps the first pairs of its order, on two threads as on one,
// and says that it left some out.
TEST(BroadphaseWalk, PastTheLimitTheFirstPairsOfTheOrderAreKept) {
    Grid grid;
    detail::BroadphasePairs all;
    EXPECT_TRUE(grid.broadphase.findPairs(all, nullptr, 1u << 20));
    detail::TaskPool pool(2);
    grid.broadphase.invalidate();
    detail::BroadphasePairs first;
    EXPECT_FALSE(grid.broadphase.findPairs(first, nullptr, 1000,
                                           [&](int count, const auto &task) { pool.run(count, [&](int i, int) { task(i); }); }));
    ASSERT_EQ(first.contacts.size(), 1000u);
    EXPECT_TRUE(samePairs(first.contacts, {all.contacts.begin(), all.contacts.begin() + 1000}));
}

}  // namespace
}  // namespace cyclone
