// The landing correction: after the step's integration (and continuous collision), the
// candidate pairs in which a body moved fast this step are tested again at the poses the
// step ends with, and the points found deeper than a tolerance are pushed apart by
// position only, so that no frame shows a body sunk in another (WorldSettings::
// landingCorrection).
//
// Design note. The step's contacts come from its start. A body landing on a pile that is
// itself still landing may be let through by the solver (ten passes do not carry a
// column's impulse within one step), and a body landing on one or two points turns about
// them so that its far side plunges where the step's manifold had no point: within the
// step, the motion makes overlaps that no contact of the step's start sees
// (docs/solver.md, "Landing correction"). Here the narrowphase runs once more, on the
// step's candidate pairs with a fast body only, and nonlinear Gauss-Seidel passes over
// the fresh points, lowest first, translate each point's two bodies apart along its
// normal, split by their inverse masses, until it is no deeper than half the tolerance.
// Translation only: two convex shapes moved apart by d along a normal along which they
// overlap by p overlap by at most p - d, so a push never leaves a pair deeper elsewhere,
// which a turn (splitting by the inertias too) does on round sides. Velocities are left
// as they are (the next step's contacts, now touching, stop the bodies), but for a body
// in an island of its own lifted against gravity, which pays the lift (payForLift).
// Only the fast bodies move: every pair of theirs is tested, so a push meets every
// neighbour it can reach. A body that hardly moved made none of the overlap, and its
// pairs with third bodies are not tested: pushed, it would go unseen into the ground
// under it. The bodies of a pair the step began deep in (kRestingFactor tolerances: sunk under
// a pile's load) count as fast, and a body resting on one of them is lifted with it
// rather than let the push drive it back down (liftAbove). Static, kinematic and
// sleeping bodies are immovable (a body woken by this step's contacts was solved in it,
// and moves). Bodies held together by joints move as one group,
// all by the same translation, which opens no joint (a hinge's or slider's angles and a
// distance joint's length depend only on the members' relative poses): a fast member
// makes the whole group fast, so that every member's pairs are tested, and a group joined
// to the world or to a body that may not move does not move.
// A pair of convex shapes (or compounds) that overlaps along one axis (its normal at the
// step's start, else the line between the bodies) by no more than the passes' target has
// no point to push: two support points say so, and only the other pairs go through the
// narrowphase (in a landing pile of 1,000 bodies, 7 % of the pairs listed). The points of
// such a pair's start manifolds, held by their anchors, stand guard in the passes.
// The points of every manifold found are kept, the shallow ones too, and shapes a hair
// apart give points (WorldSettings::speculativeDistance, for the pairs with a test of
// their own), so that a push does not drive a body into a neighbour the round tested;
// the pairs of the bodies a round moved are tested afresh in the next (at most kRounds
// in all). The pairs' manifolds, impulses and touching states are not touched, so no
// contact event changes; what FCL found at these poses goes on to the next step's
// narrowphase (ContactManager's end normals), which starts from them. A step in which no body moved fast and no pair is deep costs
// one pose comparison per awake body and one depth comparison per contact point.
#pragma once

#include <cstdint>
#include <vector>

#include "collision/narrowphase.h"
#include "contacts/pair_cache.h"
#include "cyclone/world/stats.h"
#include "cyclone/world/settings.h"
#include "world/chunk_lists.h"
#include "world/body_store.h"

namespace cyclone::detail {

class ContactManager;
class Islands;
class JointSet;
class PreSolve;
struct StepContext;
class Workers;

class LandingCorrection {
public:
    /// Tests again the step's candidate pairs with a fast body at the bodies' poses now,
    /// and pushes apart by position the points deeper than the tolerance.
    void correct(const StepContext &context, BodyStore &bodies, ContactManager &contacts, const PreSolve &preSolve,
                 const JointSet &joints, const Islands &islands, StepStats &stats);

private:
    /// A point of a manifold found at the end of the step, held by anchors on both bodies
    /// so that its depth follows the bodies as the passes move them.
    struct Point {
        std::uint32_t a = 0, b = 0;          ///< Body indices.
        Vector3 localA = Vector3::Zero();    ///< Anchor on A, A's body space, m.
        Vector3 localB = Vector3::Zero();    ///< Anchor on B, B's body space, m.
        Vector3 localNormal = Vector3::Zero();  ///< Normal A to B in A's body space.
        real target = 0;                     ///< Depth the passes push it back to, m.
        real height = 0;                     ///< Along -gravity: the passes go lowest first.
        std::uint32_t order = 0;             ///< Place in the rounds' pair walks: breaks ties in height.
        /// The push count (pushes_) when a pass last found it no deeper than its target;
        /// 0 when none has, or a pass found it deeper.
        std::uint64_t shallowAt = 0;
    };

