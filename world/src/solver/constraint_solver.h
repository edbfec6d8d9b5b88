// The contact solver as the step uses it: it builds the step's constraints from the
// touching pairs' manifolds (constraint_builder.cpp) and solves them, sub-step by
// sub-step (solve.cpp). The passes themselves live beside it: velocity_pass,
// carrier_pass, penetration_pass and contact_solver (the scalar rows).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "contacts/pair_cache.h"
#include "cyclone/world/world.h"
#include "solver/carriers.h"
#include "solver/contact_solver.h"
#include "solver/jacobian_stamp.h"
#include "solver/manifold_order.h"
#include "solver/penetration_pass.h"
#include "solver/rolling_resistance.h"
#include "solver/round_depths.h"
#include "solver/threads/carrier_threads.h"
#include "solver/threads/ordered_shares.h"
#include "solver/threads/partition.h"
#include "solver/velocity_pass.h"
#include "world/body_store.h"
#include "world/body_transitions.h"
#include "world/chunk_lists.h"

namespace cyclone::detail {

class ContactManager;
class JointSet;
class PreSolve;
struct StepContext;
class Workers;

/// The split-impulse target normal velocity of point p of m in a sub-step of h s
/// (inverseH = 1 / h): a gap may close within the sub-step and no more; a contact
/// touching, or closing its gap within the sub-step, at a speed that bounces (the first
/// sub-step only for one touching) bounces.
CYCLONE_INLINE real velocityBias(const SolverManifold &m, const SolverPoint &p, real h, real inverseH,
                                 real restitutionThreshold, bool firstSubstep) {
    const bool bounces = m.restitution > 0 && p.approachSpeed < -restitutionThreshold;
    if (p.depth < 0) {
        // A speculative contact that closes its gap within this sub-step at a speed that
        // bounces: the bounce, as if it had touched.
        if (bounces && -p.approachSpeed * h >= -p.depth) return -m.restitution * p.approachSpeed;
        return p.depth * inverseH;
    }
    return firstSubstep && bounces ? -m.restitution * p.approachSpeed : 0;
}

class ConstraintSolver {
public:
    friend struct StateFields;  ///< Saves and restores the kept Jacobians (snapshot/world_state_io.cpp).
    /// The step's solver manifolds, in their slots (solve order: solveOrder_).
    const SolverManifolds &manifolds() const { return manifolds_; }

    /// Orders the touching pairs' manifolds of `contacts` (lowest first along -gravity),
    /// runs the pre-solve stage over them, gives each a solver slot and fills it from the
    /// manifold (warm started at context.plan.warmScale); writes each manifold's slot and
    /// step (context.stepCount), context.deepest and the stats' manifold and contact counts.
    void build(StepContext &context, const BodyStore &bodies, ContactManager &contacts, PreSolve &preSolve,
               StepStats &stats);
    /// Sets up the solver bodies and, for every slot whose Jacobians do not still hold,
    /// the Jacobians and effective masses (sub-steps of context.h s, context.plan.substeps
    /// of them); orders the passes and the carrier pass; counts the rows in `stats`.
    void prepare(const StepContext &context, const BodyStore &bodies, StepStats &stats);
    /// One sub-step's velocities: predicted without contacts, then corrected by the
    /// velocity passes, the joints (when context.activeJoints) and the carrier pass (its
    /// direction from context.stepCount), and given to the bodies; a body whose velocity
    /// overflows is isolated through `transitions`. Counts its passes in `stats`.
    void solveVelocities(const StepContext &context, BodyStore &bodies, JointSet &joints, BodyTransitions transitions,
                         StepStats &stats, bool firstSubstep);
    /// Pushes bodies out of penetration beyond the slop without adding energy (a body whose
    /// pose overflows is isolated through `transitions`), then projects the joined bodies'
    /// positions onto their joints.
    void recoverPenetration(const StepContext &context, BodyStore &bodies, JointSet &joints,
                            BodyTransitions transitions, StepStats &stats);
    /// Hands the accumulated impulses back to the pairs' manifolds for warm starting, and
    /// reports each solved pair's normal impulse of the step in events.contactImpulses.
    void storeImpulses(const StepContext &context, const BodyStore &bodies, PairCache &pairs, WorldEvents &events);

private:
    // Building (constraint_builder.cpp).
    void addSolverManifold(const WorldSettings &settings, const BodyStore &bodies, ContactManager &contacts,
                           const PreSolve &preSolve, std::uint64_t stepCount, real warmScale, std::uint32_t keyIndex,
                           std::size_t slot);
    void assignSlots(const PairCache &pairs, Workers &workers, std::uint64_t stepCount);
    // Preparing (constraint_builder.cpp), in order.
    void prepareBodies(const BodyStore &bodies, Workers &workers, real h);
    void orderManifolds(const WorldSettings &settings, const BodyStore &bodies, Workers &workers);
    void prepareManifolds(const WorldSettings &settings, const BodyStore &bodies, Workers &workers, int substeps,
                          StepStats &stats, real h);
    void prepareResistanceAndShares(const WorldSettings &settings, const BodyStore &bodies, Workers &workers,
                                    StepStats &stats);
    void prepareManifold(const BodyStore &bodies, std::size_t s, real h, real dt,
                         real restitutionThreshold);
    bool jacobiansHold(real tolerance, const BodyStore &bodies, const JacobianStamp &stamp, const PairState &pair,
                       const ManifoldState &m) const;
    // Solving (solve.cpp). One sub-step's stages, in order:
    void predictVelocities(const WorldSettings &settings, BodyStore &bodies, Workers &workers,
                           BodyTransitions transitions, int substeps, StepStats &stats, real h, bool firstSubstep);
    void refreshTargets(const BodyStore &bodies, Workers &workers, real restitutionThreshold, real h);
    void solvePasses(const StepContext &context, const BodyStore &bodies, JointSet &joints, StepStats &stats,
                     bool firstSubstep);
    void giveVelocities(const WorldSettings &settings, BodyStore &bodies, Workers &workers,
                        BodyTransitions transitions, bool firstSubstep);
    // The passes.
    void loadVelocityPasses(Workers &workers, const WorldSettings &settings, bool firstSubstep);
    void solveVelocityPass(Workers &workers, bool reverse);
    void storeVelocityPasses(Workers &workers);
    void solveCarrierPass(Workers &workers, StepStats &stats, bool reverse);
    void solveResistancePass(Workers &workers);
    void recoverContactPenetration(const WorldSettings &settings, BodyStore &bodies, Workers &workers,
                                   BodyTransitions transitions, real recovery, StepStats &stats, real h);
    void reportImpulses(Workers &workers, const BodyStore &bodies, const PairCache &pairs, std::vector<ContactImpulse> &out);

