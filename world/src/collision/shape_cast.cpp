// Shape casts by conservative advancement (Mirtich): at each step the GJK distance d and
// the unit direction n from the moving shape to the target give the closing speed
// s = translation.n; the distance of two convex shapes is convex along a translation, so
// it stays above its tangent d - s t and the shape may advance by d / s without passing
// the first touch. A few steps reach the tolerance (one for flat contacts).
#include "collision/shape_cast.h"

#include <algorithm>
#include <cmath>

#include "collision/gjk.h"
#include "collision/heightfield.h"
#include "collision/narrowphase.h"

namespace cyclone::detail {
namespace {

constexpr int kMaxSteps = 64;
// A shape touching a surface at the start and moving within this sine of parallel to it
// slides along it.
constexpr real kSlideSine = 1e-3;

Matrix4 moved(const Matrix4 &start, const Vector3 &translation, real t) {
    Matrix4 pose = start;
    pose.translation() += t * translation;
    return pose;
}

// One convex shape (triangle `triangle` of a mesh target) against another. `faceNormal`:
// for a mesh triangle, its unit normal turned towards the moving shape's start.
bool castConvex(const CollisionShape &moving, const Matrix4 &start, const Vector3 &translation,
                const CollisionShape &target, const Matrix4 &targetPose, int triangle, const Vector3 *faceNormal,
                real limit, CastHit &hit) {
    real t = 0;
    Vector3 normal = -translation.normalized();  // A to B: replaced by the first distance
    for (int step = 0; step < kMaxSteps; ++step) {
        const Matrix4 pose = moved(start, translation, t);
        const auto support = [&](const Vector3 &d) {
            return Vector3(target.supportPoint(targetPose, d, triangle) - moving.supportPoint(pose, -d, -1));
        };
        Vector3 between;
        if (!closestToOrigin(support, translation, between)) {
            if (step > 0) break;  // touching at t, along the last normal
            // Overlapping at the start: a hit only when the motion goes deeper.
            Vector3 inward;
            if (faceNormal) {
                inward = -*faceNormal;
            } else {
                std::vector<Manifold> contact;
                if (collide(moving, pose, target, targetPose, NarrowphaseSettings(), contact) == 0) return false;
                inward = contact[0].normal;
            }
            if (!(translation.dot(inward) > 0)) return false;
            normal = inward;
            break;
        }
        const real gap = between.norm();
        normal = between / gap;
        const real speed = translation.dot(normal);
        if (!(speed > 0)) return false;  // parting or sliding past: never closer
        if (gap <= kShapeCastTolerance) {
            // Touching at the start: sliding along the surface (within the GJK normal's
            // noise, 1e-3 rad) is not a hit.
            if (step == 0 && speed <= kSlideSine * translation.norm()) return false;
            break;
        }
        t += (gap - kShapeCastTolerance / 2) / speed;
        if (t > limit) return false;
    }
    if (t > limit) return false;
    hit.fraction = t;
    hit.normal = -normal;
    hit.point = moving.supportPoint(moved(start, translation, t), normal, -1);
    return true;
}

bool castAgainstPlane(const CollisionShape &moving, const Matrix4 &start, const Vector3 &translation,
                      const CollisionShape &plane, const Matrix4 &planePose, real limit, CastHit &hit) {
    const Vector3 up = planePose.linear() * plane.planeNormal();
    const real level = up.dot(planePose.translation()) + plane.planeOffset();
    const Vector3 lowest = moving.supportPoint(start, -up, -1);
    const real height = up.dot(lowest) - level;
    const real closing = -translation.dot(up);
    if (!(closing > 0)) return false;
    const real t = std::max(real(0), (height - kShapeCastTolerance / 2) / closing);
    if (t > limit) return false;
    hit.fraction = t;
    hit.normal = up;
    hit.point = lowest + t * translation;
    return true;
}

bool castAgainstMesh(const CollisionShape &moving, const Matrix4 &start, const Vector3 &translation,
                     const CollisionShape &mesh, const Matrix4 &meshPose, real limit, CastHit &hit) {
    // The swept shape's box in the mesh's frame, against each triangle's.
    const Matrix4 toMesh = meshPose.inverse();
    const Vector3 radius = Vector3::Constant(moving.boundingRadius() + kShapeCastTolerance);
    const Vector3 from = toMesh * start.translation();
    const Vector3 to = toMesh * (start.translation() + limit * translation);
    const Vector3 low = from.cwiseMin(to) - radius;
    const Vector3 high = from.cwiseMax(to) + radius;
    bool found = false;
    for (std::size_t f = 0; f < mesh.faces().size(); ++f) {
        const std::vector<int> &tri = mesh.faces()[f];
        Vector3 lo = mesh.vertices()[tri[0]], hi = lo;
        for (int k = 1; k < 3; ++k) {
            lo = lo.cwiseMin(mesh.vertices()[tri[k]]);
            hi = hi.cwiseMax(mesh.vertices()[tri[k]]);
        }
        if ((lo.array() > high.array()).any() || (hi.array() < low.array()).any()) continue;
        Vector3 face = meshPose.linear() * mesh.faceNormals()[f];
        if (face.dot(start.translation() - meshPose * mesh.vertices()[tri[0]]) < 0) face = -face;
        CastHit candidate;
        if (!castConvex(moving, start, translation, mesh, meshPose, static_cast<int>(f), &face, limit, candidate))
            continue;
        if (found && !(candidate.fraction < hit.fraction)) continue;
        hit = candidate;
        limit = candidate.fraction;
        found = true;
    }
    return found;
}

// The triangles of the cells under the swept shape's box (heightfield.h), each cast as a
// mesh's triangle; the solid lies below, so each pushes upwards.
bool castAgainstHeightfield(const CollisionShape &moving, const Matrix4 &start, const Vector3 &translation,
                            const CollisionShape &field, const Matrix4 &fieldPose, real limit, CastHit &hit) {
    const Matrix4 toField = fieldPose.inverse();
    const Vector3 radius = Vector3::Constant(moving.boundingRadius() + kShapeCastTolerance);
    const Vector3 from = toField * start.translation();
    const Vector3 to = toField * (start.translation() + limit * translation);
    bool found = false;
    HeightfieldGrid(field.shape()).forEachTriangleIn(from.cwiseMin(to) - radius, from.cwiseMax(to) + radius, [&](int t) {
        const Vector3 face = fieldPose.linear() * field.triangleNormal(t);
        CastHit candidate;
        if (castConvex(moving, start, translation, field, fieldPose, t, &face, limit, candidate) &&
            (!found || candidate.fraction < hit.fraction)) {
            hit = candidate;
            limit = candidate.fraction;
            found = true;
        }
        return true;
    });
    return found;
}

}  // namespace

bool castShape(const CollisionShape &moving, const Matrix4 &start, const Vector3 &translation,
               const CollisionShape &target, const Matrix4 &targetPose, real limit, CastHit &hit) {
    // A compound on either side: the earliest hit of any pair of children.
    if (moving.isCompound() || target.isCompound()) {
        bool found = false;
        const bool movingCompound = moving.isCompound();
        const CollisionShape &split = movingCompound ? moving : target;
        for (std::size_t k = 0; k < split.children().size(); ++k) {
            CastHit candidate;
            const bool hitChild =
                movingCompound
                    ? castShape(*split.children()[k].shape, partPose(split, k, start), translation, target, targetPose,
                                limit, candidate)
                    : castShape(moving, start, translation, *split.children()[k].shape,
                                partPose(split, k, targetPose), limit, candidate);
            if (!hitChild || (found && !(candidate.fraction < hit.fraction))) continue;
            hit = candidate;
            limit = candidate.fraction;
            found = true;
        }
        return found;
    }
    switch (target.shape().type) {
        case ShapeType::Plane: return castAgainstPlane(moving, start, translation, target, targetPose, limit, hit);
        case ShapeType::Mesh: return castAgainstMesh(moving, start, translation, target, targetPose, limit, hit);
        case ShapeType::Heightfield:
            return castAgainstHeightfield(moving, start, translation, target, targetPose, limit, hit);
        default: return castConvex(moving, start, translation, target, targetPose, -1, nullptr, limit, hit);
    }
}

}  // namespace cyclone::detail
