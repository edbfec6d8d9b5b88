// How a stage changes a body between awake, asleep and isolated, or moves its collision
// object between the broadphase's trees, in the middle of its own work. Each change reaches
// lists that the stage and the stages after it walk (the awake and simulated bodies, the
// pairs, the sensors' overlaps, the trees), so it is made at once, in the stage's order,
// by the World (world/wake_and_sleep.cpp). A stage that makes none does not take this.
#pragma once

#include <cstdint>

#include "collision/broadphase.h"

namespace cyclone::detail {

struct WorldState;

/// A handle on the World's body transitions (copied freely; it refers to the World).
class BodyTransitions {
public:
    explicit BodyTransitions(WorldState &world) : world_(&world) {}
    /// Wakes the body and the rest of its sleeping island (WorldState::wake).
    void wake(std::uint32_t index) const;
    /// Takes a body whose state went non-finite out of collision and solve for good
    /// (WorldState::isolate).
    void isolate(std::uint32_t index) const;
    /// Moves the body's collision object to another broadphase tree (WorldState::setTree).
    void setTree(std::uint32_t index, Tree tree) const;
    /// After a teleport: refits the body's box and wakes what it or its contacts concern
    /// (WorldState::refreshCollisionObject).
    void refresh(std::uint32_t index) const;

private:
    WorldState *world_;
};

}  // namespace cyclone::detail
