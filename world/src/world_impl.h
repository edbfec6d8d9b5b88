// The World's private state and its step stages.
//
// Design note. Bodies live in one vector of records indexed by BodyId::index (removed
// slots are reused; the generation tells stale handles apart). Contact pairs persist in
// a PairCache across steps so that impulses warm-start the solver and sleeping pairs keep
// their manifolds. A step simulates the bodies awake when it starts ("simulated"): a
// body woken during the step (touched by an awake body) acts as immovable for the rest
// of that step and moves from the next one.
#pragma once

#include <Eigen/LU>
#include <fcl/fcl.h>

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "broadphase.h"
#include "collision_shape.h"
#include "contact_solver.h"
#include "jacobian_stamp.h"
#include "manifold_order.h"
#include "solver_partition.h"
#include "wide_pass.h"
#include "wide_pseudo.h"
#include "solver_schedule.h"
#include "task_pool.h"
#include "cyclone/world/world.h"
#include "narrowphase.h"
#include "pair_cache.h"
#include "support.h"
#include "support_lanes.h"

namespace cyclone {

struct BodyRecord {
    RigidBody body;
    std::shared_ptr<const detail::CollisionShape> shape;
    std::unique_ptr<detail::BodyObject> object;  ///< Null for planes.
    std::string name;
    Material material;
    std::uint32_t generation = 0;
    bool alive = false;
    bool isStatic = false;
    bool isPlane = false;
    bool ccd = false;
    std::shared_ptr<fcl::CollisionGeometryd> core;  ///< ccd bodies: the sphere swept when already touching.
    bool quarantined = false;   ///< State went non-finite: out of collision and solve.
    bool simulated = false;     ///< Awake dynamic body at the start of this step.
    detail::Tree tree = detail::Tree::None;
    int sleepingIsland = -1;    ///< Index in sleepingIslands_ while asleep.
    int island = -1;            ///< Island of the last step (-1: none).
    int solverIndex = 0;        ///< Index in the solver arrays (0: immovable).
    std::vector<std::uint32_t> pairs;  ///< Pair slots this body is in (any order).
    int awakeSlot = -1;         ///< Index in World::Impl::awake (-1: not in it).
    std::uint64_t rank = 0;     ///< When it was added: orders World::Impl::awake as `order` is.
    real boundingRadius = 0;    ///< Farthest point of the shape from its origin, m.
};

struct SpringRecord {
    SpringSettings settings;
    std::uint32_t generation = 0;
    bool alive = false;
    Vector3 implicitForce = Vector3::Zero();  ///< Force on a in the last sub-step, N (the implicit solve's warm start).
    bool implicit = false;                    ///< Backward Euler in this sub-step (chooseSpringForces).
};

/// Passes over the implicit springs per sub-step (block Gauss-Seidel on the coupled system).
inline constexpr int kImplicitSpringPasses = 4;

/// An implicit spring during one sub-step: what stays fixed through the passes.
struct ImplicitSpring {
    std::uint32_t spring = 0;         ///< Index in World::Impl::springs.
    bool aMoves = false;
    bool bMoves = false;
    Vector3 pa = Vector3::Zero();     ///< World attachment points, m.
    Vector3 pb = Vector3::Zero();
    Vector3 force0 = Vector3::Zero(); ///< Spring force on a at the sub-step's start, N.
    Matrix3 response = Matrix3::Zero();  ///< h K + C, N s/m.
    Eigen::PartialPivLU<Matrix3> system;  ///< 1 + h (h K + C) W.
};

/// A pair slot's touching state at the end of the last step, for contact events.
struct ContactTrack {
    BodyId a;
    BodyId b;
    bool touching = false;
};

struct World::Impl {
    WorldSettings settings;
    std::vector<BodyRecord> bodies;
    std::vector<std::uint32_t> freeBodies;
    std::vector<std::uint32_t> order;  ///< Live bodies in the order they were added.
    /// Awake dynamic bodies not quarantined: what a step visits, so that sleeping and
    /// static bodies cost nothing per step. Sorted by rank when `awakeSorted`.
    std::vector<std::uint32_t> awake;
    bool awakeSorted = true;
    std::uint64_t nextRank = 0;
    int quarantinedBodies = 0;  ///< Live bodies isolated for a non-finite state.
    std::vector<std::uint32_t> planes;
    std::unordered_map<std::string, std::uint32_t> names;
    std::vector<SpringRecord> springs;
    std::vector<std::uint32_t> freeSprings;

    detail::Broadphase broadphase;
    detail::PairCache pairs;
    std::vector<std::vector<std::uint32_t>> sleepingIslands;
    std::vector<int> freeSleepingIslands;

