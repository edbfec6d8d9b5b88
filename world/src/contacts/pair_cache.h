// Contact pairs that persist across steps: their manifolds, the anchors of each point
// in both bodies' frames, and the impulses that warm-start the solver.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "cyclone/core.h"
#include "collision/narrowphase.h"
#include "contacts/pose_change.h"
#include "world/block_array.h"

namespace cyclone::detail {

/// A contact point as it persists from one step to the next.
struct PersistentPoint {
    Vector3 localA = Vector3::Zero();  ///< Anchor on A, A's body space, m.
    Vector3 localB = Vector3::Zero();  ///< Anchor on B, B's body space, m.
    real depth = 0;                    ///< Penetration, m (< 0: apart, speculative).
    real normalImpulse = 0;            ///< Last step's accumulated normal impulse, N s.
    /// Its place in the manifold when its anchors were set: it stays with the point when
    /// the points are put in another order (jacobian_stamp.h).
    int id = 0;
};

struct ManifoldState {
    Vector3 normal = Vector3::UnitY();       ///< World space, from A to B.
    Vector3 localNormal = Vector3::UnitY();  ///< The normal in A's body space.
    int count = 0;
    PersistentPoint points[Manifold::kMaxPoints];
    Vector3 frictionImpulse = Vector3::Zero();  ///< Last step's patch friction impulse, world, N s.
    real twistImpulse = 0;  ///< Last step's twist friction impulse about the normal, N m s.
    /// Which set of anchors its points have: a number no other set in the world had
    /// (ContactManager::countAnchors hands them out), so that equal numbers mean the same anchors.
    std::uint64_t anchorsId = 0;
    std::uint32_t solverSlot = 0;  ///< Its solver slot in step solverStep (ConstraintSolver::assignSlots).
    std::uint64_t solverStep = ~std::uint64_t(0);  ///< The last step it was solved in (~0: never).
    /// Whether it was solved in the step before step `stepCount` (never in the first step,
    /// where `stepCount - 1` would wrap around to the "never" above).
    bool solvedInStepBefore(std::uint64_t stepCount) const {
        return stepCount > 0 && solverStep == stepCount - 1;
    }
    int childA = 0;  ///< The child of A it touches when A is a compound, else 0.
    int childB = 0;  ///< The child of B it touches when B is a compound, else 0.
    /// B seen from A when the pair was last tested (all of a pair's manifolds hold the
    /// same): manifold reuse reads it, and only a touching pair has a manifold to hold it.
    RelativePose tested;
};

/// Which manifold of which pair: a PairCache slot and an index in PairState::manifolds.
struct ManifoldRef {
    std::uint32_t pair = 0;
    std::uint32_t index = 0;
};

/// What the narrowphase reads of every candidate pair, in one cache line: a pile's pairs
/// are visited in the broadphase's order, not the slots', and each visit missed the cache
/// twice when the pair's relative pose (read only while it touches) sat between these
/// fields (its manifolds hold it now: ManifoldState::tested).
struct alignas(64) PairState {
    std::uint32_t a = 0;  ///< Body index of A (the smaller index).
    std::uint32_t b = 0;  ///< Body index of B.
    std::uint64_t lastSeen = 0;   ///< Step in which the broadphase last reported the pair.
    bool alive = false;
    /// At its last test both bodies stood still (no velocity, no fall) and it found no
    /// contact: while both stand still and neither pose changes (SeenState), it stands.
    bool testedStill = false;
    std::uint64_t testedStep = 0;  ///< Step of its last narrowphase test.
    std::vector<ManifoldState> manifolds;
    bool touching() const { return !manifolds.empty(); }
};
static_assert(sizeof(PairState) == 64, "a pair's state fills one cache line");

class PairCache {
public:
    friend struct StateFields;  ///< Saves and restores the state (snapshot/world_state_io.cpp).
    /// The pair of bodies i and j (any order), created if new; returns its index.
    std::uint32_t findOrAdd(std::uint32_t i, std::uint32_t j, bool &created);
    /// Index of the pair of i and j, or -1.
    long find(std::uint32_t i, std::uint32_t j) const;
    /// Whether slot `pair` holds the live pair of bodies i and j (any order): a cheap
    /// check of a slot remembered from an earlier step, with no table look-up.
    bool holds(std::uint32_t pair, std::uint32_t i, std::uint32_t j) const {
        if (pair >= pairs_.size() || !pairs_[pair].alive) return false;
        return pairs_[pair].a == std::min(i, j) && pairs_[pair].b == std::max(i, j);
    }
    void remove(std::uint32_t pair);
    PairState &operator[](std::uint32_t pair) { return pairs_[pair]; }
    const PairState &operator[](std::uint32_t pair) const { return pairs_[pair]; }
    /// Asks the cache for slot `pair`'s state ahead of a visit: a walk over the step's
    /// pairs in the broadphase's order jumps between slots.
    void prefetch(std::uint32_t pair) const { __builtin_prefetch(&pairs_[pair]); }
    /// How many pairs ahead such a walk asks for a pair's state.
    static constexpr std::size_t kPrefetchAhead = 8;
    /// For a walk over `slots` (up to `end`) at `k`: asks for the state of the pair
    /// kPrefetchAhead on, when there is one with a slot (a candidate not in the table yet
    /// has none).
    void prefetchAhead(const std::vector<std::uint32_t> &slots, std::size_t k, std::size_t end) const {
        if (k + kPrefetchAhead < end && slots[k + kPrefetchAhead] < pairs_.size()) prefetch(slots[k + kPrefetchAhead]);
    }
    /// Every slot, alive or not (check PairState::alive).
    std::size_t slots() const { return pairs_.size(); }

private:
    static std::uint64_t key(std::uint32_t i, std::uint32_t j) {
        if (i > j) std::swap(i, j);
        return (std::uint64_t(i) << 32) | j;
    }
    /// The table position of `key`, or of the empty entry where it would go.
    std::size_t position(std::uint64_t key) const;
    void insert(std::uint64_t key, std::uint32_t slot);
    void erase(std::uint64_t key);

