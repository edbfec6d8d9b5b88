// The contacts' lifecycle: candidate pairs from the broadphase, the narrowphase (or a
// manifold kept from the last step when its bodies hardly moved), persistent pairs with
// their warm-start impulses, and the contact begin and end events.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "collision/broadphase.h"
#include "collision/narrowphase.h"
#include "contacts/contact_tracks.h"
#include "contacts/pair_cache.h"
#include "cyclone/world/world.h"
#include "world/body_store.h"
#include "world/body_transitions.h"
#include "world/chunk_lists.h"

namespace cyclone::detail {

class JointSet;
struct StepContext;
class Workers;

class ContactManager {
public:
    friend struct StateFields;  ///< Saves and restores the state (snapshot/world_state_io.cpp).
    PairCache pairs;
    /// Pairs touching after this step's narrowphase, in the broadphase's order.
    std::vector<std::uint32_t> touchingPairs;

    /// The broadphase stage: places the awake bodies' collision objects and refits their
    /// boxes in `broadphase`, each grown by how far the body can move in the step, and
    /// lists the candidate pairs (planes tested apart); counts them, and a pair budget
    /// exceeded, in `stats`.
    void findCandidates(const StepContext &context, BodyStore &bodies, Broadphase &broadphase, StepStats &stats);
    /// The narrowphase stage: each candidate's manifolds, kept or made anew (speculative
    /// ones for shapes apart that can meet within the step), but for bodies
    /// whose joints exclude the contact; wakes the sleeping bodies a contact reaches
    /// (through `transitions`), which join this step with their island's pairs; drops the
    /// pairs that separated. Counts the pairs tested, reused and skipped in `stats`.
    void updateContacts(const StepContext &context, BodyStore &bodies, const JointSet &joints,
                        BodyTransitions transitions, StepStats &stats);
    /// Records the contacts that began or ended since the last call in `events`.
    void reportContactEvents(const StepContext &context, const BodyStore &bodies, WorldEvents &events);

    /// The step's pairs of a sensor and a body it sees (either order), for the sensors.
    const std::vector<CandidatePair> &sensorCandidates() const { return found_.sensors; }
    /// The step's pair slots (each candidate once, in the broadphase's order), for the
    /// landing correction (contacts/landing.h).
    const std::vector<std::uint32_t> &stepPairs() const { return stepPairs_; }
    /// Whether this step's broadphase reported pair slot p (it is in stepPairs()).
    bool inStep(std::uint32_t p) const {
        return p < stepIndex_.size() && stepIndex_[p] < stepPairs_.size() && stepPairs_[stepIndex_[p]] == p;
    }
    /// Where pair slot p is in stepPairs(), when inStep.
    std::uint32_t stepIndex(std::uint32_t p) const { return stepIndex_[p]; }

    ManifoldState &manifold(ManifoldRef ref) { return pairs[ref.pair].manifolds[ref.index]; }
    /// The pair of bodies i and j, created (and listed with both bodies) if new.
    std::uint32_t findOrAddPair(BodyStore &bodies, std::uint32_t i, std::uint32_t j, bool &created);
    /// Removes a pair from the cache and from its bodies' lists.
    void removePair(BodyStore &bodies, std::uint32_t pair);
    /// Removes every pair of body `index`.
    void removePairsOf(BodyStore &bodies, std::uint32_t index);
    // End normals: what the landing correction's FCL tests found (collide's memos). It
    // tests its pairs at the poses the next step's narrowphase starts from, which then
    // builds the manifolds of the pairs whose bodies stayed there without FCL's test and
    // the choice of normal (docs/solver.md, "Landing correction"). Only the pairs
    // that reached FCL have one.

