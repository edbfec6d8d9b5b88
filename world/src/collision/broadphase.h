// Broadphase: three FCL dynamic AABB trees (awake, sleeping, static bodies) and the
// planes kept apart (a half-space has an infinite AABB and no place in a tree).
//
// Candidate pairs are awake x awake, awake x sleeping, awake x static and awake x plane:
// a sleeping body's pairs with sleeping or static bodies are never visited, so a large
// sleeping pile costs nothing per step.
#pragma once

#include <fcl/fcl.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace cyclone::detail {

struct StateFields;

/// How far a broadphase box reaches beyond its body, m: a body that moves less than this
/// costs no tree update.
inline constexpr double kBroadphaseMargin = 0.02;

// FCL's AABBd::center() and contain(), inline: FCL defines them out of line, and they
// are called for every awake body every step.
inline fcl::Vector3d boxCentre(const fcl::AABBd &box) { return (box.min_ + box.max_) * 0.5; }
inline bool boxContains(const fcl::AABBd &outer, const fcl::AABBd &inner) {
    return !(outer.min_.array() > inner.min_.array()).any() && !(outer.max_.array() < inner.max_.array()).any();
}

/// The box of `geometry` placed at `pose`, grown by `margin` (m): its local box turned
/// (BodyObject::place's tight box).
inline fcl::AABBd placedBox(const fcl::CollisionGeometryd &geometry, const fcl::Transform3d &pose, double margin = 0) {
    const fcl::AABBd &local = geometry.aabb_local;
    const fcl::Vector3d centre = pose * boxCentre(local);
    const fcl::Vector3d half =
        pose.linear().cwiseAbs() * (0.5 * (local.max_ - local.min_)) + fcl::Vector3d::Constant(margin);
    return fcl::AABBd(centre - half, centre + half);
}

/// Whether the placed boxes of two bounded geometries (not a half-space) lie more than
/// `gap` apart along some axis (m): the shapes in them are then more than `gap` apart.
inline bool boxesApart(const fcl::CollisionGeometryd &a, const fcl::Transform3d &poseA,
                       const fcl::CollisionGeometryd &b, const fcl::Transform3d &poseB, double gap) {
    const fcl::AABBd boxA = placedBox(a, poseA, gap);
    const fcl::AABBd boxB = placedBox(b, poseB);
    return (boxA.min_.array() > boxB.max_.array()).any() || (boxB.min_.array() > boxA.max_.array()).any();
}

/// A body's FCL collision object whose broadphase box is fattened by a margin, so that
/// a body moving a little stays in its tree node and the tree is not rebuilt each step.
class BodyObject : public fcl::CollisionObjectd {
public:
    friend struct StateFields;  ///< Saves and restores the fat box (snapshot/world_state_io.cpp).
    using fcl::CollisionObjectd::CollisionObjectd;

    /// Places the object at `pose` and refreshes its fat box; true when the tight box,
    /// grown by `reach` (how far the body can move before the next refit, m), left the fat
    /// one (the tree must then be updated).
    bool place(const fcl::Transform3d &pose, double margin, double reach = 0) {
        setTransform(pose);
        // FCL's computeAABB bounds a rotated shape by its bounding sphere (a rotated unit
        // box gets a 1.73 m box); the rotated local box is much tighter.
        aabb = placedBox(*collisionGeometry(), pose, reach);
        if (boxContains(fat_, aabb)) {
            aabb = fat_;
            return false;
        }
        fat_ = aabb;
        fat_.expand(fcl::Vector3d::Constant(margin));
        aabb = fat_;
        return true;
    }

private:
    fcl::AABBd fat_;
};

/// Which tree a body's collision object is in.
enum class Tree : std::uint8_t { None, Awake, Asleep, Static };

/// A candidate pair of body indices (unordered).
struct CandidatePair {
    std::uint32_t a;
    std::uint32_t b;
};

/// What becomes of a pair of overlapping boxes.
enum class PairKind : std::uint8_t {
    Contact,   ///< A candidate contact, for the narrowphase.
    Sensor,    ///< A sensor and a body it sees, for the sensors' overlap test.
    Filtered,  ///< Never tested: layers, a pair rule, or two sensors.
};