    // In blocks: a pile's pairs are many (11 per body in a landing pile), and a
    // std::vector that outgrows its room holds twice as many for good.
    BlockArray<PairState> pairs_;
    std::vector<std::uint32_t> free_;
    // Pair slots by key, open addressing with linear probing: unlike a node-based map it
    // allocates only when it grows, so pairs that come and go cost no allocation.
    struct Entry {
        std::uint64_t key = kEmpty;
        std::uint32_t slot = 0;
    };
    static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);  ///< No pair has it (i < j).
    std::vector<Entry> table_;  ///< Size a power of two, at most half full.
    std::size_t used_ = 0;
};

/// Refreshes `m` from the bodies' current poses using its anchors (no narrowphase):
/// world normal from A's frame, depth from the anchors' separation along it, points put
/// in the order the narrowphase gives a fresh manifold (contactOrder), impulses kept.
void refreshFromAnchors(ManifoldState &m, const Matrix4 &poseA, const Matrix4 &poseB);

/// Refreshes the manifolds from their anchors and keeps only the points whose anchors
/// are less than `distance` apart; drops manifolds left empty. Each manifold kept is
/// numbered as a new set of anchors from `anchorsIssued` (counted up).
void keepNearPoints(std::vector<ManifoldState> &manifolds, const Matrix4 &poseA, const Matrix4 &poseB, real distance,
                    std::uint64_t &anchorsIssued);

/// Replaces `state` with `fresh`, carrying each old point's impulses to the new point
/// whose anchor on A lies within `matchDistance` (warm starting), or, on a side that is
/// round there (collision/round_side.h; shapeA and shapeB are the bodies' shapes), whose
/// anchor lies over the same point of the core: a rolling body's contact point moves on
/// both bodies, but stays below the same point of its core. The new anchors are numbered
/// `anchorsId`. `state` must be the manifold of the same children (or of none).
void mergeManifold(ManifoldState &state, const Manifold &fresh, const Matrix4 &poseA, const Matrix4 &poseB,
                   const CollisionShape &shapeA, const CollisionShape &shapeB, real matchDistance,
                   std::uint64_t anchorsId);

}  // namespace cyclone::detail
