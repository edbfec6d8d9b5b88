// The World's private state: the subsystems a step runs through, each owning its state
// and scratch (kept between steps, so that a steady step allocates nothing).
//
// A step simulates the bodies awake when it starts ("simulated") and those its contacts,
// joints, springs and kinematic bodies wake before the solve: a sleeping body that is hit
// joins the step of the hit with its mass and its island (Integration::admit).
#pragma once

#include <cstdint>

#include "character/characters.h"
#include "collision/broadphase.h"
#include "collision/shape_set.h"
#include "contacts/contact_manager.h"
#include "contacts/landing.h"
#include "contacts/pre_solve.h"
#include "contacts/sensors.h"
#include "cyclone/world/world.h"
#include "dynamics/axis_locks.h"
#include "dynamics/ccd.h"
#include "dynamics/holding.h"
#include "dynamics/integration.h"
#include "dynamics/islands.h"
#include "dynamics/kinematic_bodies.h"
#include "dynamics/step_plan.h"
#include "dynamics/springs.h"
#include "joints/joint_set.h"
#include "queries/queries.h"
#include "solver/constraint_solver.h"
#include "world/body_store.h"
#include "world/event_log.h"
#include "world/step_context.h"
#include "world/workers.h"

namespace cyclone {
namespace detail {

/// What every stage reads: the subsystems, the settings, the step's counters.
struct WorldState {
    WorldSettings settings;
    BodyStore bodies;
    SpringSet springs;
    JointSet joints;
    Broadphase broadphase;
    ContactManager contacts;
    PreSolve preSolve;
    Sensors sensors;
    ConstraintSolver solver;
    Holding holding;
    Integration integration;
    AxisLocks axisLocks;
    Islands islands;
    ContinuousCollision ccd;
    LandingCorrection landing;
    Characters characters;
    EventLog events;
    Workers workers;
    StepStats stats;
    std::uint64_t stepCount = 0;
    /// Every distinct shape a body was added with, in the order first added (kept after the
    /// body is removed): a saved state names its bodies' shapes by place in it
    /// (snapshot/world_state_io.cpp).
    ShapeSet shapes;
    /// Calls of the World's non-const members so far (World::State counts them): a
    /// callback that must only read is refused when this changed while it ran.
    std::uint64_t changingCalls = 0;

    explicit WorldState(const WorldSettings &s) : settings(s) {}

    /// One step of dt seconds, stage by stage (world/step.cpp).
    void step(real dt);

    // How a body moves between awake, asleep and isolated (world/wake_and_sleep.cpp).
    /// Wakes the body and the rest of its sleeping island; static and isolated bodies
    /// stay as they are.
    void wake(std::uint32_t index);
    /// Puts the listed bodies to sleep as one island; `report` false for a body added
    /// asleep, which did not fall asleep.
    void sleepIsland(const std::uint32_t *members, int count, bool report = true);
    /// Takes a body whose state went non-finite out of collision and solve for good.
    void isolate(std::uint32_t index);
    /// Moves the body's collision object to another broadphase tree.
    void setTree(std::uint32_t index, Tree tree);
    /// After a teleport: refits the body's box and wakes what it or its contacts concern.
    void refreshCollisionObject(std::uint32_t index);

    // Layers, pair rules and sensors (world/world_filters.cpp).
    /// After body `index`'s layers or pair rules changed: the broadphase walks again, and
    /// the sensor overlaps they now forbid end.
    void filterChanged(std::uint32_t index);
    /// Before body `index` is removed: its sensor overlaps end, and its pair rules and
    /// sensor flag go.
    void leaveFilters(std::uint32_t index);

    /// What the queries read (queries/queries.h).
    QueryScene queryScene() const { return {bodies, broadphase, changingCalls}; }
};

}  // namespace detail

/// The World's private state is its WorldState (the subsystems see that name).
struct World::Impl : detail::WorldState {
    using WorldState::WorldState;
};

}  // namespace cyclone
