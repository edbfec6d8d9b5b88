/// \file
/// Joints: ball-and-socket, hinge, fixed, slider and distance constraints between two
/// bodies, or a body and the world, and the mouse joint that drags a body to a moving
/// point, solved with the contacts (World::addJoint).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>

#include "cyclone/core.h"
#include "cyclone/world/settings.h"

namespace cyclone {

/// What a joint keeps.
enum class JointType {
    /// The two anchors stay together; any rotation.
    Ball,
    /// The anchors stay together and the bodies turn only about `axis`.
    Hinge,
    /// No relative motion: the anchors stay together, the relative orientation stays as at creation.
    Fixed,
    /// No relative rotation; the anchors move apart only along `axis`.
    Slider,
    /// The anchors stay between `minDistance` and `maxDistance` apart (a rope, or a rod when equal).
    Distance,
    /// a's anchor is pulled towards a world point, the target, which the caller moves
    /// (World::setMouseTarget), by a damped spring whose force is at most
    /// `JointPull::maxForce`: how a mouse drags a body. Only a: `b` must be empty.
    Mouse,
};

/// A hinge's angle or a slider's offset range, from the pose at creation.
struct JointLimits {
    /// Lowest angle (rad, in [-pi, pi]) or offset (m), finite.
    real lower = 0;
    /// Highest angle (rad, in [-pi, pi]) or offset (m), finite, >= lower.
    real upper = 0;
};

/// A hinge's or a slider's motor: it drives the relative speed towards `speed`.
struct JointMotor {
    /// Target relative speed of `a` with respect to `b` about (hinge, rad/s) or along
    /// (slider, m/s) the axis, finite.
    real speed = 0;
    /// Largest torque (hinge, N m) or force (slider, N) the motor exerts, finite, >= 0.
    real maxForce = 0;
};

/// How a mouse joint pulls its anchor to the target: as a damped spring of frequency
/// `frequency` would pull a body of a's mass held at its centre of mass (stiffness
/// m (2 pi f)^2, damping 2 m zeta (2 pi f)), its force clamped to `maxForce`. The spring
/// is solved implicitly, so no frequency is too stiff for the step.
struct JointPull {
    /// Natural frequency, Hz, finite, > 0.
    real frequency = 5;
    /// Damping ratio, finite, >= 0 (1: critical, no overshoot; 0: none).
    real dampingRatio = 0.7;
    /// Largest force of the pull, N, > 0 (infinity: no limit).
    real maxForce = std::numeric_limits<real>::infinity();
};

/// What World::addJoint needs. Positions and the axis are world space at creation: each
/// body keeps them in its own frame from then on.
///
/// Angles and offsets are those of `a` relative to `b` (the frame it moves in; the world
/// when `b` is empty): a hinge's angle is a's turn about `axis` since creation, a
/// slider's offset is how far a's anchor has moved along `axis` from b's.
struct JointSettings {
    /// What the joint keeps.
    JointType type = JointType::Ball;
    /// First body; dynamic or kinematic or static, but one of the two must be dynamic
    /// (mouse joints: `a` is).
    BodyId a;
    /// Second body, different from `a`; empty joins `a` to the world (mouse joints: empty).
    std::optional<BodyId> b;
    /// Where the joint sits, world space at creation, m (finite, within 1e12 m of the
    /// origin). Distance joints: the anchor on `a`.
    Vector3 anchor = Vector3::Zero();
    /// Distance joints: the anchor on `b` (or in the world), world space at creation, m;
    /// mouse joints: the target, world space, m. Empty means `anchor`. Other types have none.
    std::optional<Vector3> anchorB;
    /// Hinge and slider: the axis, world space at creation, finite, not zero (normalised).
    Vector3 axis = Vector3::UnitY();
    /// Hinge and slider: the range of the angle (rad) or offset (m); none means free.
    std::optional<JointLimits> limits;
    /// Hinge and slider: a motor; none means no drive.
    std::optional<JointMotor> motor;
    /// Distance joints: the shortest distance between the anchors, m, finite, >= 0;
    /// empty means their distance at creation.
    std::optional<real> minDistance;
    /// Distance joints: the longest distance, m, finite, >= minDistance; empty means
    /// their distance at creation.
    std::optional<real> maxDistance;
    /// Distance joints: a spring pulls the anchors back within [min, max] with this
    /// stiffness instead of holding them there, N/m, finite, >= 0; 0 means rigid.
    real stiffness = 0;
    /// Distance joints with stiffness: damping of that spring, N s/m, finite, >= 0.
    real damping = 0;
    /// Mouse joints: how the anchor is pulled; empty means JointPull's defaults. Other
    /// types have none.
    std::optional<JointPull> pull;
    /// The joint breaks (is removed and reported in WorldEvents::jointsBroken) in a step
    /// whose mean force exceeds this, N, > 0 (infinity: never).
    real breakForce = std::numeric_limits<real>::infinity();
    /// The same for the torque its angular rows exert, N m, > 0 (infinity: never).
    real breakTorque = std::numeric_limits<real>::infinity();
    /// Whether the two bodies still collide with each other.
    bool collideConnected = false;
};

/// A handle to a joint; a default-constructed JointId names no joint.
struct JointId {
    /// Slot of the joint in its World; reused after the joint is removed.
    std::uint32_t index = UINT32_MAX;
    /// Incremented each time the slot is reused, so that an old handle stays stale.
    std::uint32_t generation = 0;
    /// True when both name the same joint.
    bool operator==(const JointId &other) const { return index == other.index && generation == other.generation; }
    /// True when they name different joints.
    bool operator!=(const JointId &other) const { return !(*this == other); }
    /// Orders handles by slot, then generation (for std::map, std::set and sorting; the
    /// order says nothing about when the joints were added).
    bool operator<(const JointId &other) const {
        return index != other.index ? index < other.index : generation < other.generation;
    }
};

/// What a joint did in the last step (World::jointState).
struct JointState {
    /// Mean force the joint exerted on `a` during the last step, world space, N (the
    /// opposite acts on `b`).
    Vector3 force = Vector3::Zero();
    /// Mean torque its angular rows (rotation locks, hinge limit and motor) exerted on
    /// `a`, world space, N m.
    Vector3 torque = Vector3::Zero();
    /// How far the joint is from what it keeps now, m: the gap between the anchors (ball,
    /// hinge, fixed), their distance across the axis (slider), or how far their distance
    /// is outside [min, max] (distance), or the anchor's distance from the target (mouse).
    real error = 0;
    /// Hinge: a's angle about the axis relative to b since creation, rad, in (-pi, pi];
    /// slider: a's offset along the axis, m; others: 0.
    real position = 0;
};

}  // namespace cyclone

// The joint handle's hash, for std::unordered_map and std::unordered_set.
namespace std {
/// Hash of a JointId: its slot and generation.
template <>
struct hash<cyclone::JointId> {
    /// The hash of `id`.
    size_t operator()(const cyclone::JointId &id) const noexcept {
        return hash<uint64_t>()(uint64_t{id.generation} << 32 | id.index);
    }
};
}  // namespace std