    /// Marks the bodies round 0 moves: those that moved fast this step and those of the
    /// pairs the step began deep in.
    void markFastBodies(const WorldSettings &settings, const BodyStore &bodies, const ContactManager &contacts,
                        const PreSolve &preSolve, Workers &workers, real deepest);
    /// Lists in pairs_ the pairs a round tests: those with a body moved in round `last`.
    void listRoundPairs(const BodyStore &bodies, const ContactManager &contacts, const PreSolve &preSolve,
                        Workers &workers, int last);
    /// Puts points_ lowest first (ties in the pair walks' order); its first `kept` points
    /// are in that order already.
    void orderPoints(std::size_t kept);
    /// Whether body `index` moved in `round`.
    bool movedIn(std::uint32_t index, int round) const;
    static bool appendPoints(const std::vector<Manifold> &out, const PairState &pair,
                             const Matrix4 &poseA, const Matrix4 &poseB, real tolerance, const Vector3 &up,
                             std::vector<Point> &found);
    static void appendAnchored(const PairState &pair, const Matrix4 &poseA, const Matrix4 &poseB, real tolerance,
                               const Vector3 &up, std::vector<Point> &found);
    /// Tests the pairs in pairs_ at the bodies' poses now and appends their manifolds'
    /// points; returns whether one of them is deeper than its pair's tolerance.
    bool detect(const WorldSettings &settings, const BodyStore &bodies, ContactManager &contacts, Workers &workers,
                std::uint64_t stepCount);
    /// Nonlinear Gauss-Seidel passes over points_; marks each body moved as moved in
    /// `round`. Returns how many points were pushed.
    int push(const WorldSettings &settings, BodyStore &bodies, int round);
    /// How much farther a push between two movable bodies may move body `index`, `down`
    /// being the cosine of its direction with gravity (`up` points against it): a round's
    /// pushes kStepReach of the body's size in all, the step's kStepReach down (unbounded
    /// in a joint group), m.
    real reachLeft(const BodyStore &bodies, std::uint32_t index, real down, const Vector3 &up) const;
    /// Per body index: the translation this step's pushes gave it outside joint groups, m.
    std::vector<Vector3> shifts_;
    /// Takes from the body's speed against its pushes the potential energy they gave it.
    void payForLift(BodyStore &bodies, const Islands &islands, const Vector3 &gravity, std::uint32_t index);

    /// Per body index: the last round that moved it (0: it moved fast in the step; -1: none).
    std::vector<int> movedRound_;
    /// Per body index: whether it is in a pair the step began deep in (sunk under a
    /// pile's load) or was lifted off such a body (liftAbove).
    std::vector<char> sunk_;
    /// Bodies held together by joints (directly or through others) form a joint group,
    /// which the passes move as one: all its members by the same translation, so that no
    /// joint opens. Per body index, while the world has joints: its group, named by one
    /// member's index, or -1 outside joints.
    std::vector<int> group_;
    /// Per group (at the index that names it): whether the passes may move it, its
    /// inverse mass (1 / the members' summed mass) and its first member; nextMember_
    /// chains the rest (-1 ends the chain).
    std::vector<char> groupMovable_;
    std::vector<real> groupInverseMass_;
    std::vector<std::int32_t> firstMember_;
    std::vector<std::int32_t> nextMember_;
    /// Builds group_ and the per-group lists from the world's joints; marks every member
    /// of a movable group with a fast member fast too (its pairs are then all tested).
    void buildJointGroups(const BodyStore &bodies, const JointSet &joints);
    /// Counts the body as moved fast in the step (round 0).
    void markFast(std::uint32_t index);
    /// The inverse mass a push of the body moves: its group's, or its own outside joints.
    real pushedInverseMass(const BodyStore &bodies, std::uint32_t index) const;
    /// Moves the body, or every member of its group, by `delta`, noting the moves.
    void translate(BodyStore &bodies, std::uint32_t index, const Vector3 &delta, real length);
    bool movable(const BodyStore &bodies, std::uint32_t index) const;
    /// For a point of which one body may move (A when `moveA`, else B): makes the other,
    /// still one movable (and sunk) when the moving one is sunk and the still one lies
    /// above it (`normalUp`: the point's normal, A to B, along -gravity), so that the push
    /// lifts it rather than drive the sunk body down. Returns whether it did.
    bool liftAbove(const BodyStore &bodies, const Point &point, bool moveA, real normalUp, int round);
    std::vector<std::uint32_t> activeBodies_;  ///< Bodies whose movedRound_ is set (to clear it).
    std::vector<std::uint32_t> pairs_;          ///< The round's pair slots to test.
    std::vector<char> flags_;                   ///< Scratch: what a test on the threads picked.
    std::vector<std::vector<Manifold>> threadFinds_;  ///< Per thread, what the narrowphase found for one pair.
    /// What FCL found for an entry of pairs_ (collide's memo, but for the shapes and poses:
    /// the pair's), for the next step's narrowphase.
    struct Memo {
        std::uint32_t k = 0;  ///< Entry of pairs_.
        bool touching = false;
        Vector3 normal = Vector3::UnitY();
    };
    ChunkLists<Memo> chunkMemos_;  ///< By chunk of pairs_, what FCL's tests found.
    std::vector<Point> points_;
    /// By chunk of pairs_: the points its finds gave (their order not yet set), and
    /// whether one of them lies deeper than its pair's tolerance.
    ChunkLists<Point> chunkPoints_;
    std::vector<char> chunkDeep_;
    /// A point's place in the order the passes take points_ in.
    struct SortKey {
        real height = 0;
        std::uint32_t order = 0;
        std::uint32_t index = 0;  ///< In points_.
    };
    std::vector<SortKey> sortKeys_;
    std::vector<SortKey> mergedKeys_;  ///< The kept and the new keys merged.
    std::uint32_t nextOrder_ = 0;      ///< The order the next point found takes.
    /// Puts points_ in the order of sortKeys_ (sorted: the k-th key names the point that
    /// goes k-th), in place.
    void placeInOrder();
    /// How far a round's passes moved a body in all (the sum of its pushes), m.
    struct Move {
        std::uint32_t body = 0;
        real length = 0;
    };
    std::vector<Move> moved_;
    std::vector<int> moveSlot_;  ///< Per body index: its entry in moved_ (-1: none).
    /// Pushes made so far (never reset), and per body index the count at its last push:
    /// a point found no deeper than its target whose bodies no push has moved since is
    /// not measured again (push).
    std::uint64_t pushes_ = 1;
    std::vector<std::uint64_t> pushedAt_;
    /// Adds a push of `length` to the body's entry in moved_.
    void noteMove(std::uint32_t body, real length);
};

}  // namespace cyclone::detail