    /// The body records of a slot's A and B: the passes over the slots read them here,
    /// not from the pair, whose record is a cache miss away.
    struct SlotBodies {
        std::uint32_t a = 0, b = 0;
    };

    std::vector<SolverBody> bodies_;  ///< Entry 0 is immovable; simulated body k is k + 1.
    SolverManifolds manifolds_;
    std::vector<ManifoldRef> sources_;  ///< The pair manifold each slot was made from.
    std::vector<SlotBodies> slotBodies_;
    std::vector<ManifoldKey> keys_;         ///< The manifolds to build, in solve order.
    ChunkLists<ManifoldKey> chunkKeys_;     ///< The keys as the chunks of touching pairs made them.
    std::vector<ManifoldKey> keysScratch_;  ///< Scratch of sortByHeight.
    /// By place in the solve order: the rolling and spinning lengths (m) of a manifold that
    /// needs resistance rows, zeros for one that does not.
    std::vector<std::pair<real, real>> resistanceLengths_;
    std::vector<int> resistancePlaces_;  ///< The places in the solve order whose manifolds need rows.
    /// Solver slot of each entry of keys_: the solve order (Gauss-Seidel's) of the slots,
    /// which the manifolds keep from step to step (assignSlots).
    std::vector<int> solveOrder_;
    std::vector<char> slotTaken_;           ///< Scratch of assignSlots.
    /// A chunk of slots' share of the step's counters: contacts and the deepest (build),
    /// Jacobians made, friction rows and restitution contacts (prepare).
    struct ChunkCount {
        int contacts = 0;
        real deepest = 0;
        int jacobians = 0;
        int frictionRows = 0;
        int restitution = 0;
    };
    std::vector<ChunkCount> chunkCounts_;  ///< Per chunk (Workers::kChunk) of slots.
    std::vector<std::uint32_t> keyOfSlot_;  ///< Entry of keys_ each slot holds.
    std::vector<real> heights_;             ///< Each slot's contact height (ManifoldKey::height), m.
    BlockArray<JacobianStamp> stamps_;      ///< What each slot's Jacobians were made from.
    SolverPartition partition_;             ///< The velocity passes' order on threads (threads/partition.h).
    PartitionScratch partitionScratch_;
    std::vector<ManifoldBatch> batches_[3];            ///< Each part's groups' rows during the velocity passes.
    std::vector<PenetrationBatch> penetration_[3];     ///< And what its penetration passes need of them.
    std::vector<ResistanceRow> resistance_;  ///< Rolling and spinning rows, in solve order (rolling_resistance.h).
    std::vector<Vector3> positions_;         ///< Position of each solver body (entry 0 unused).
    std::vector<DepthFrame> depthFrames_;    ///< Each slot's, for penetration recovery.
    RoundDepths roundDepths_;                ///< The slots with a round side (round_depths.h).
    CarrierScratch carrierScratch_;
    CarrierRuns carrierRuns_;
    CarrierThreads carrierThreads_;
    /// Whether the resistance rows and the carrier pass's manifolds without a carrier are
    /// shared between two threads this step (threads/ordered_shares.h), and how.
    bool orderedShares_ = false;
    OrderedShares resistanceShares_;  ///< Entries: resistance_.
    OrderedShares uncarriedShares_;   ///< Entries: carrierRuns_.uncarried.
    std::vector<Vector3> predictedV_;  ///< Velocity each simulated body reaches without contacts.
    std::vector<Vector3> predictedW_;
    std::vector<real> linearFactor_;   ///< damping^h of each simulated body.
    std::vector<real> angularFactor_;
    std::vector<char> overflowed_;     ///< Simulated bodies whose penetration push overflowed this sub-step (isolated).
    std::vector<real> stepImpulse_;    ///< Per slot: its points' normal impulses summed over the step's sub-steps, N s.
};

}  // namespace cyclone::detail