/// Sorts pairs in the broadphase callback, so that filtered pairs never become candidates.
class PairFilter {
public:
    /// What the pair of bodies i and j is.
    virtual PairKind classify(std::uint32_t i, std::uint32_t j) const = 0;

protected:
    ~PairFilter() = default;
};

/// The pairs of one broadphase walk, sorted by kind.
struct BroadphasePairs {
    std::vector<CandidatePair> contacts;  ///< Candidate contacts.
    std::vector<CandidatePair> sensors;   ///< A sensor and a body it sees (either order).
    int filtered = 0;                     ///< Pairs dropped.

    void clear() {
        contacts.clear();
        sensors.clear();
        filtered = 0;
    }
};

class Broadphase {
public:
    friend struct StateFields;  ///< Saves and restores the state (snapshot/world_state_io.cpp).
    Broadphase();

    /// Puts `object` (whose user data is its body index) into `tree`, moving it out of
    /// the tree it was in. O(1) into a tree: the object waits in the tree's list of
    /// arrivals until something reads the tree (flush()).
    void place(fcl::CollisionObjectd *object, Tree from, Tree to);
    /// Inserts the arrivals waiting for each tree: one by one (FCL's insertion, which
    /// descends the tree) while they are fewer than half the tree's leaves, else by
    /// rebuilding the tree top-down from its leaves and the arrivals (O(n log n)). Adding
    /// n bodies then costs O(n log n) whatever their places: inserted one by one, n boxes
    /// at one point would chain into a tree n deep (each insertion descending all of it).
    /// Called by every reader below; safe to call from concurrent const calls.
    void flush() const;
    /// Leaves the last flush() rebuilt (for tests: how much work arrivals cost).
    std::uint64_t rebuiltLeaves() const { return rebuiltLeaves_; }
    /// Leaves the last flush() inserted one by one.
    std::uint64_t insertedLeaves() const { return insertedLeaves_; }
    /// Refits the awake tree after the objects in `moved` changed their AABBs.
    void refitAwake(const std::vector<fcl::CollisionObjectd *> &moved);
    /// Refits one object in `tree` after its box moved.
    void refit(fcl::CollisionObjectd *object, Tree tree);
    /// Appends every pair of overlapping AABBs with at least one awake member to
    /// `out.contacts`, or, with a `filter`, each where the filter says, at most `limit` of
    /// them (contacts and sensor pairs together): the walk stops at the limit, so the pairs
    /// kept are the first ones of the trees' fixed order. Returns false when pairs were
    /// left out. When no tree has changed since the last call (and invalidate() was not
    /// called, and the filter and limit are the same), the pairs (and their order) are the
    /// same: they are given again without walking the trees. Without a filter nothing is
    /// asked per pair.
    ///
    /// The walk is FCL's (the awake tree against itself, then against the sleeping and the
    /// static trees; at each pair of nodes the larger box is split), cut into pieces at
    /// its top: `forEachTask(count, task)` runs task(i) for each i in [0, count), on
    /// several threads at once or not (Workers::forEachTask), and the pieces' pairs are
    /// joined in the order one walk would give them, so that the pairs do not depend on
    /// the thread count. A walk that passes the limit is made again in one piece.
    template <class ForEachTask>
    bool findPairs(BroadphasePairs &out, const PairFilter *filter, std::size_t limit, const ForEachTask &forEachTask) {
        if (mustWalk(filter, limit)) {
            const int pieces = cutWalk();
            forEachTask(pieces, [&](int piece) { walkPiece(piece, filter, limit); });
            joinWalk(filter, limit);
        }
        out.contacts.insert(out.contacts.end(), pairs_.contacts.begin(), pairs_.contacts.end());
        out.sensors.insert(out.sensors.end(), pairs_.sensors.begin(), pairs_.sensors.end());
        out.filtered += pairs_.filtered;
        return complete_;
    }
    /// The same on the calling thread alone.
    bool findPairs(BroadphasePairs &out, const PairFilter *filter, std::size_t limit) {
        return findPairs(out, filter, limit, [](int count, const auto &task) {
            for (int i = 0; i < count; ++i) task(i);
        });
    }
    /// Pieces the last walk was cut into (for tests: whether threads can share it).
    int walkPieces() const { return pieceCount_; }
    /// The next findPairs() walks the trees: what a filter says of some pair changed.
    void invalidate() { changed_ = true; }
    /// The root of `tree`'s hierarchy (null when empty), for queries that walk it; a
    /// leaf's data is its collision object.
    const fcl::detail::NodeBase<fcl::AABBd> *root(Tree tree) const;
    /// Appends the body index of every object, in any tree, whose box overlaps `box`
    /// (continuous collision's candidates along a sweep).
    void overlapping(const fcl::AABBd &box, std::vector<std::uint32_t> &out);
    /// Counts the changes to the trees (objects placed, moved or refitted): a walk of a
    /// tree is invalid once it changes.
    std::uint64_t changes() const { return changes_; }

private:
    // Mutable: flush() inserts waiting arrivals on behalf of const readers (queries).
    mutable fcl::DynamicAABBTreeCollisionManagerd awake_;
    mutable fcl::DynamicAABBTreeCollisionManagerd asleep_;
    mutable fcl::DynamicAABBTreeCollisionManagerd static_;
    /// Objects placed in each tree (Awake, Asleep, Static) and not yet inserted.
    mutable std::vector<fcl::CollisionObjectd *> arrivals_[3];
    mutable std::atomic<bool> waiting_{false};  ///< Whether any arrivals_ is not empty.
    mutable std::mutex flushing_;                ///< Held by the flush() that inserts them.
    mutable std::uint64_t rebuiltLeaves_ = 0;    ///< See rebuiltLeaves().
    mutable std::uint64_t insertedLeaves_ = 0;   ///< See insertedLeaves().
    std::unique_ptr<fcl::CollisionObjectd> probe_;  ///< Carries the box of overlapping().
    BroadphasePairs pairs_;  ///< What findPairs() found when it last walked the trees.
    bool changed_ = true;               ///< Whether a tree changed since then.
    const PairFilter *lastFilter_ = nullptr;  ///< The filter of that walk.
    std::uint64_t changes_ = 0;         ///< See changes().
    std::size_t limit_ = 0;             ///< The limit of that walk.
    bool complete_ = true;              ///< Whether that walk found every pair.

