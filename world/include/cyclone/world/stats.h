/// \file
/// Per-step counters and timings, read after World::step() with World::stats() (how a
/// scene proves it pays only for what it uses).
#pragma once

#include "cyclone/precision.h"

namespace cyclone {

/// Milliseconds of the solve stage's parts (each included in StageTimes::solve), to see
/// what a solver setting costs.
struct SolveTimes {
    double setup = 0;     ///< The sub-steps' plan, Jacobians, effective masses, the passes' order (once per step).
    double velocity = 0;  ///< Predicted velocities, warm start and the velocity passes.
    double carrier = 0;   ///< The carrier pass (DebugSettings::carrierPass; 0 when off or without contacts).
    double position = 0;  ///< Penetration recovery (positionIterations; 0 when 0 or without contacts).
};

/// Milliseconds spent in each stage of the last step.
struct StageTimes {
    double forces = 0;       ///< Gravity, user forces and springs (every sub-step).
    double broadphase = 0;   ///< AABB updates and overlapping pairs.
    double narrowphase = 0;  ///< Contact tests (FCL or a pair's own) and manifold reuse.
    double events = 0;       ///< Contact begin and end detection.
    double sensors = 0;      ///< Sensor overlap tests and their events (0 without sensors).
    double manifolds = 0;    ///< Point matching, warm-start data, the solver's manifolds (its Jacobians: solveParts.setup).
    double islands = 0;      ///< Island building and wake propagation.
    double solve = 0;        ///< Velocity and position iterations (parts in solveParts).
    double integrate = 0;    ///< RigidBody::integrate and position correction.
    double ccd = 0;          ///< Continuous collision of fast bodies with BodySettings::ccd.
    double landing = 0;      ///< The landing correction (DebugSettings::landingCorrection).
    double sleep = 0;        ///< Held bodies (DebugSettings::holding) and island sleep decisions.
    double characters = 0;   ///< Moving the characters, and the bodies that run into them (0 without characters).
    double total = 0;        ///< The whole step.
    /// Of the total, the time in work shared between threads (WorldSettings::threads): on
    /// one thread, the work that two would share. total - shared is the serial part.
    double shared = 0;
    SolveTimes solveParts;   ///< Where the solve stage's time went (the rest: restitution, storing impulses).
};

/// What kept the last step from being the step it should have been (bit flags, as
/// Jolt's EPhysicsUpdateError): the step still ran, degraded as each flag says.
enum StepError : unsigned {
    /// More pairs of overlapping boxes than WorldSettings::maxPairs: the broadphase kept
    /// the first maxPairs of its fixed order (body-plane pairs first) and dropped the rest,
    /// whose bodies then pass through each other this step. Raise maxPairs, or spawn fewer
    /// bodies in one place.
    PairBudgetExceeded = 1u << 0,
};

/// Counters of the last step.
struct StepStats {
    unsigned errors = 0;        ///< StepError flags of the step; 0 when it ran as it should.
    int bodies = 0;             ///< Bodies in the world (static and dynamic).
    int awakeBodies = 0;        ///< Dynamic bodies awake after the step.
    int integratedBodies = 0;   ///< Dynamic bodies integrated during the step.
    int movingKinematicBodies = 0; ///< Kinematic bodies moved during the step.
    int broadphasePairs = 0;    ///< Overlapping AABB pairs that may touch (including plane pairs): the narrowphase's candidates (filtered and sensor pairs are counted apart).
    int immovablePairsSkipped = 0; ///< Broadphase pairs of a moving kinematic body with a static or kinematic one, never tested.
    int filteredPairs = 0;      ///< Overlapping box pairs dropped in the broadphase, never tested: layers that do not collide (BodySettings::layer, collidesWith), a World::setPairCollision rule, or two sensors.
    int sensorPairs = 0;        ///< Pairs of a sensor and a body tested for overlap (those the broadphase found, and those a call asked for).
    int pairsTested = 0;        ///< Pairs sent to the narrowphase (FCL or a test of its own).
    int pairsReused = 0;        ///< Pairs whose manifold was reused without narrowphase.
    int pairsUnchanged = 0;     ///< Pairs apart at their last test, both bodies still and unchanged since: no contact, untested (DebugSettings::unchangedPairs).
    int manifolds = 0;          ///< Contact manifolds given to the solver.
    int preSolvedManifolds = 0; ///< Manifolds the pre-solve stage saw (ContactListener, one-way and surface-velocity bodies); 0 without them.
    int contacts = 0;           ///< Contact points given to the solver.
    int jacobiansMade = 0;      ///< Manifolds whose Jacobians were made this step (the others kept theirs: DebugSettings::manifoldReuseTolerance).
    int frictionRows = 0;       ///< Friction constraint rows (per manifold with friction: 2 tangents, plus a twist with 2 or more points).
    int resistanceRows = 0;     ///< Rolling and spinning resistance rows (2 rolling per point or line contact, 1 spinning per point contact, where the pair's lengths are > 0).
    int restitutionContacts = 0;///< Points that bounce this step.
    int islands = 0;            ///< Islands of awake dynamic bodies.
    int heldBodies = 0;         ///< Awake bodies held still this step, left out of the solve (DebugSettings::holding).
    int substeps = 0;           ///< Sub-steps taken: WorldSettings::substeps, or DebugSettings::restingSubsteps in a step where every awake body rests.
    int velocityIterations = 0; ///< Velocity iterations run (summed over sub-steps).
    int positionIterations = 0; ///< Position iterations run (summed over sub-steps).
    int carrierSweeps = 0;      ///< Sweeps the carrier pass gave bodies resting on others, one body's sweep each (summed over sub-steps; 0 without the carrier pass).
    int springs = 0;            ///< Springs evaluated (once per step, whatever the sub-steps).
    int joints = 0;             ///< Joints solved this step (at least one end simulated).
    int jointRows = 0;          ///< Joint rows solved (summed over sub-steps).
    int gyroscopicBodies = 0;   ///< Bodies given the implicit gyroscopic step (anisotropic inertia only).
    int ccdSweeps = 0;          ///< ccd bodies that moved far enough this step to be swept.
    int ccdHits = 0;            ///< ccd bodies moved back to their time of impact.
    int landingPairs = 0;       ///< Pairs tested again at the step's end by the landing correction (DebugSettings::landingCorrection).
    int landingPushes = 0;      ///< Contact points the landing correction pushed apart (deeper than its tolerance at the step's end).
    int isolatedBodies = 0;     ///< Bodies isolated because their state became non-finite (or beyond 1e12 m).
    real maxPenetration = 0;    ///< Deepest contact of the step, m.
    StageTimes ms;              ///< Time per stage, ms.
};

}  // namespace cyclone
