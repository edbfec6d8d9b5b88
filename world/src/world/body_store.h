// The World's bodies: one record per body, indexed by BodyId::index. Removed slots are
// reused, and the generation tells a stale handle from the body that took its slot.
#pragma once

#include <fcl/fcl.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "collision/broadphase.h"
#include "collision/collision_shape.h"
#include "cyclone/world/world.h"

namespace cyclone::detail {

/// A body's pose as the narrowphase last saw it, and the step since which every
/// narrowphase has seen it so: a pair apart at its last test, both bodies then and now
/// without velocity, whose bodies' poses are unchanged since keeps its result untested
/// (ContactManager, "unchanged pairs"). Velocities need no record: both zero then and now.
struct SeenState {
    Vector3 position = Vector3::Zero();
    Quaternion orientation = Quaternion::Identity();
    std::uint64_t since = UINT64_MAX;  ///< UINT64_MAX: not seen yet.

    /// Takes the body's pose as seen by step `step`'s narrowphase: `since` moves to
    /// `step` when it differs, bit for bit, from the last one seen.
    void look(const RigidBody &body, std::uint64_t step) {
        const bool same = since != UINT64_MAX && bitsEqual(position, body.getPosition()) &&
                          bitsEqual(orientation.coeffs(), body.getOrientation().coeffs());
        if (same) return;
        renew(body, step);
    }
    /// Takes the body's pose as new from step `step` on, whatever was seen before.
    void renew(const RigidBody &body, std::uint64_t step) {
        position = body.getPosition();
        orientation = body.getOrientation();
        since = step;
    }

private:
    template <class V>
    static bool bitsEqual(const V &x, const V &y) {
        return std::memcmp(x.data(), y.data(), sizeof(real) * V::SizeAtCompileTime) == 0;
    }
};

struct BodyRecord {
    RigidBody body;
    std::shared_ptr<const CollisionShape> shape;
    std::uint32_t shapeIndex = 0;  ///< Its shape's place in WorldState::shapes.
    std::unique_ptr<BodyObject> object;  ///< Null for planes.
    std::string name;
    Material material;
    std::uint32_t generation = 0;
    bool alive = false;
    bool immovable = false;     ///< Static or kinematic: infinite mass, never moved by the dynamics, never woken.
    bool kinematic = false;     ///< Moved only at the velocities the game sets (dynamics/kinematic_bodies.h).
    bool moving = false;        ///< Kinematic with a velocity or rotation this step: it has a solver entry.
    bool isPlane = false;
    bool ccd = false;
    std::shared_ptr<fcl::CollisionGeometryd> core;  ///< ccd bodies: the sphere swept when already touching.
    bool isolated = false;      ///< State went non-finite: out of collision and solve.
    bool simulated = false;     ///< Awake dynamic body at the start of this step.
    SeenState seen;             ///< Its pose at the last narrowphase that looked, for unchanged pairs.
    bool held = false;          ///< Held in the last step chosen (dynamics/holding.h): Islands::build and WorldState::wake read it; saved with the state.
    Tree tree = Tree::None;
    int sleepingIsland = -1;    ///< Index in Islands::sleeping while asleep.
    int island = -1;            ///< Island of the last step (-1: none).
    int solverIndex = 0;        ///< Index in the solver's body arrays (0: immovable; moving kinematic bodies after the simulated ones).
    std::vector<std::uint32_t> pairs;  ///< Pair slots this body is in (any order).
    int awakeSlot = -1;         ///< Index in BodyStore::awake (-1: not in it).
    std::uint64_t rank = 0;     ///< When it was added: orders BodyStore::awake as `order` is.
    real boundingRadius = 0;    ///< Farthest point of the shape from its origin, m.
    int layer = 0;              ///< Collision layer, [0, 31].
    std::uint32_t collidesWith = kAllLayers;  ///< Layers it collides with, bit k for layer k.
    bool sensor = false;        ///< Reports overlaps, never touches (contacts/sensors.h).
    std::vector<std::uint32_t> keptApart;  ///< Bodies it never collides with (World::setPairCollision), any order.
    real gravityScale = 1;      ///< Factor of the world's gravity on it (BodySettings::gravityScale).
    LockedAxes locked;          ///< Axes it may not move along or turn about (dynamics/axis_locks.h).
    Vector3 surfaceVelocity = Vector3::Zero();  ///< Body space, m/s (BodySettings::surfaceVelocity).
    Vector3 oneWay = Vector3::Zero();  ///< Unit, body space; zero: not one-way (contacts/pre_solve.h).
    std::uint64_t userData = 0;  ///< BodySettings::userData.
};

/// The offset from a body's shape frame to its centre of mass, world space, m: zero
/// except for a compound, whose frame is where its children were placed.
inline Vector3 frameToCentre(const RigidBody &body, const CollisionShape &shape) {
    if (!shape.isCompound()) return Vector3::Zero();
    return body.getOrientation() * shape.frameToCentre();
}

struct BodyStore final : PairFilter {
    std::vector<BodyRecord> records;
    std::vector<std::uint32_t> free;   ///< Slots of removed bodies, reused first.
    std::vector<std::uint32_t> order;  ///< Live bodies in the order they were added.
    /// Awake dynamic bodies not isolated: what a step visits, so that sleeping and static
    /// bodies cost nothing per step. Sorted by rank when `awakeSorted`.
    std::vector<std::uint32_t> awake;
    bool awakeSorted = true;
    std::uint64_t nextRank = 0;
    /// The bodies the step moves (awake when it began), in rank order; solver index k + 1.
    std::vector<std::uint32_t> simulated;
    /// Every kinematic body, in the order they were added; empty in a scene without any,
    /// which then pays nothing for them.
    std::vector<std::uint32_t> kinematic;
    /// The kinematic bodies moving this step, in `kinematic`'s order; solver index
    /// simulated.size() + 1 + k.
    std::vector<std::uint32_t> moving;
    /// Live bodies whose layer or mask is not the default: while there are none (and no
    /// sensor or pair rule), the broadphase asks nothing per pair.
    int filteredCount = 0;
    /// Live sensors.
    int sensorCount = 0;
    /// Live bodies whose shape may be round (collision/round_side.h): while there are
    /// none, the solver lists no round sides (solver/round_depths.h).
    int roundCount = 0;
    /// Pairs kept apart by World::setPairCollision.
    int keptApartCount = 0;
    /// Live dynamic bodies with a locked axis: while there are none, no stage looks for them.
    int lockedCount = 0;
    /// Live bodies with a surface velocity or a one-way direction: while there are none
    /// (and no contact listener), the pre-solve stage is skipped.
    int ruledCount = 0;
    int isolatedCount = 0;  ///< Live bodies isolated for a non-finite state.
    std::vector<std::uint32_t> planes;
    std::unordered_map<std::string, std::uint32_t> names;