    // Scratch of a step, kept to avoid allocation in steady state.
    std::vector<std::uint32_t> simulatedBodies;
    std::vector<fcl::CollisionObjectd *> movedObjects;  ///< Objects whose fat box moved.
    std::vector<detail::CandidatePair> candidates;
    /// Pair slot of each candidate when it was last looked up (kNoSlot: none), by position.
    std::vector<std::uint32_t> candidateSlots;
    static constexpr std::uint32_t kNoSlot = ~std::uint32_t(0);
    std::vector<detail::Manifold> fresh;
    std::vector<std::uint32_t> stepPairs;  ///< Pair slots the broadphase reported this step.
    std::vector<char> pairReused;          ///< Per entry of stepPairs.
    std::vector<std::uint32_t> touchingPairs;
    std::vector<detail::SolverBody> solverBodies;
    std::vector<detail::SolverManifold> solverManifolds;
    std::vector<std::uint32_t> solverSource;  ///< Pair index and manifold of each solver manifold.
    /// Body records of each solver manifold's A and B (the pair's): the passes over the
    /// slots read them here, not from the pair, whose record is a cache miss away.
    struct SlotBodies {
        std::uint32_t a = 0, b = 0;
    };
    std::vector<SlotBodies> solverRecords;
    std::vector<ManifoldKey> manifoldKeys;    ///< The solver manifolds to build, in solve order.
    std::vector<ManifoldKey> manifoldKeysScratch;  ///< Scratch of orderManifolds.
    /// Solver slot of each entry of manifoldKeys: the solve order (Gauss-Seidel's) of the
    /// solver manifolds, which keep their slots from step to step (assignSlots).
    std::vector<int> solveOrder;
    std::vector<char> slotTaken;              ///< Scratch of assignSlots.
    std::vector<std::uint32_t> keyOfSlot;     ///< Entry of manifoldKeys each slot holds.
    std::vector<real> solverHeights;          ///< Each slot's contact height (ManifoldKey::height), m.
    std::vector<detail::JacobianStamp> jacobianStamps;  ///< What each solver slot's Jacobians were made from.
    detail::SolverPartition partition;  ///< Coupled passes' order (solver_partition.h).
    detail::PartitionScratch partitionScratch;
    std::vector<detail::WideManifold> wideManifolds[3];  ///< Each part's groups' rows during a sub-step's coupled passes (wide_pass.h).
    std::vector<detail::WidePseudo> widePseudo[3];  ///< And what its penetration passes need of them (wide_pseudo.h).
    std::vector<Vector3> solverPositions;  ///< Position of each solver body (entry 0 unused).
    std::vector<detail::DepthFrame> depthFrames;  ///< Each slot's, for penetration recovery.
    std::vector<char> bodyFlags;           ///< Per simulated body, for a stage's own use.
    std::vector<int> islandParent;
    std::vector<int> islandStart;
    std::vector<std::uint32_t> islandBodies;
    std::vector<Vector3> savedForces;
    std::vector<Vector3> savedTorques;
    std::vector<Vector3> predictedV;      ///< Velocity each body reaches without contacts.
    std::vector<Vector3> predictedW;
    std::vector<real> linearFactor;       ///< damping^h of each simulated body.
    std::vector<real> angularFactor;
    std::vector<std::uint32_t> sweepCandidates;  ///< Bodies near a ccd body's sweep.
    std::vector<ImplicitSpring> implicitSprings;
    std::vector<real> springLoad;  ///< Per body: sum of k (w_a + w_b) of its springs, 1/s^2.

    // Events (events.cpp). Calls between steps record into pendingEvents; a step moves
    // them into `events` and records its own there (eventSink says which list is open).
    WorldEvents events;
    WorldEvents pendingEvents;
    WorldEvents *eventSink = &pendingEvents;
    std::vector<ContactTrack> contactTracks;  ///< By pair slot.
    /// Pair slots whose touching state may have changed since the last contact events:
    /// seen by the narrowphase or removed (detectContactEvents looks at these only).
    std::vector<std::uint32_t> eventSlots;

    /// The step's other threads (settings.threads > 1), started by the first step that
    /// needs them.
    std::unique_ptr<detail::TaskPool> pool;

    detail::SupportScratch supportScratch;
    detail::SupportRuns supportRuns;
    detail::SupportLanes supportLanes;
    detail::SoftStepSettings soft;
    std::uint64_t stepCount = 0;
    std::uint64_t anchorSettings = 0;  ///< Settings of anchors so far (ManifoldState::anchors).
    StepStats stats;

    explicit Impl(const WorldSettings &s) : settings(s) {}

    // Lookup and validation.
    BodyRecord &record(BodyId id, const char *function);
    const BodyRecord &record(BodyId id, const char *function) const;
    BodyRecord &dynamicRecord(BodyId id, const char *function);
    BodyId idOf(std::uint32_t index) const { return {index, bodies[index].generation}; }
    bool isDynamic(std::uint32_t index) const { return !bodies[index].isStatic; }

