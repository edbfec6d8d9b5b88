// The humanoid ragdoll: its parts' sizes and masses, and its joints' limits.
//
// Proportions and masses are those of the shipped ragdoll on stairs (a 1.83 m, 69 kg
// adult; examples/scenes/ragdoll-stairs.json), scaled: lengths by height / 1.83, masses by
// mass / 69. The limits are a ragdoll's usual, rounded (docs/ragdolls.md gives them).
#include "cyclone/world/ragdoll.h"

#include <cmath>
#include <string>

#include "cyclone/detail/validation.h"

namespace cyclone {
namespace {

constexpr real kReferenceHeight = 1.83;
constexpr real kReferenceMass = 69;

// One part at the reference size, in the standing frame (pelvis centre at the origin,
// up +y, facing +x, left towards -z): a capsule along y (`upright`) or along z.
struct PartShape {
    real radius, length, mass;
    Vector3 centre;
    bool upright;
};

// In RagdollPart's order.
const PartShape kParts[kRagdollParts] = {
    {0.10, 0.20, 12, {0, 0, 0}, false},           // pelvis
    {0.14, 0.20, 20, {0, 0.35, 0}, true},         // torso
    {0.10, 0.06, 5, {0, 0.75, 0}, true},          // head
    {0.05, 0.19, 2.5, {0, 0.355, -0.26}, true},   // left upper arm
    {0.045, 0.20, 1.5, {0, 0.045, -0.26}, true},  // left lower arm
    {0.05, 0.19, 2.5, {0, 0.355, 0.26}, true},    // right upper arm
    {0.045, 0.20, 1.5, {0, 0.045, 0.26}, true},   // right lower arm
    {0.07, 0.30, 8, {0, -0.27, -0.1}, true},      // left thigh
    {0.06, 0.32, 4, {0, -0.73, -0.1}, true},      // left shin
    {0.07, 0.30, 8, {0, -0.27, 0.1}, true},       // right thigh
    {0.06, 0.32, 4, {0, -0.73, 0.1}, true},       // right shin
};

// One joint at the reference size: a ball joint with a swing cone (towards the front,
// towards the side) and a twist range about `axis`, or a hinge about z with `range`.
struct JointShape {
    RagdollPart parent, child;
    Vector3 anchor;
    bool hinge;
    Vector3 axis;
    real forward, sideways;  // swing half-angles, rad (ball)
    JointLimits range;       // twist (ball) or angle (hinge), rad
};

// Ball joints: `a` the parent (the cone is fixed in it), `b` the child, twist axis along
// the child, the cone's normal the front (+x). Hinges: `a` the child, turning about z
// (+: forwards); an elbow bends forwards, a knee backwards.
const JointShape kJoints[kRagdollJoints] = {
    {RagdollPart::Pelvis, RagdollPart::Torso, {0, 0.10, 0}, false, {0, 1, 0}, 0.6, 0.35, {-0.5, 0.5}},       // waist
    {RagdollPart::Torso, RagdollPart::Head, {0, 0.605, 0}, false, {0, 1, 0}, 0.7, 0.5, {-1.0, 1.0}},         // neck
    {RagdollPart::Torso, RagdollPart::LeftUpperArm, {0, 0.5, -0.26}, false, {0, -1, 0}, 1.5, 0.8, {-0.8, 0.8}},   // shoulders
    {RagdollPart::Torso, RagdollPart::RightUpperArm, {0, 0.5, 0.26}, false, {0, -1, 0}, 1.5, 0.8, {-0.8, 0.8}},
    {RagdollPart::LeftUpperArm, RagdollPart::LeftLowerArm, {0, 0.2, -0.26}, true, {0, 0, 1}, 0, 0, {0, 2.4}},   // elbows
    {RagdollPart::RightUpperArm, RagdollPart::RightLowerArm, {0, 0.2, 0.26}, true, {0, 0, 1}, 0, 0, {0, 2.4}},
    {RagdollPart::Pelvis, RagdollPart::LeftThigh, {0, -0.05, -0.1}, false, {0, -1, 0}, 1.4, 0.6, {-0.6, 0.6}},  // hips
    {RagdollPart::Pelvis, RagdollPart::RightThigh, {0, -0.05, 0.1}, false, {0, -1, 0}, 1.4, 0.6, {-0.6, 0.6}},
    {RagdollPart::LeftThigh, RagdollPart::LeftShin, {0, -0.5, -0.1}, true, {0, 0, 1}, 0, 0, {-2.4, 0}},      // knees
    {RagdollPart::RightThigh, RagdollPart::RightShin, {0, -0.5, 0.1}, true, {0, 0, 1}, 0, 0, {-2.4, 0}},
};

JointSettings jointOf(const JointShape &shape, const Ragdoll &r, const Quaternion &q, const Vector3 &place,
                      real friction) {
    JointSettings j;
    j.friction = friction;
    const BodyId parent = r.bodies[static_cast<int>(shape.parent)];
    const BodyId child = r.bodies[static_cast<int>(shape.child)];
    j.anchor = place;
    j.axis = q * shape.axis;
    if (shape.hinge) {
        j.type = JointType::Hinge;
        j.a = child;
        j.b = parent;
        j.limits = shape.range;
        return j;
    }
    j.type = JointType::Ball;
    j.a = parent;
    j.b = child;
    j.normal = q * Vector3::UnitX();
    j.swingLimit = JointSwingLimit{shape.forward, shape.sideways};
    j.twistLimit = shape.range;
    return j;
}

}  // namespace

Ragdoll addRagdoll(World &world, const RagdollSettings &settings) {
    static const char *function = "addRagdoll";
    if (!(settings.height >= 0.1 && settings.height <= 10))
        detail::refuse(function, "height", "must be in [0.1, 10] m, got " + detail::show(settings.height));
    if (!(settings.mass > 0) || !std::isfinite(settings.mass))
        detail::refuse(function, "mass", "must be finite and > 0, got " + detail::show(settings.mass));
    const real scale = settings.height / kReferenceHeight;
    const real massScale = settings.mass / kReferenceMass;
    const Quaternion q = settings.orientation.norm() > 0 ? settings.orientation.normalized() : settings.orientation;
    const Quaternion upright = q * Quaternion(Eigen::AngleAxis<real>(M_PI / 2, Vector3::UnitX()));
    Ragdoll r;
    int added = 0;
    try {
        for (; added < kRagdollParts; ++added) {
            const PartShape &p = kParts[added];
            BodySettings s;
            s.shape = Shape::capsule(p.radius * scale, p.length * scale);
            s.mass = p.mass * massScale;
            s.position = settings.position + q * (scale * p.centre);
            s.orientation = p.upright ? upright : settings.orientation;
            s.velocity = settings.velocity;
            s.layer = settings.layer;
            s.collidesWith = settings.collidesWith;
            r.bodies[added] = world.addBody(s);
        }
        for (int k = 0; k < kRagdollJoints; ++k)
            r.joints[k] = world.addJoint(
                jointOf(kJoints[k], r, q, settings.position + q * (scale * kJoints[k].anchor), settings.jointFriction));
    } catch (...) {
        for (int k = 0; k < added; ++k) world.removeBody(r.bodies[k]);
        throw;
    }
    return r;
}

}  // namespace cyclone