    /// A piece of the walk: the pairs within the subtree `first` (no `second`), or between
    /// the subtrees `first` and `second`.
    struct WalkNodes {
        const fcl::detail::NodeBase<fcl::AABBd> *first = nullptr;
        const fcl::detail::NodeBase<fcl::AABBd> *second = nullptr;
    };
    /// A piece and the pairs it found.
    struct WalkPiece {
        WalkNodes nodes;
        BroadphasePairs pairs;
    };
    std::vector<WalkPiece> pieces_;  ///< The pieces of the walk (their lists kept between steps).
    std::vector<WalkNodes> cut_, nextCut_;  ///< cutWalk()'s scratch.
    int pieceCount_ = 0;             ///< Pieces in use.
    std::atomic<std::size_t> walked_{0};  ///< Pairs the pieces found, all kinds.

    fcl::DynamicAABBTreeCollisionManagerd *manager(Tree tree) const;
    void flushTree(Tree tree) const;
    /// Whether the trees must be walked (else the last walk's pairs stand); flushes them.
    bool mustWalk(const PairFilter *filter, std::size_t limit);
    /// Cuts the walk into pieces, in the walk's order; returns how many.
    int cutWalk();
    /// Walks piece `piece` into its own list. Safe to call for different pieces at once.
    void walkPiece(int piece, const PairFilter *filter, std::size_t limit);
    /// Joins the pieces' pairs into pairs_, or, when they passed the limit, walks again
    /// in one piece, which stops at the limit.
    void joinWalk(const PairFilter *filter, std::size_t limit);
};

/// The body index stored in a collision object's user data.
inline std::uint32_t bodyIndexOf(const fcl::CollisionObjectd *object) {
    return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(object->getUserData()));
}

}  // namespace cyclone::detail