    // Sleep and wake.
    /// Puts the body into `awake` or takes it out, as its state now says.
    void updateAwakeList(std::uint32_t index);
    void wake(std::uint32_t index);
    /// Puts the listed bodies to sleep as one island; `report` false for a body added
    /// asleep, which did not fall asleep.
    void sleepIsland(const std::uint32_t *members, int count, bool report = true);
    void setTree(std::uint32_t index, detail::Tree tree);
    void refreshCollisionObject(std::uint32_t index);

    // The step, stage by stage.
    void step(real dt);
    void applyForces(real dt);
    /// Marks the springs that get the backward-Euler force in a sub-step of h seconds;
    /// returns how many.
    int chooseSpringForces(real h);
    void addExplicitSpringForces();
    void substepForces(real h, bool firstSubstep);
    void addImplicitSpringForces(real h);
    void updateBroadphase();
    void runNarrowphase();
    /// Refreshes pair p's manifolds from their anchors when its bodies hardly moved
    /// relative to each other since it was last tested; false: it must be tested.
    bool reuseManifolds(std::uint32_t p);
    /// Runs FCL on pair p and merges what it finds into the pair's manifolds.
    void testPair(std::uint32_t p);
    void buildManifolds(real dt);
    /// Sorts manifoldKeys for Gauss-Seidel: lower contacts first.
    void orderManifolds();
    /// Gives each entry of manifoldKeys a solver slot (solveOrder).
    void assignSlots();
    detail::ManifoldState &manifoldOf(const ManifoldKey &key) { return pairs[key.source >> 2].manifolds[key.source & 3]; }
    bool jacobiansHold(const detail::JacobianStamp &stamp, const detail::PairState &pair,
                       const detail::ManifoldState &m) const;
    /// Whether body `index` is still in its stamped role, within the manifold-reuse
    /// tolerance of its stamped pose.
    bool bodyStillStamped(const detail::StampedBody &stamped, std::uint32_t index) const;
    void stampBody(detail::StampedBody &stamped, std::uint32_t index) const;
    /// Fills solverManifolds[slot], solverSource[slot] and solverRecords[slot] from the manifold `key` names.
    void addSolverManifold(const ManifoldKey &key, std::size_t slot);
    /// Solve-order height of a contact between a and b: the lower body's, m along `up`.
    real contactHeight(const BodyRecord &a, const BodyRecord &b, const Vector3 &up) const;
    void buildIslands();
    /// Runs task(i) for i in [0, count), on the pool's threads when there is one; the
    /// tasks must be independent.
    template <class Task>
    void forEachTask(int count, const Task &task) {
        if (pool) pool->run(count, task);
        else for (int i = 0; i < count; ++i) task(i);
    }
    /// Runs task(s) for every solver manifold s, in chunks of kChunk.
    template <class Task>
    void forEachManifold(const Task &task) {
        forEachInChunks(solverManifolds.size(), task);
    }
    /// Runs task(k) for every simulated body k, in chunks of kChunk.
    template <class Task>
    void forEachBody(const Task &task) {
        forEachInChunks(simulatedBodies.size(), task);
    }
    /// Items handed to a thread at once: enough to outweigh the handing (a microsecond).
    static constexpr std::size_t kChunk = 64;
    template <class Task>
    void forEachInChunks(std::size_t count, const Task &task) {
        forEachTask(static_cast<int>((count + kChunk - 1) / kChunk), [&](int chunk) {
            const std::size_t end = std::min(count, std::size_t(chunk + 1) * kChunk);
            for (std::size_t i = std::size_t(chunk) * kChunk; i < end; ++i) task(i);
        });
    }
    /// Starts or stops threads to match settings.threads.
    void matchThreads();
    void prepareSolver(real h);
    void prepareManifold(std::size_t s);
    void warmStart();
    void loadCoupledPasses();
    void solveCoupledPass(bool reverse);
    void storeCoupledPasses();
    void solveSupportPass(bool reverse);
    void solve(real h, bool firstSubstep);
    void integrate(real h);
    void recoverPenetration(real h);
    void restitution();
    void sweepContinuous();
    void updateSleep();
    void storeImpulses();
    void quarantine(std::uint32_t index);
    /// The pair of bodies i and j, created (and listed with both bodies) if new.
    std::uint32_t findOrAddPair(std::uint32_t i, std::uint32_t j, bool &created);
    /// Removes a pair from the cache and from its bodies' lists.
    void removePair(std::uint32_t pair);
    /// Removes every pair of body `index`.
    void removePairsOf(std::uint32_t index);

    // Events (events.cpp): the step opens and closes them; detectContactEvents() runs
    // after the narrowphase.
    void openStepEvents();
    void detectContactEvents();
    void closeStepEvents();

    // Queries (queries.cpp): whether a query considers a body.
    bool accepts(std::uint32_t index, const QueryFilter &filter) const;
};

}  // namespace cyclone
