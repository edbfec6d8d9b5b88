#include "collision/round_side.h"

#include <algorithm>
#include <cmath>

namespace cyclone::detail {

RoundCore roundCore(const CollisionShape &shape, int child) {
    const CollisionShape *part = &shape;
    Matrix4 pose = Matrix4::Identity();
    if (shape.isCompound()) {
        const CompoundPart &p = shape.children()[static_cast<std::size_t>(child)];
        part = p.shape.get();
        pose = p.pose;
    }
    const Shape &s = part->shape();
    RoundCore core;
    switch (s.type) {
        case ShapeType::Sphere: core.radius = s.radius; break;
        case ShapeType::Capsule:
            core.radius = s.radius;
            core.halfLength = s.length / 2;
            break;
        case ShapeType::Cylinder:
            core.radius = s.radius;
            core.halfLength = s.length / 2;
            core.cylinder = true;
            break;
        default: return core;
    }
    core.centre = pose.translation();
    if (s.type != ShapeType::Sphere) core.axis = pose.linear() * Vector3::UnitZ();
    return core;
}

bool onRoundPart(const RoundCore &core, const Vector3 &outward) {
    // cos 15 degrees: supportingFeature's cap (collision_shape.h).
    constexpr real kCap = 0.9659258262890683;
    return core.radius > 0 && (!core.cylinder || std::abs(core.axis.dot(outward)) < kCap);
}

bool mayBeRound(const CollisionShape &shape) {
    const ShapeType type = shape.shape().type;
    return type == ShapeType::Sphere || type == ShapeType::Capsule || type == ShapeType::Cylinder ||
           type == ShapeType::Compound;
}

RoundCore roundSideAt(const CollisionShape &shape, int child, const Vector3 &outward) {
    if (!mayBeRound(shape)) return RoundCore();
    RoundCore core = roundCore(shape, child);
    if (!onRoundPart(core, outward)) core.radius = 0;
    return core;
}

bool farthestSideLine(const CollisionShape &shape, const Matrix4 &pose, const Vector3 &direction, Vector3 &end0,
                      Vector3 &end1) {
    const Shape &s = shape.shape();
    if (s.type != ShapeType::Capsule && s.type != ShapeType::Cylinder) return false;
    if (!(s.length > 0)) return false;
    const Vector3 axis = pose.linear().col(2);
    Vector3 outward = direction;
    if (s.type == ShapeType::Cylinder) {
        outward -= axis.dot(direction) * axis;
        const real across = outward.norm();
        if (!(across > 0)) return false;
        outward /= across;
    }
    const Vector3 half = axis * (s.length / 2);
    end0 = pose.translation() - half + s.radius * outward;
    end1 = pose.translation() + half + s.radius * outward;
    return true;
}

Vector3 nearestCorePoint(const RoundCore &core, const Vector3 &point) {
    const real along = std::clamp(core.axis.dot(point - core.centre), -core.halfLength, core.halfLength);
    return core.centre + along * core.axis;
}

real roundDepthChange(const RoundCore &core, const Vector3 &start, const Vector3 &now) {
    if (!core.cylinder) return core.radius * (1 - start.dot(now));
    const Vector3 across0 = start - core.axis.dot(start) * core.axis;
    const Vector3 across = now - core.axis.dot(now) * core.axis;
    const real length0 = across0.norm();
    if (!(length0 > 0)) return 0;
    return core.radius * (across.norm() - across0.dot(now) / length0);
}

}  // namespace cyclone::detail