    /// Forgets the end normals of the step before (the landing correction starts anew).
    void clearEndNormals() { endNormals_.clear(); }
    /// Keeps `memo` as pair p's end normal in step `step`, replacing one kept before.
    void keepEndNormal(std::uint32_t p, const NormalMemo &memo, std::uint64_t step);

private:
    /// What testing the step's pairs reads (testPairs, detect).
    struct PairTest {
        const WorldSettings &settings;
        const BodyStore &bodies;
        Workers &workers;
        std::uint64_t stepCount;
        real dt;  ///< The step's length, s.
    };
    /// Lists the candidates' pair slots in stepPairs_ (creating new pairs), but for those
    /// whose joints exclude the contact or whose bodies are both immovable (counted).
    void listCandidates(BodyStore &bodies, const JointSet &joints, Workers &workers, StepStats &stats);
    /// Appends pair slot p to stepPairs_ unless it is there already.
    void listPair(std::uint32_t p);
    /// Appends the pairs of a body woken in this step to stepPairs_.
    void listPairsOf(const BodyStore &bodies, const JointSet &joints, std::uint32_t index);
    /// Tests stepPairs_[first, last): manifolds kept, or found into finds_ and
    /// chunkFinds_ for countAnchors and mergePairs.
    void testPairs(const PairTest &test, std::size_t first, std::size_t last);
    /// Whether both bodies of pair `p` stand still: no velocity, no fall between them.
    bool standStill(const PairTest &test, std::uint32_t p) const;
    /// Whether pair `p` found no contact at its last test, its bodies standing still, and
    /// neither body's pose has changed since (SeenState); asked only of pairs that stand
    /// still now.
    bool unchanged(std::uint32_t p, const BodyStore &bodies) const;
    /// Hands out the anchor numbers of the merges of stepPairs_[first, last), in order;
    /// counts the pairs tested and reused.
    void countAnchors(StepStats &stats, std::size_t first, std::size_t last);
    /// Merges the finds of stepPairs_[first, last) into their pairs.
    void mergePairs(const BodyStore &bodies, Workers &workers, std::size_t first, std::size_t last);
    /// Lists the touching pairs of stepPairs_[first, last) and wakes what they reach.
    void wakeTouched(BodyTransitions transitions, std::size_t first, std::size_t last);
    /// Drops the simulated and moving bodies' pairs that step `stepCount` did not list.
    void removeUnseenPairs(BodyStore &bodies, Workers &workers, std::uint64_t stepCount);
    /// Refreshes pair p's manifolds from their anchors when its bodies hardly moved
    /// relative to each other since it was last tested; false: it must be tested.
    bool reuseManifolds(const WorldSettings &settings, const BodyStore &bodies, std::uint32_t p);
    /// Runs the narrowphase on pair p and appends the manifolds it finds to `out`;
    /// returns how many. Changes nothing else but `memo`, the pair's end normal if it has
    /// one (pairs are detected on several threads).
    std::size_t detect(const PairTest &test, std::uint32_t p, std::vector<Manifold> &out, NormalMemo *memo) const;
    /// Pair p's end normal kept in step `step`, or null.
    NormalMemo *endNormal(std::uint32_t p, std::uint64_t step);
    /// What a thread's merges keep: a compound pair's manifolds before its merge, and
    /// which a fresh one took; the rooms of manifold lists emptied (spareRoom, takeRoom).
    struct MergeScratch {
        std::vector<ManifoldState> previous;
        std::vector<char> used;
        std::vector<std::vector<ManifoldState>> rooms;
    };
    /// Deals the threads' spare rooms out evenly among the first `threads` scratches.
    void dealRooms(int threads);
    /// How many anchor numbers mergeFinds issues for pair p with `n` manifolds found.
    std::uint64_t anchorsIssuedBy(const BodyStore &bodies, std::uint32_t p, std::size_t n) const;
    /// Merges the `n` manifolds `found` for pair p into its manifolds, numbering new
    /// anchors from issued + 1 on; writes only pair p (pairs are merged on several threads).
    void mergeFinds(const BodyStore &bodies, std::uint32_t p, const Manifold *found, std::size_t n,
                    std::uint64_t issued, MergeScratch &scratch);
    /// Merges `found` into a pair with a compound, each manifold with the old one of its
    /// children.
    void mergeByChildren(PairState &pair, const Manifold *found, std::size_t n, const Matrix4 &poseA,
                         const Matrix4 &poseB, const CollisionShape &shapeA, const CollisionShape &shapeB,
                         real matchDistance, std::uint64_t issued, MergeScratch &scratch);

