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

/// A ball joint's swing cone, fixed in `a`: b's twist axis may lean away from a's by at
/// most `normalAngle` in the plane of `axis` and `normal`, by at most `binormalAngle` in
/// the plane of `axis` and `axis x normal`, and within the ellipse between them elsewhere
/// (the lean's angle theta in direction phi from `normal` obeys
/// (theta cos phi / normalAngle)^2 + (theta sin phi / binormalAngle)^2 <= 1).
struct JointSwingLimit {
    /// Half-angle of the cone towards `normal`, rad, in (0, pi].
    real normalAngle = 0;
    /// Half-angle of the cone towards `axis x normal`, rad, in (0, pi].
    real binormalAngle = 0;
};

/// A hinge's or a slider's motor: it drives the relative speed towards `speed`.
struct JointMotor {
    /// Target relative speed of `a` with respect to `b` about (hinge, rad/s) or along
    /// (slider, m/s) the axis, finite.
    real speed = 0;
    /// Largest torque (hinge, N m) or force (slider, N) the motor exerts, finite, >= 0.
    real maxForce = 0;
};

/// A hinge's or a slider's servo: a motor that drives the angle or offset towards
/// `target` as a spring of natural frequency `frequency` and damping ratio
/// `dampingRatio` would (stiffness m (2 pi f)^2, damping 2 m zeta (2 pi f), m the mass the
/// axis moves with the joint's other rows held; solved implicitly), with at most
/// `maxForce`.
struct JointServo {
    /// The angle (hinge, rad, in [-pi, pi]) or offset (slider, m) it drives to, measured
    /// as JointLimits are, finite.
    real target = 0;
    /// The spring's natural frequency, Hz, finite, > 0.
    real frequency = 1;
    /// The spring's damping ratio, finite, >= 0 (1: critical, no overshoot).
    real dampingRatio = 1;
    /// Largest torque (hinge, N m) or force (slider, N) it exerts, finite, >= 0.
    real maxForce = 0;
};

/// A limit made soft: past it, the joint is pushed back as by a damped spring of this
/// natural frequency and damping ratio (stiffness and damping scaled by the mass the
/// limit moves, as for a servo), instead of being stopped dead.
struct JointSpring {
    /// Natural frequency, Hz, finite, > 0.
    real frequency = 5;
    /// Damping ratio, finite, >= 0.
    real dampingRatio = 1;
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
    /// Hinge and slider, and ball joints with a swing or twist limit: the axis (a ball
    /// joint's twist axis), world space at creation, finite, not zero (normalised).
    Vector3 axis = Vector3::UnitY();
    /// Hinge and slider: the range of the angle (rad) or offset (m); none means free.
    std::optional<JointLimits> limits;
    /// Hinge and slider: a motor; none means no drive.
    std::optional<JointMotor> motor;
    /// Hinge and slider: a servo (not with `motor`); none means none.
    std::optional<JointServo> servo;
    /// Ball joints: the swing cone of b's twist axis (`axis`) about a's; none means free.
    std::optional<JointSwingLimit> swingLimit;
    /// Ball joints with a swing limit: the direction `normalAngle` is measured towards,
    /// world space at creation, finite, perpendicular to `axis` (normalised); required
    /// when the two half-angles differ, any perpendicular otherwise.
    std::optional<Vector3> normal;
    /// Ball joints: the range of the twist about `axis` (rad, in [-pi, pi]): a's turn
    /// about b's twist axis since creation, once the swing that takes b's axis onto a's
    /// is taken out (as a hinge's angle); none means free.
    std::optional<JointLimits> twistLimit;
    /// Ball joints and hinges: friction in the joint, N m, finite, >= 0: a torque of at
    /// most this opposes the bodies' relative rotation (as a speed motor driving it to 0
    /// would), so that a limb comes to rest instead of swinging on; 0 means none.
    real friction = 0;
    /// Hinges, sliders and limited ball joints: their limits (`limits`, `swingLimit`,
    /// `twistLimit`) are springs of these; none means rigid limits.
    std::optional<JointSpring> limitSpring;
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