    BodyRecord &operator[](std::uint32_t index) { return records[index]; }
    const BodyRecord &operator[](std::uint32_t index) const { return records[index]; }
    std::size_t size() const { return records.size(); }

    bool contains(BodyId id) const {
        return id.index < records.size() && records[id.index].alive && records[id.index].generation == id.generation;
    }
    /// Whether bodies i and j may touch: each one's mask holds the other's layer.
    bool collide(std::uint32_t i, std::uint32_t j) const {
        const BodyRecord &a = records[i];
        const BodyRecord &b = records[j];
        return (a.collidesWith >> b.layer & 1u) && (b.collidesWith >> a.layer & 1u);
    }
    /// Whether a World::setPairCollision rule keeps bodies i and j apart.
    bool keptApart(std::uint32_t i, std::uint32_t j) const {
        const std::vector<std::uint32_t> &a = records[i].keptApart;
        const std::vector<std::uint32_t> &b = records[j].keptApart;
        if (a.empty() || b.empty()) return false;
        const bool aShorter = a.size() <= b.size();
        const std::vector<std::uint32_t> &list = aShorter ? a : b;
        return std::find(list.begin(), list.end(), aShorter ? j : i) != list.end();
    }
    /// Whether pairs must be asked classify() at all: some body has a layer, a mask, a
    /// sensor flag or a pair rule that is not the default.
    bool filtering() const { return filteredCount > 0 || sensorCount > 0 || keptApartCount > 0; }
    /// Contact when the layers let bodies i and j touch, Sensor when one is a sensor that
    /// sees the other (each one's mask holds the other's layer, as for contacts), Filtered
    /// otherwise (two sensors, or a pair rule).
    PairKind classify(std::uint32_t i, std::uint32_t j) const override {
        const BodyRecord &a = records[i];
        const BodyRecord &b = records[j];
        PairKind kind;
        if (a.sensor || b.sensor) {
            kind = !(a.sensor && b.sensor) && collide(i, j) ? PairKind::Sensor : PairKind::Filtered;
        } else {
            kind = collide(i, j) ? PairKind::Contact : PairKind::Filtered;
        }
        return kind != PairKind::Filtered && keptApart(i, j) ? PairKind::Filtered : kind;
    }
    BodyId idOf(std::uint32_t index) const { return {index, records[index].generation}; }
    /// The body `id` names; refused with `function`'s name when it names none.
    BodyRecord &record(BodyId id, const char *function);
    const BodyRecord &record(BodyId id, const char *function) const;
    /// The same, and refused when the body is isolated (non-finite state): every call
    /// that would change it refuses it, so that none succeeds without effect.
    BodyRecord &changeableRecord(BodyId id, const char *function);
    /// The same (isolated bodies refused), and refused when the body is static or kinematic.
    BodyRecord &dynamicRecord(BodyId id, const char *function);
    /// The same (isolated bodies refused), and refused when the body is static (dynamic
    /// and kinematic bodies pass).
    BodyRecord &movableRecord(BodyId id, const char *function);
    /// Puts the body into `awake` or takes it out, as its state now says.
    void updateAwakeList(std::uint32_t index);
    /// Sorts `awake` by rank if a wake put it out of order: bodies are simulated in the
    /// order they were added, whatever the order they woke in.
    void sortAwake();
};

}  // namespace cyclone::detail
