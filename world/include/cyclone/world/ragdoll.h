/// \file
/// A humanoid ragdoll made of capsules and limited joints (addRagdoll).
#pragma once

#include <array>

#include "cyclone/world/world.h"

namespace cyclone {

/// The parts of a ragdoll, in the order Ragdoll::bodies holds them.
enum class RagdollPart {
    Pelvis,         ///< Across the hips; the ragdoll's root.
    Torso,          ///< Chest and belly, on the pelvis at the waist.
    Head,           ///< On the torso at the neck.
    LeftUpperArm,   ///< On the torso at the left shoulder.
    LeftLowerArm,   ///< On the left upper arm at the elbow.
    RightUpperArm,  ///< On the torso at the right shoulder.
    RightLowerArm,  ///< On the right upper arm at the elbow.
    LeftThigh,      ///< On the pelvis at the left hip.
    LeftShin,       ///< On the left thigh at the knee.
    RightThigh,     ///< On the pelvis at the right hip.
    RightShin,      ///< On the right thigh at the knee.
};

/// Parts of a ragdoll.
inline constexpr int kRagdollParts = 11;
/// Joints of a ragdoll: waist, neck, shoulders, elbows, hips, knees.
inline constexpr int kRagdollJoints = 10;

/// What addRagdoll makes: a person of `height` and `mass` standing along its
/// orientation's +y, facing its +x (its left side towards -z), the pelvis's centre at
/// `position`.
struct RagdollSettings {
    /// From the soles to the top of the head, m, finite, in [0.1, 10].
    real height = 1.8;
    /// Of the eleven bodies together, kg, finite, > 0.
    real mass = 70;
    /// The pelvis's centre, world space, m.
    Vector3 position = Vector3::Zero();
    /// Standing: the ragdoll's up is this orientation's +y, its front its +x.
    Quaternion orientation = Quaternion::Identity();
    /// Every part's initial velocity, m/s.
    Vector3 velocity = Vector3::Zero();
    /// Each joint's friction (JointSettings::friction), N m, finite, >= 0: what lets a
    /// ragdoll come to rest (without it a head or limb lying at its limit can turn on
    /// for ever; docs/joints.md, "Piles of ragdolls").
    real jointFriction = 2;
    /// Collision layer of every part, in [0, 31].
    int layer = 0;
    /// The layers every part collides with (BodySettings::collidesWith).
    std::uint32_t collidesWith = kAllLayers;
};

/// The bodies and joints of one ragdoll.
struct Ragdoll {
    /// Indexed by RagdollPart.
    std::array<BodyId, kRagdollParts> bodies;
    /// Waist, neck, left and right shoulder, left and right elbow, left and right hip,
    /// left and right knee.
    std::array<JointId, kRagdollJoints> joints;
};

/// Adds a humanoid ragdoll to `world`: eleven capsules (pelvis, torso, head, upper and
/// lower arms, thighs, shins) with the proportions and mass shares of a 1.83 m, 69 kg
/// adult scaled to `height` and `mass`, joined with human limits (docs/ragdolls.md): ball
/// joints with swing cones and twist ranges at the waist, neck, shoulders and hips,
/// limited hinges at the elbows and knees. Joined parts do not collide with each other
/// (the joints' own filter); the others do, so limbs cannot pass through the body.
/// Throws InvalidArgument (function "addRagdoll") on a height or mass out of range, and
/// whatever World::addBody throws on the position, orientation, velocity or layers;
/// nothing is added then.
Ragdoll addRagdoll(World &world, const RagdollSettings &settings);

}  // namespace cyclone
