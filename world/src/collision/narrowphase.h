// Narrowphase: FCL contact detection between two placed shapes, turned into contact
// manifolds of up to four well-spread points.
#pragma once

#include <array>
#include <vector>

#include "collision/collision_shape.h"

namespace cyclone::detail {

/// One contact point of a manifold, world space.
struct ContactPoint {
    Vector3 pointA = Vector3::Zero();  ///< On A's surface: A's deepest point into B, m.
    Vector3 pointB = Vector3::Zero();  ///< On B's surface, m.
    real depth = 0;                    ///< (pointA - pointB).normal: > 0 penetrating, < 0 apart, m.
};

/// Contact between two shapes along one normal.
struct Manifold {
    static constexpr int kMaxPoints = 4;
    Vector3 normal = Vector3::UnitY();  ///< Unit, world space, pointing from A to B.
    int count = 0;
    std::array<ContactPoint, kMaxPoints> points;
    int childA = 0;  ///< The child of A it touches when A is a compound, else 0.
    int childB = 0;  ///< The child of B it touches when B is a compound, else 0.
};

struct NarrowphaseSettings {
    /// Clipped points up to this far apart are kept (speculative contact), m, >= 0.
    real speculativeDistance = 0.02;
    /// Shapes apart by less than this still get a manifold, its points' depths down to
    /// -reach (a speculative contact: the solver lets them close the gap and no more), m,
    /// >= 0. 0: only shapes that overlap or touch.
    real reach = 0;
    /// The pairs with a test of their own (box-box, sphere-sphere, sphere-box, a plane
    /// against a solid shape) also give a manifold to shapes apart by up to this, m, >= 0:
    /// shapes placed to touch are often apart by a rounding error, and without a contact
    /// a resting body would fall into what it rests on for a whole step. Costs those
    /// tests nothing; FCL's pairs and meshes do not use it.
    real touchMargin = 0;
    /// Test every pair with FCL, even the pairs that have a test of their own (box-box,
    /// sphere-sphere, sphere-box, sphere-capsule, capsule-capsule, capsule-box, a cylinder
    /// against a cylinder or a capsule, a plane against any solid shape); for comparing
    /// the two.
    bool forceFcl = false;
    /// Whether the pair had no contact when last tested. A pair that goes to FCL then
    /// first tries to show by GJK's lower bound on the distance that it is still farther
    /// apart than the reach: cheaper than FCL's tests when it is, wasted when it touches.
    bool wasApart = false;
};

/// What collide() learnt of two convex solids that FCL tested (not a plane, a mesh or a
/// compound): whether FCL found them touching and, if so, the normal chosen. Both depend
/// on the two shapes and their poses only, so a later test of the same shapes at the same
/// poses, bit for bit, takes them from here instead of FCL's test and the choice of
/// normal, and builds the very manifold the full test would (docs/solver.md, "Landing
/// correction").
struct NormalMemo {
    const CollisionShape *a = nullptr;  ///< The shapes tested; null: nothing kept.
    const CollisionShape *b = nullptr;
    Eigen::Matrix<real, 3, 4> poseA;  ///< A's pose tested: rotation, then translation.
    Eigen::Matrix<real, 3, 4> poseB;  ///< B's pose tested.
    bool touching = false;            ///< Whether FCL found them touching.
    Vector3 normal = Vector3::UnitY();  ///< When touching: the normal chosen, A to B.

    /// Whether it holds shapes `a` and `b` at exactly these poses.
    bool holds(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB) const;
    /// Keeps what a test of `a` at `poseA` and `b` at `poseB` found.
    void keep(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
              bool touching, const Vector3 &normal);
};

/// Tests shapes `a` at `poseA` and `b` at `poseB` and appends one manifold per contact
/// normal to `out` (none when apart; a mesh may give several). Returns the number
/// appended. Box-box (separating axes), sphere-sphere, sphere-box, sphere-capsule,
/// capsule-capsule, capsule-box (closest features, round_pairs.h), a cylinder against a
/// cylinder or a capsule where a round side faces the other (cylinder_pairs.h; FCL
/// confirms the contact unless two round sides face each other) and a plane against any
/// solid shape have tests of their own; every other pair goes through FCL's contact test
/// (GST_LIBCCD, through collideShapes), and so does every pair with `settings.forceFcl`,
/// unless a box or an axis (or for a pair `settings.wasApart`, GJK's lower bound on their
/// distance) shows the two more than the reach apart (nothing appended).
/// Normals point from A to B whatever order FCL used internally; near-zero normals are
/// dropped. A mesh pushes a shape out to the side of each triangle that Shape::sides
/// allows (both sides: the side the shape's centre is on), and contacts on its inner
/// edges take the face normal (mesh_contacts.h). A compound is tested child by child (each child pair
/// whose boxes, widened by the speculative distance, overlap), and its manifolds name
/// the children (Manifold::childA, childB). Allocates nothing once `out` has grown, except
/// inside FCL for box-box pairs forced through it and for meshes. With a `memo`, two
/// convex solids that go to FCL take FCL's answer and the normal from it when it holds
/// them at these poses, and leave this test's there otherwise.
int collide(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
            const NarrowphaseSettings &settings, std::vector<Manifold> &out, NormalMemo *memo = nullptr);

/// Whether `a` at `poseA` and `b` at `poseB` overlap or touch, by fcl::collide (a
/// compound child by child).
bool intersects(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB);

/// The order in which collide() lists the points of a manifold, applied to `count`
/// (<= Manifold::kMaxPoints) existing points with B-side positions `pointB` and depths
/// `depth` along `normal`: the deepest (of equally deep ones, the farthest from their
/// centre), the farthest from it, the one spanning the largest triangle with those two,
/// then the one adding the most area. Writes a permutation of 0..count-1 into `order`
/// (points that add nothing come last). The contact solver visits points in this order,
/// and Gauss-Seidel favours the first: a manifold reused without the narrowphase is put
/// in this order again so that, like a fresh one, it starts from its deepest point.
void contactOrder(const Vector3 *pointB, const real *depth, int count, const Vector3 &normal, int *order);

}  // namespace cyclone::detail
