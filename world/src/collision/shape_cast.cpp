// Shape casts by conservative advancement (Mirtich): at each step the GJK distance d and
// the unit direction n from the moving shape to the target give a bound s on how fast
// any point of the moving shape closes along n: the translation's part along n, plus,
// when it turns, angle |n x axis| times the farthest its points lie from the pivot. No
// point crosses the separating plane before d / s, so the shape advances by that. For a
// straight cast s is the closing speed itself, and the distance of two convex shapes is
// convex along a translation, so a few steps reach the tolerance (one for flat contacts).
//
// The distance is our GJK (gjk.h) on support points rather than fcl::distance: it is
// what the straight cast and the contacts use on a mesh's or a height field's single
// triangle (FCL has no geometry for one triangle of a field), so a zero turn is the
// straight cast step for step. FCL's own continuousCollide (CCDM_SCREW,
// CCDC_CONSERVATIVE_ADVANCEMENT) was not used: it dispatches on FCL's node types, and
// our height fields and compounds are FCL boxes (their broadphase bounds), so it would
// cast against those boxes.
#include "collision/shape_cast.h"

#include <algorithm>
#include <cmath>

#include "collision/gjk.h"
#include "collision/heightfield.h"
#include "collision/narrowphase.h"

namespace cyclone::detail {
namespace {

constexpr int kMaxSteps = 64;
// A turning cast's bound stays above the closing speed where the shape passes close by
// a target without touching it, so it takes smaller steps there.
constexpr int kMaxTurningSteps = 256;
// A shape touching a surface at the start and moving within this sine of parallel to it
// slides along it.
constexpr real kSlideSine = 1e-3;

// One convex shape (triangle `triangle` of a mesh target) against another. `faceNormal`:
// for a mesh triangle, its unit normal turned towards the moving shape's start.
bool castConvex(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
                const CollisionShape &target, const Matrix4 &targetPose, int triangle, const Vector3 *faceNormal,
                real limit, CastHit &hit) {
    // GJK's first direction (any will do).
    const Vector3 search = motion.translation.isZero(0) ? Vector3(Vector3::UnitX()) : motion.translation;
    const real reach = motion.reach(start, moving.boundingRadius());
    const int steps = motion.angle == 0 ? kMaxSteps : kMaxTurningSteps;
    real t = 0;
    Vector3 normal = -search.normalized();  // A to B: replaced by the first distance
    for (int step = 0; step < steps; ++step) {
        const Matrix4 pose = motion.at(start, t);
        const auto support = [&](const Vector3 &d) {
            return Vector3(target.supportPoint(targetPose, d, triangle) - moving.supportPoint(pose, -d, -1));
        };
        Vector3 between;
        if (!closestToOrigin(support, search, between)) {
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
            const Vector3 deepest = moving.supportPoint(pose, inward, -1);
            if (!(motion.velocity(deepest, 0).dot(inward) > 0)) return false;
            normal = inward;
            break;
        }
        const real gap = between.norm();
        normal = between / gap;
        const real speed = motion.closingBound(normal, reach);
        if (!(speed > 0)) return false;  // parting or sliding past: never closer
        if (gap <= kShapeCastTolerance) {
            // Touching at the start: sliding along the surface (within the GJK normal's
            // noise, 1e-3 rad) is not a hit.
            if (step == 0) {
                const Vector3 velocity = motion.velocity(moving.supportPoint(pose, normal, -1), 0);
                if (velocity.dot(normal) <= kSlideSine * velocity.norm()) return false;
            }
            break;
        }
        t += (gap - kShapeCastTolerance / 2) / speed;
        if (t > limit) return false;
    }
    if (t > limit) return false;
    hit.fraction = t;
    hit.normal = -normal;
    hit.point = moving.supportPoint(motion.at(start, t), normal, -1);
    return true;
}

// A turning shape against a plane: conservative advancement on its lowest point's height.
bool castTurningAgainstPlane(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
                             const Vector3 &up, real level, real limit, CastHit &hit) {
    const real reach = motion.reach(start, moving.boundingRadius());
    real t = 0;
    Vector3 lowest = moving.supportPoint(start, -up, -1);
    for (int step = 0; step < kMaxTurningSteps; ++step) {
        lowest = moving.supportPoint(motion.at(start, t), -up, -1);
        const real height = up.dot(lowest) - level;
        if (height <= kShapeCastTolerance) {
            // In or on it at the start: a hit only when the lowest point goes deeper.
            if (step == 0 && !(motion.velocity(lowest, 0).dot(up) < 0)) return false;
            break;
        }
        const real closing = motion.closingBound(-up, reach);
        if (!(closing > 0)) return false;
        t += (height - kShapeCastTolerance / 2) / closing;
        if (t > limit) return false;
    }
    hit.fraction = t;
    hit.normal = up;
    hit.point = lowest;
    return true;
}

bool castAgainstPlane(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
                      const CollisionShape &plane, const Matrix4 &planePose, real limit, CastHit &hit) {
    const Vector3 up = planePose.linear() * plane.planeNormal();
    const real level = up.dot(planePose.translation()) + plane.planeOffset();
    if (motion.angle != 0) return castTurningAgainstPlane(moving, start, motion, up, level, limit, hit);
    const Vector3 &translation = motion.translation;
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

// The box, in the frame `toLocal` maps world space to, that the moving shape sweeps up to
// `limit`: the path of its centre (of the pivot, when it turns) widened by how far its
// points lie from it.
void sweptBox(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion, const Matrix4 &toLocal,
              real limit, Vector3 &low, Vector3 &high) {
    const bool turns = motion.angle != 0;
    const Vector3 centre = turns ? motion.pivot : Vector3(start.translation());
    const real far = turns ? motion.reach(start, moving.boundingRadius()) : moving.boundingRadius();
    const Vector3 radius = Vector3::Constant(far + kShapeCastTolerance);
    const Vector3 from = toLocal * centre;
    const Vector3 to = toLocal * (centre + limit * motion.translation);
    low = from.cwiseMin(to) - radius;
    high = from.cwiseMax(to) + radius;
}

bool castAgainstMesh(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
                     const CollisionShape &mesh, const Matrix4 &meshPose, real limit, CastHit &hit) {
    // The swept shape's box in the mesh's frame, against each triangle's.
    Vector3 low, high;
    sweptBox(moving, start, motion, meshPose.inverse(), limit, low, high);
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
        if (!castConvex(moving, start, motion, mesh, meshPose, static_cast<int>(f), &face, limit, candidate))
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
bool castAgainstHeightfield(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
                            const CollisionShape &field, const Matrix4 &fieldPose, real limit, CastHit &hit) {
    Vector3 low, high;
    sweptBox(moving, start, motion, fieldPose.inverse(), limit, low, high);
    bool found = false;
    HeightfieldGrid(field.shape()).forEachTriangleIn(low, high, [&](int t) {
        const Vector3 face = fieldPose.linear() * field.triangleNormal(t);
        CastHit candidate;
        if (castConvex(moving, start, motion, field, fieldPose, t, &face, limit, candidate) &&
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

Matrix4 CastMotion::at(const Matrix4 &start, real s) const {
    Matrix4 pose = start;
    pose.translation() += s * translation;
    if (angle != 0) {
        const Matrix3 turn = Eigen::AngleAxis<real>(s * angle, axis).toRotationMatrix();
        pose.linear() = turn * start.linear();
        pose.translation() = pivot + s * translation + turn * (start.translation() - pivot);
    }
    return pose;
}

Vector3 CastMotion::velocity(const Vector3 &point, real s) const {
    if (angle == 0) return translation;
    return translation + angle * axis.cross(point - (pivot + s * translation));
}

real CastMotion::closingBound(const Vector3 &direction, real reach) const {
    const real along = translation.dot(direction);
    if (angle == 0) return along;
    // A point r from the pivot moves by angle (axis x r).direction = angle r.(direction x axis).
    return along + angle * direction.cross(axis).norm() * reach;
}

real CastMotion::reach(const Matrix4 &start, real radius) const {
    return angle == 0 ? 0 : (start.translation() - pivot).norm() + radius;
}

bool castShape(const CollisionShape &moving, const Matrix4 &start, const CastMotion &motion,
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
                    ? castShape(*split.children()[k].shape, partPose(split, k, start), motion, target, targetPose, limit,
                                candidate)
                    : castShape(moving, start, motion, *split.children()[k].shape, partPose(split, k, targetPose), limit,
                                candidate);
            if (!hitChild || (found && !(candidate.fraction < hit.fraction))) continue;
            hit = candidate;
            limit = candidate.fraction;
            found = true;
        }
        return found;
    }
    switch (target.shape().type) {
        case ShapeType::Plane: return castAgainstPlane(moving, start, motion, target, targetPose, limit, hit);
        case ShapeType::Mesh: return castAgainstMesh(moving, start, motion, target, targetPose, limit, hit);
        case ShapeType::Heightfield: return castAgainstHeightfield(moving, start, motion, target, targetPose, limit, hit);
        default: return castConvex(moving, start, motion, target, targetPose, -1, nullptr, limit, hit);
    }
}

}  // namespace cyclone::detail