    /// Most manifolds a pair with a compound keeps (one per touching pair of children,
    /// or more against a mesh).
    static constexpr std::size_t kMaxCompoundManifolds = 32;
    /// Most manifolds any other pair keeps (a mesh may report more normals).
    static constexpr std::size_t kMaxPairManifolds = 4;
    /// How many of `n` fresh manifolds a pair keeps (with a compound or not).
    static std::size_t keptManifolds(std::size_t n, bool compound) {
        return std::min(n, compound ? kMaxCompoundManifolds : kMaxPairManifolds);
    }

    static constexpr std::uint32_t kNoSlot = ~std::uint32_t(0);
    std::uint64_t anchorsIssued_ = 0;
    std::vector<fcl::CollisionObjectd *> movedObjects_;  ///< Objects whose fat box moved.
    /// Flags set on the threads and read in order (Workers::forFlagged): per simulated,
    /// then moving kinematic, body in the broadphase (its fat box moved) and in the
    /// narrowphase (it holds a pair the broadphase no longer reports); per entry of
    /// eventSlots_ in the contact events (its contact began or ended).
    std::vector<char> flags_;
    /// What a candidate pair is: skipped (joined, or two immovable bodies), held by a slot
    /// (the one it had last step, or the one the table gives), or not in the table yet.
    enum class CandidateKind : std::uint8_t { Excluded, Immovable, Held, New };
    std::vector<CandidateKind> candidateKinds_;  ///< Per candidate.
    /// Per pair slot: its place in stepPairs_ when last listed (this step's if it is there).
    std::vector<std::uint32_t> stepIndex_;
    BroadphasePairs found_;  ///< The step's pairs: candidate contacts, sensor pairs, the filtered count.
    BroadphasePairs planePairs_;  ///< This step's body-plane pairs, found before the trees'.
    /// Pair slot of each candidate when it was last looked up (kNoSlot: none), by position.
    std::vector<std::uint32_t> candidateSlots_;
    /// What the narrowphase stage did with each entry of stepPairs_: kept its manifolds,
    /// or found `count` manifolds from its chunk's `first` on in chunkFinds_.
    /// issuedBefore: anchor numbers issued before its merge; touching, wakeA, wakeB:
    /// whether the pair touches after it and wakes body A or B.
    struct Find {
        bool reused = false;
        bool still = false;      ///< Both bodies stand still (standStill).
        bool unchanged = false;  ///< Apart, as at its last test: not tested (unchanged).
        bool touching = false;
        bool wakeA = false;
        bool wakeB = false;
        std::uint32_t first = 0;
        std::uint32_t count = 0;
        std::uint32_t anchors = 0;  ///< Anchor numbers its merge issues (anchorsIssuedBy).
        std::uint64_t issuedBefore = 0;
    };
    std::vector<Find> finds_;
    ChunkLists<Manifold> chunkFinds_;  ///< By chunk of Workers::kChunk step pairs.
    std::vector<MergeScratch> mergeScratch_;         ///< Per thread.
    std::vector<std::uint32_t> stepPairs_;  ///< Pair slots the broadphase reported this step.
    /// An end normal, of pair slot `pair`, kept in step `step`.
    struct EndNormal {
        std::uint32_t pair = 0;
        std::uint64_t step = 0;
        NormalMemo memo;
    };
    std::vector<EndNormal> endNormals_;
    std::vector<std::uint32_t> endNormalOf_;  ///< By pair slot: its entry in endNormals_ (if that names it).
    ContactTracks tracks_;
    /// Pair slots whose touching state may have changed since the last contact events:
    /// seen by the narrowphase or removed (reportContactEvents looks at these only).
    std::vector<std::uint32_t> eventSlots_;
};

}  // namespace cyclone::detail
