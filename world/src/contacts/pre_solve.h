// The pre-solve stage: before the solver builds its manifolds, each manifold the step is
// about to solve goes, in the solve order and on the stepping thread, through the
// built-in rules (one-way bodies, surface velocities) and then the user's
// ContactListener, which may disable it or change its friction, restitution and surface
// velocity.
//
// Design note. One-way bodies (BodySettings::oneWay) keep one decision per pair for as long
// as the pair has manifolds to solve, step after step: a pair met from the allowed side
// (the normal, from the one-way body to the other, within 60 degrees of its direction, and
// no point deeper than kOneWayEntryDepth) is solved; any other, met from below or already
// overlapping, passes until the pair has no manifold left (the bodies are apart), so that
// a body that jumps up through a platform is not caught by it half way, whatever the normal
// then says. The landing correction leaves the pairs of disabled manifolds alone.
//
// Without a listener and without one-way or surface-velocity bodies the stage is skipped
// (one test per step) and the solver reads the materials as before.
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/world/contact_listener.h"
#include "solver/manifold_order.h"

namespace cyclone::detail {

struct BodyStore;
class PairCache;

/// How the solver is to solve one manifold, as the stage left it.
struct ContactOverride {
    real friction = 0;                              ///< Coulomb coefficient.
    real restitution = 0;                           ///< In [0, 1].
    Vector3 surfaceVelocity = Vector3::Zero();      ///< B's surface relative to A's, world, m/s.
};

/// Deepest point, m, at which a pair first met from the allowed side of a one-way body is
/// still solved: a deeper first contact is an overlap that began elsewhere (from below,
/// or at the start), which passes.
inline constexpr real kOneWayEntryDepth = 0.01;
/// Cosine of the largest angle between a one-way body's direction and the normal (from it
/// to the other body) at which a new pair is solved: 60 degrees.
inline constexpr real kOneWayCosine = 0.5;

class PreSolve {
public:
    /// The user's listener (World::setContactListener); null: none.
    ContactListener *listener = nullptr;

    /// Whether the stage runs this step: a listener, or a body with a built-in rule.
    bool active(const BodyStore &bodies) const;
    /// Runs the rules and the listener over `keys` (in solve order; the manifolds of
    /// `pairs`, between `bodies`) and removes the keys of disabled manifolds; override(k)
    /// is then kept key k's. Throws InvalidArgument on a value the listener set out of
    /// range (nothing of the step's solve has begun).
    void run(const BodyStore &bodies, const PairCache &pairs, std::vector<ManifoldKey> &keys);
    /// Forgets this step's overrides and disabled pairs (a step without the stage).
    void skip();
    /// Whether run() set the overrides of this step.
    bool ran() const { return ran_; }
    /// Kept key k's override.
    const ContactOverride &override(std::size_t k) const { return overrides_[k]; }
    /// Whether a manifold of pair slot `pair` was disabled this step.
    bool disabled(std::uint32_t pair) const;
    /// Whether any manifold was disabled this step.
    bool anyDisabled() const { return !disabledPairs_.empty(); }

private:
    struct OneWayPair {
        std::uint32_t a = 0, b = 0;  ///< Body indices, a < b.
        bool passing = false;
        bool operator<(const OneWayPair &o) const { return a != o.a ? a < o.a : b < o.b; }
    };
    bool oneWayAllows(const BodyStore &bodies, const PairCache &pairs, std::uint32_t pair, const ManifoldRef &ref);

    bool ran_ = false;
    std::vector<ContactOverride> overrides_;
    std::vector<std::uint32_t> disabledPairs_;  ///< Sorted pair slots.
    std::vector<OneWayPair> oneWay_;            ///< This step's decisions, sorted at the end.
    std::vector<OneWayPair> oneWayBefore_;      ///< Last step's, sorted.
};

}  // namespace cyclone::detail
