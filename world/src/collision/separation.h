// Two convex solids apart: how far, and along which line, by GJK on their cores. The
// narrowphase's speculative contacts need no more than that, which FCL's distance query
// (libccd's GJK) gave at a higher cost and, on curved sides, up to 0.1 mm long.
#pragma once

#include "collision/collision_shape.h"

namespace cyclone::detail {

/// The radius a sphere or capsule adds around its core (its centre, its axis segment);
/// 0 for other shapes, which are their own core.
inline real coreRadius(const CollisionShape &shape) {
    const ShapeType type = shape.shape().type;
    return type == ShapeType::Sphere || type == ShapeType::Capsule ? shape.shape().radius : 0;
}

/// The support point of the shape's core along d (supportPoint less the radius along d).
inline Vector3 coreSupport(const CollisionShape &shape, const Matrix4 &pose, const Vector3 &d, int triangle) {
    switch (shape.shape().type) {
        case ShapeType::Sphere: return pose.translation();
        case ShapeType::Capsule: {
            const Vector3 axis = pose.linear().col(2);
            const real half = shape.shape().length / 2;
            return pose.translation() + (axis.dot(d) >= 0 ? half : -half) * axis;
        }
        default: return shape.supportPoint(pose, d, triangle);
    }
}

/// Whether two bounded convex solids (box, sphere, capsule, cylinder, hull) lie apart;
/// if so, their distance (m) and the unit direction from A's nearest point to B's. False
/// when they touch or overlap.
bool separation(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                real &distance, Vector3 &direction);

}  // namespace cyclone::detail
