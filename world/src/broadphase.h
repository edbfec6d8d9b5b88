// Broadphase: three FCL dynamic AABB trees (awake, sleeping, static bodies) and the
// planes kept apart (a half-space has an infinite AABB and no place in a tree).
//
// Candidate pairs are awake x awake, awake x sleeping, awake x static and awake x plane:
// a sleeping body's pairs with sleeping or static bodies are never visited, so a large
// sleeping pile costs nothing per step.
#pragma once

#include <fcl/fcl.h>

#include <cstdint>
#include <vector>

namespace cyclone::detail {

/// Which tree a body's collision object is in.
enum class Tree : std::uint8_t { None, Awake, Asleep, Static };

/// A candidate pair of body indices (unordered).
struct CandidatePair {
    std::uint32_t a;
    std::uint32_t b;
};

class Broadphase {
public:
    Broadphase();

    /// Puts `object` (whose user data is its body index) into `tree`, moving it out of
    /// the tree it was in.
    void place(fcl::CollisionObjectd *object, Tree from, Tree to);
    /// Refits the awake tree after the objects in `moved` changed their AABBs.
    void refitAwake(const std::vector<fcl::CollisionObjectd *> &moved);
    /// Refits a static object's AABB after it was moved.
    void refitStatic(fcl::CollisionObjectd *object);
    /// Appends every pair of overlapping AABBs with at least one awake member.
    void findPairs(std::vector<CandidatePair> &out);

private:
    fcl::DynamicAABBTreeCollisionManagerd awake_;
    fcl::DynamicAABBTreeCollisionManagerd asleep_;
    fcl::DynamicAABBTreeCollisionManagerd static_;

    fcl::DynamicAABBTreeCollisionManagerd *manager(Tree tree);
};

/// The body index stored in a collision object's user data.
inline std::uint32_t bodyIndexOf(const fcl::CollisionObjectd *object) {
    return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(object->getUserData()));
}

}  // namespace cyclone::detail
