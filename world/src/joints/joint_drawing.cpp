// Joints drawn for debugging (World::debugDraw): anchors, axes, limits.
#include <algorithm>
#include <cmath>

#include "joints/joint_set.h"

namespace cyclone::detail {
namespace {

// A unit vector perpendicular to the unit `n`.
Vector3 perpendicular(const Vector3 &n) {
    const Vector3 helper = std::abs(n.x()) < 0.57 ? Vector3::UnitX() : Vector3::UnitY();
    return n.cross(helper).normalized();
}

void cross(DebugDraw &draw, const Vector3 &at, real size, const DebugColor &color) {
    for (int k = 0; k < 3; ++k) draw.line(at - size * Vector3::Unit(k), at + size * Vector3::Unit(k), color);
}

// The arc of directions R(axis, angle) zero for angle in [lower, upper] at `radius` from
// `centre`, with its two ends' spokes.
void arc(DebugDraw &draw, const Vector3 &centre, const Vector3 &axis, const Vector3 &zero, const JointLimits &range,
         real radius, int segments, const DebugColor &color) {
    const int n = std::max(1, static_cast<int>(std::ceil(segments * (range.upper - range.lower) / (2 * M_PI))));
    const auto at = [&](real angle) -> Vector3 { return centre + radius * (Eigen::AngleAxis<real>(angle, axis) * zero); };
    Vector3 previous = at(range.lower);
    draw.line(centre, previous, color);
    for (int k = 1; k <= n; ++k) {
        const Vector3 next = at(range.lower + (range.upper - range.lower) * k / n);
        draw.line(previous, next, color);
        previous = next;
    }
    draw.line(centre, previous, color);
}

// A ball joint's swing cone, fixed in a: its rim at `radius` from the anchor, and four
// spokes (towards the normal and across it, both ways).
void cone(DebugDraw &draw, const Vector3 &apex, const Vector3 &axis, const Vector3 &normal, const JointSwingLimit &c,
          real radius, int segments, const DebugColor &color) {
    const Vector3 binormal = axis.cross(normal);
    const auto rim = [&](real phi) -> Vector3 {
        const real e = std::hypot(std::cos(phi) / c.normalAngle, std::sin(phi) / c.binormalAngle);
        const real theta = 1 / e;
        return apex + radius * (std::cos(theta) * axis + std::sin(theta) * (std::cos(phi) * normal + std::sin(phi) * binormal));
    };
    Vector3 previous = rim(0);
    for (int k = 1; k <= segments; ++k) {
        const Vector3 next = rim(2 * M_PI * k / segments);
        draw.line(previous, next, color);
        previous = next;
    }
    for (int k = 0; k < 4; ++k) draw.line(apex, rim(M_PI / 2 * k), color);
}

}  // namespace

void JointSet::draw(const BodyStore &bodies, DebugDraw &draw, const DebugDrawOptions &options) const {
    const real size = options.jointSize;
    for (const JointRecord &j : records) {
        if (!j.alive) continue;
        const RigidBody &a = bodies[j.settings.a.index].body;
        const RigidBody *b = j.settings.b ? &bodies[j.settings.b->index].body : nullptr;
        const Quaternion qa = a.getOrientation();
        const Quaternion qb = b ? b->getOrientation() : Quaternion::Identity();
        const Vector3 pa = a.getPointInWorldSpace(j.localA);
        const Vector3 pb = b ? b->getPointInWorldSpace(j.localB) : j.localB;
        if (!pa.allFinite() || !pb.allFinite()) continue;
        cross(draw, pa, 0.2 * size, options.jointAnchor);
        if ((pa - pb).norm() > 1e-6) {
            cross(draw, pb, 0.2 * size, options.jointAnchor);
            draw.line(pa, pb, options.jointAnchor);
        }
        const JointSettings &s = j.settings;
        const bool axial = s.type == JointType::Hinge || s.type == JointType::Slider;
        if (!axial && !s.swingLimit && !s.twistLimit) continue;
        const Vector3 axis = qb * j.axisB;  // b's axis
        draw.line(pb - size * axis, pb + size * axis, options.jointAxis);
        if (s.type == JointType::Slider && s.limits) {
            const Vector3 side = size * 0.3 * perpendicular(axis);
            for (const real offset : {s.limits->lower, s.limits->upper})
                draw.line(pb + offset * axis - side, pb + offset * axis + side, options.jointLimit);
            continue;
        }
        // A hinge's or the twist's angle: a's perpendicular v turns about b's axis from
        // where the reference pose puts it in b (q_b ref v at angle 0).
        const Vector3 v = perpendicular(j.axisA);
        const Vector3 zero = qb * (j.reference * v);
        const Vector3 now = qa * v;
        const std::optional<JointLimits> &range = s.type == JointType::Hinge ? s.limits : s.twistLimit;
        const Vector3 zeroAcross = zero - zero.dot(axis) * axis, nowAcross = now - now.dot(axis) * axis;
        if (range && zeroAcross.norm() > 1e-9 && nowAcross.norm() > 1e-9) {
            arc(draw, pb, axis, zeroAcross.normalized(), *range, size, options.circleSegments, options.jointLimit);
            draw.line(pb, pb + size * nowAcross.normalized(), options.jointAxis);
        }
        if (s.swingLimit)
            cone(draw, pa, qa * j.axisA, qa * j.normalA, *s.swingLimit, size, options.circleSegments, options.jointLimit);
    }
}

}  // namespace cyclone::detail
