// Narrowphase: FCL says whether two shapes touch; the manifold is built here from the
// normal of least overlap (contact_normal.cpp) and the features clipped along it
// (manifold_clipping.cpp). Box-box, boxes and hulls of few edges (polytope.cpp), sphere
// pairs, capsule pairs (round_pairs.cpp), cylinders against cylinders and capsules
// (cylinder_pairs.cpp) and planes have tests of their own.
//
// Meshes give one FCL contact per triangle; mesh_contacts.cpp builds their manifolds.
//
// Everything here lives in fixed-size arrays on the stack; only FCL allocates (see
// shape_contact.cpp for which of its calls still do).
#include "collision/narrowphase.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "collision/box_box.h"
#include "collision/broadphase.h"
#include "collision/contact_building.h"
#include "collision/cylinder_pairs.h"
#include "collision/gjk.h"
#include "collision/mesh_contacts.h"
#include "collision/polytope.h"
#include "collision/round_pairs.h"
#include "collision/shape_contact.h"
#include "collision/sphere_pairs.h"

namespace cyclone::detail {
namespace {

fcl::CollisionRequestd makeRequest(size_t maxContacts) {
    fcl::CollisionRequestd request(maxContacts, true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    return request;
}

// FCL's contact request for two shapes, or for a shape and a mesh (one contact per triangle).
const fcl::CollisionRequestd &contactRequest(bool withMesh) {
    static const fcl::CollisionRequestd shapeRequest = makeRequest(4);
    static const fcl::CollisionRequestd meshRequest = makeRequest(kMaxFclContacts);
    return withMesh ? meshRequest : shapeRequest;
}

// Whether FCL's libccd solver has an exact routine for the pair; the others go through
// MPR, whose normal is only a starting point.
bool exactInFcl(ShapeType a, ShapeType b) {
    if (a == ShapeType::Sphere) std::swap(a, b);
    if (b == ShapeType::Sphere) return a != ShapeType::Convex;
    return a == ShapeType::Box && b == ShapeType::Box;
}

// The points of two convex shapes along `normal` (A to B): their supporting features
// clipped against each other.
void clippedPoints(const Pair &pair, const Vector3 &normal, PointSet &points) {
    SupportFeature fa, fb;
    pair.a.supportingFeature(pair.poseA, normal, -1, fa);
    pair.b.supportingFeature(pair.poseB, -normal, -1, fb);
    clipFeatures(pair, normal, fa, fb, points);
}

// The manifold of two convex shapes along `normal`: their clipped points, reduced to at
// most four.
int clipAlong(const Pair &pair, const Vector3 &normal, std::vector<Manifold> &out) {
    PointSet points;
    clippedPoints(pair, normal, points);
    return appendReduced(points, normal, out);
}

// The manifold of a cylinder and a cylinder or capsule along `normal`: the features
// clipped as in clipAlong, and the axis segments' ends of nearly parallel cores.
int roundPairManifold(const Pair &pair, const Vector3 &normal, std::vector<Manifold> &out) {
    PointSet points;
    clippedPoints(pair, normal, points);
    addAxisEnds(axisCore(pair.a, pair.poseA), axisCore(pair.b, pair.poseB), normal, pair.speculative, points);
    return appendReduced(points, normal, out);
}

// Convex shapes FCL found apart: a speculative manifold when they are closer than
// `reach`, along the line between their nearest points (fcl::distance), clipped from the
// features that face each other along it.
int apartContact(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                 real reach, std::vector<Manifold> &out, bool roundPair = false) {
    // The distance costs as much as the contact test: pairs that close less than this in
    // a step (0.3 m/s at 60 Hz) go without, and enter each other at most that far (plus
    // what gravity adds within the step) before their contact acts, m.
    constexpr real kMinDistanceReach = 0.005;
    // The most the shapes may overlap along the nearest points' line, m (none, but for
    // rounding).
    constexpr real kApartNormalError = 1e-4;
    if (!(reach >= kMinDistanceReach)) return 0;
    static const fcl::DistanceRequestd request = [] {
        fcl::DistanceRequestd r(true);
        r.gjk_solver_type = fcl::GST_LIBCCD;
        return r;
    }();
    fcl::DistanceResultd result;
    const real distance = distanceShapes(a.geometry().get(), poseA, b.geometry().get(), poseB, request, result);
    if (!(distance > 0 && distance < reach)) return 0;
    const Vector3 between = result.nearest_points[1] - result.nearest_points[0];
    if (!(between.norm() > kMinNormalLength)) return 0;
    Vector3 normal = between.normalized();
    const Pair pair{a, poseA, -1, b, poseB, -1, reach, reach};
    // Nearest points a hair apart give no direction: along the line between them the
    // shapes may overlap deeply, and the clipped points would claim that depth. The
    // normal of least overlap (which the touching pairs take) is then the contact's; a
    // pair that overlaps along it too gets none.
    if (!(pair.overlap(normal) <= kApartNormalError)) {
        SupportFeature fa, fb;
        real overlap = 0;
        normal = chooseNormal(pair, normal, NormalRule{}, true, fa, fb, overlap);
        if (!(overlap <= kApartNormalError)) return 0;
    }
    return roundPair ? roundPairManifold(pair, normal, out) : clipAlong(pair, normal, out);
}

// A cylinder against a cylinder or a capsule where two round sides face each other, from
// their closest features (cylinder_pairs.cpp); -1 for the others, which FCL tests.
int cylinderContact(const Pair &pair, real reach, std::vector<Manifold> &out) {
    Vector3 normal;
    switch (cylinderPairNormal(pair, axisCore(pair.a, pair.poseA), axisCore(pair.b, pair.poseB), reach, normal)) {
        case CylinderPairResult::Apart: return 0;
        case CylinderPairResult::NotHandled: return -1;
        case CylinderPairResult::Found: break;
    }
    return roundPairManifold(pair, normal, out);
}

// A plane against a solid shape: a solid shape's support point is exact, so it touches
// the half-space when that point lies on or below the surface (as in FCL). A mesh needs
// FCL's triangles (-1); a heightfield never meets a plane (both static).
int planePairContact(const Pair &pair, bool planeIsA, real reach, std::vector<Manifold> &out) {
    const CollisionShape &plane = planeIsA ? pair.a : pair.b;
    const Matrix4 &planePose = planeIsA ? pair.poseA : pair.poseB;
    const CollisionShape &other = planeIsA ? pair.b : pair.a;
    if (other.hasTriangles()) return other.shape().type == ShapeType::Heightfield ? 0 : -1;
    const Vector3 up = planePose.linear() * plane.planeNormal();
    const real level = up.dot(planePose.translation()) + plane.planeOffset();
    const Vector3 deepest = other.supportPoint(planeIsA ? pair.poseB : pair.poseA, -up, -1);
    if (!(level - deepest.dot(up) >= -reach)) return 0;
    return planeContact(pair, planeIsA, out);
}

// A sphere against a sphere, a box or a capsule (-1 for other shapes).
int spherePairContact(const Pair &pair, bool sphereIsA, real reach, std::vector<Manifold> &out) {
    const CollisionShape &sphere = sphereIsA ? pair.a : pair.b;
    const CollisionShape &other = sphereIsA ? pair.b : pair.a;
    const Vector3 centre = (sphereIsA ? pair.poseA : pair.poseB).translation();
    const Matrix4 &otherPose = sphereIsA ? pair.poseB : pair.poseA;
    Manifold manifold;
    bool hit = false;
    if (other.shape().type == ShapeType::Sphere)
        hit = sphereSphere(sphere.shape().radius, centre, other.shape().radius, otherPose.translation(), manifold,
                           reach);
    else if (other.shape().type == ShapeType::Box)
        hit = sphereBox(sphere.shape().radius, centre, other.shape().halfExtents, otherPose, manifold, reach);
    else if (other.shape().type == ShapeType::Capsule) {
        const AxisCore core = axisCore(other, otherPose);
        hit = sphereCapsule(sphere.shape().radius, centre, core.radius, core.end0, core.end1, manifold, reach);
    } else
        return -1;
    if (!hit) return 0;
    if (!sphereIsA) {
        // Computed with the sphere as A: turned into (a, b)'s order.
        manifold.normal = -manifold.normal;
        std::swap(manifold.points[0].pointA, manifold.points[0].pointB);
    }
    out.push_back(manifold);
    return 1;
}

// A capsule against a capsule or a box (-1 for other shapes): the normal from the
// closest features, the points clipped along it.
int capsulePairContact(const Pair &pair, bool capsuleIsA, real reach, std::vector<Manifold> &out) {
    const CollisionShape &capsule = capsuleIsA ? pair.a : pair.b;
    const CollisionShape &other = capsuleIsA ? pair.b : pair.a;
    const Matrix4 &otherPose = capsuleIsA ? pair.poseB : pair.poseA;
    const AxisCore core = axisCore(capsule, capsuleIsA ? pair.poseA : pair.poseB);
    // Found from the capsule (or A's capsule) to the other shape.
    Vector3 normal;
    real depth = 0;
    bool hit = false;
    if (other.shape().type == ShapeType::Capsule) {
        const AxisCore otherCore = axisCore(other, otherPose);
        hit = capsuleCapsuleNormal(core.radius, core.end0, core.end1, otherCore.radius, otherCore.end0, otherCore.end1,
                                   normal, depth, reach);
    } else if (other.shape().type == ShapeType::Box) {
        hit = capsuleBoxNormal(core.radius, core.end0, core.end1, other.shape().halfExtents, otherPose, normal, depth,
                               reach);
    } else {
        return -1;
    }
    if (!hit) return 0;
    return clipAlong(pair, capsuleIsA ? normal : Vector3(-normal), out);
}

// Whether two solids (not planes or meshes) lie farther apart than `gap`, by their boxes
// and by their extents along the line between their origins; false when unsure.
bool solidsApart(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                 real gap) {
    if (boxesApart(*a.geometry(), poseA, *b.geometry(), poseB, gap)) return true;
    const Vector3 between = poseB.translation() - poseA.translation();
    const real length = between.norm();
    if (!(length > kMinNormalLength)) return false;
    const Vector3 u = between / length;
    // B's nearest extent along u beyond A's farthest one: a separating axis.
    return (b.supportPoint(poseB, -u, -1) - a.supportPoint(poseA, u, -1)).dot(u) > gap;
}

// Whether GJK on B - A shows the two solids farther apart than `gap`: the proof for a
// pair whose boxes meet but whose solids do not (cylinders side by side in a pile); false
// when unsure.
bool supportsApart(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                   real gap) {
    const auto support = [&](const Vector3 &d) {
        return Vector3(b.supportPoint(poseB, d, -1) - a.supportPoint(poseA, -d, -1));
    };
    const Vector3 between = poseB.translation() - poseA.translation();
    const real length = between.norm();
    return fartherThan(support, length > kMinNormalLength ? Vector3(-between / length) : Vector3::UnitX(), gap);
}

// The pairs with a test of their own, which FCL would only have told touch: the
// manifolds they append are the ones the FCL path builds (the same normal, by least
// overlap, and the same clipping). Returns the number appended, or -1 for a pair that
// needs FCL.
int nativeContact(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                  const NarrowphaseSettings &settings, std::vector<Manifold> &out) {
    const ShapeType typeA = a.shape().type;
    const ShapeType typeB = b.shape().type;
    const real reach = std::max(settings.reach, settings.touchMargin);
    const Pair pair{a, poseA, -1, b, poseB, -1, std::max(settings.speculativeDistance, reach), settings.reach};
    if (typeA == ShapeType::Plane || typeB == ShapeType::Plane)
        return planePairContact(pair, typeA == ShapeType::Plane, reach, out);
    if (typeA == ShapeType::Box && typeB == ShapeType::Box) {
        Vector3 normal;
        real overlap = 0;
        if (!boxBoxAxis(a.shape().halfExtents, poseA, b.shape().halfExtents, poseB, normal, overlap, reach))
            return 0;
        return clipAlong(pair, normal, out);
    }
    const auto polytope = [](ShapeType type) { return type == ShapeType::Box || type == ShapeType::Convex; };
    if (polytope(typeA) && polytope(typeB)) {
        BoxCorners roomA, roomB;
        const Polytope polytopeA = polytopeOf(a, roomA), polytopeB = polytopeOf(b, roomB);
        if (separatingAxesSuit(polytopeA, polytopeB)) {
            if (solidsApart(a, poseA, b, poseB, reach)) return 0;
            Vector3 normal;
            real overlap = 0;
            if (!polytopeAxis(polytopeA, poseA, polytopeB, poseB, normal, overlap, reach)) return 0;
            return clipAlong(pair, normal, out);
        }
        return -1;
    }
    if (typeA == ShapeType::Sphere || typeB == ShapeType::Sphere)
        return spherePairContact(pair, typeA == ShapeType::Sphere, reach, out);
    if (typeA == ShapeType::Cylinder || typeB == ShapeType::Cylinder)
        return cylinderRoundPair(typeA, typeB) ? cylinderContact(pair, reach, out) : -1;
    if (typeA == ShapeType::Capsule || typeB == ShapeType::Capsule)
        return capsulePairContact(pair, typeA == ShapeType::Capsule, reach, out);
    return -1;
}

// Child pairs a compound pair tests at most in one call. A pair keeps at most 32
// manifolds (ContactManager::kMaxCompoundManifolds); five compounds of 300 children at
// one point had 90,000 child pairs each whose boxes met, and took 1-1.5 s a step.
// Beyond the budget the child pairs whose boxes overlap deepest are tested (the likeliest
// to be the deepest contacts), in the same (i, j) order as the rest.
constexpr std::size_t kMaxChildPairs = 256;

// A child pair whose boxes meet, and how deep: the least overlap of the boxes over the
// three axes (m; >= -speculative distance).
struct ChildPair {
    real overlap;
    std::uint32_t i, j;
};

real boxOverlap(const fcl::AABBd &x, const fcl::AABBd &y) {
    return (x.max_.cwiseMin(y.max_) - x.min_.cwiseMax(y.min_)).minCoeff();
}

// The child pairs of a and b whose boxes (A's widened by the speculative distance) meet,
// at most kMaxChildPairs of them, deepest first when more meet, in (i, j) order.
void childPairsToTest(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                      real speculative, std::vector<ChildPair> &pairs) {
    static thread_local std::vector<fcl::AABBd> boxesB;
    const std::size_t countA = a.isCompound() ? a.children().size() : 1;
    const std::size_t countB = b.isCompound() ? b.children().size() : 1;
    boxesB.clear();
    for (std::size_t j = 0; j < countB; ++j) {
        const CollisionShape &childB = b.isCompound() ? *b.children()[j].shape : b;
        boxesB.push_back(placedBox(*childB.geometry(), b.isCompound() ? partPose(b, j, poseB) : poseB));
    }
    pairs.clear();
    for (std::size_t i = 0; i < countA; ++i) {
        const CollisionShape &childA = a.isCompound() ? *a.children()[i].shape : a;
        const fcl::AABBd boxA =
            placedBox(*childA.geometry(), a.isCompound() ? partPose(a, i, poseA) : poseA, speculative);
        for (std::size_t j = 0; j < countB; ++j)
            if (boxA.overlap(boxesB[j]))
                pairs.push_back({boxOverlap(boxA, boxesB[j]), static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
    }
    if (pairs.size() <= kMaxChildPairs) return;
    const auto deeper = [](const ChildPair &x, const ChildPair &y) {
        if (x.overlap != y.overlap) return x.overlap > y.overlap;
        return x.i != y.i ? x.i < y.i : x.j < y.j;
    };
    std::nth_element(pairs.begin(), pairs.begin() + kMaxChildPairs, pairs.end(), deeper);
    pairs.resize(kMaxChildPairs);
    std::sort(pairs.begin(), pairs.end(),
              [](const ChildPair &x, const ChildPair &y) { return x.i != y.i ? x.i < y.i : x.j < y.j; });
}

// A compound against any shape (or another compound): each pair of children whose boxes
// come within the speculative distance (at most kMaxChildPairs of them), its manifolds
// tagged with the children.
int collideCompound(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                    const NarrowphaseSettings &settings, std::vector<Manifold> &out) {
    static thread_local std::vector<ChildPair> pairs;
    // A half-space has no box to compare with: every child is tested against it.
    if (a.shape().type == ShapeType::Plane || b.shape().type == ShapeType::Plane) {
        pairs.clear();
        const std::size_t countA = a.isCompound() ? a.children().size() : 1;
        const std::size_t countB = b.isCompound() ? b.children().size() : 1;
        for (std::size_t i = 0; i < countA; ++i)
            for (std::size_t j = 0; j < countB; ++j)
                pairs.push_back({0, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
    } else {
        childPairsToTest(a, poseA, b, poseB, settings.speculativeDistance, pairs);
    }
    int appended = 0;
    for (const ChildPair &pair : pairs) {
        const CollisionShape &childA = a.isCompound() ? *a.children()[pair.i].shape : a;
        const Matrix4 childPoseA = a.isCompound() ? partPose(a, pair.i, poseA) : poseA;
        const CollisionShape &childB = b.isCompound() ? *b.children()[pair.j].shape : b;
        const Matrix4 childPoseB = b.isCompound() ? partPose(b, pair.j, poseB) : poseB;
        const std::size_t first = out.size();
        const int n = collide(childA, childPoseA, childB, childPoseB, settings, out);
        for (std::size_t k = first; k < out.size(); ++k) {
            out[k].childA = static_cast<int>(pair.i);
            out[k].childB = static_cast<int>(pair.j);
        }
        appended += n;
    }
    return appended;
}

// FCL's contacts of `a` and `b` with a usable normal, turned into `raw` (A to B whatever
// order FCL used); returns how many.
int fclContacts(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                const fcl::CollisionRequestd &request, RawContact *raw) {
    // Reused so that its contact vector keeps its capacity between calls.
    static thread_local fcl::CollisionResultd result;
    result.clear();
    collideShapes(a.geometry().get(), poseA, b.geometry().get(), poseB, request, result);
    int rawCount = 0;
    for (size_t i = 0; i < result.numContacts() && rawCount < kMaxFclContacts; ++i) {
        const fcl::Contactd &contact = result.getContact(i);
        const real length = contact.normal.norm();
        if (!(length > kMinNormalLength)) continue;
        // FCL puts the mesh first when a shape is tested against a mesh.
        const bool swapped = contact.o1 != a.geometry().get();
        RawContact &r = raw[rawCount++];
        r.normal = (swapped ? -contact.normal : contact.normal) / length;
        r.depth = std::abs(contact.penetration_depth);
        r.triangleA = static_cast<int>(swapped ? contact.b2 : contact.b1);
        r.triangleB = static_cast<int>(swapped ? contact.b1 : contact.b2);
    }
    return rawCount;
}

// Two convex solids that FCL tests (not a plane, a mesh or a compound): apart, a
// speculative contact (apartContact); touching, one normal, chosen from FCL's deepest
// contact (FCL's extra box-box points are rebuilt by clipping along it), or taken from
// `memo` when it holds the pair at these poses.
int convexContact(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                  const NarrowphaseSettings &settings, std::vector<Manifold> &out, NormalMemo *memo) {
    const ShapeType typeA = a.shape().type;
    const ShapeType typeB = b.shape().type;
    const bool roundPair = cylinderRoundPair(typeA, typeB);
    const real speculative = std::max(settings.speculativeDistance, settings.reach);
    const Pair pair{a, poseA, -1, b, poseB, -1, speculative, settings.reach};
    SupportFeature fa, fb;
    Vector3 normal;
    if (memo && memo->holds(a, poseA, b, poseB)) {
        if (!memo->touching) return apartContact(a, poseA, b, poseB, settings.reach, out, roundPair);
        // The features chooseNormal leaves are those along its normal.
        normal = memo->normal;
        a.supportingFeature(poseA, normal, -1, fa);
        b.supportingFeature(poseB, -normal, -1, fb);
    } else {
        RawContact raw[kMaxFclContacts];
        const int rawCount = fclContacts(a, poseA, b, poseB, contactRequest(false), raw);
        if (rawCount == 0) {
            if (memo) memo->keep(a, poseA, b, poseB, false, Vector3::UnitY());
            return apartContact(a, poseA, b, poseB, settings.reach, out, roundPair);
        }
        int deepest = 0;
        for (int i = 1; i < rawCount; ++i)
            if (raw[i].depth > raw[deepest].depth) deepest = i;
        real overlap = 0;
        normal = chooseNormal(pair, raw[deepest].normal, NormalRule(), !exactInFcl(typeA, typeB), fa, fb, overlap);
        if (memo) memo->keep(a, poseA, b, poseB, true, normal);
    }
    PointSet points;
    clipFeatures(pair, normal, fa, fb, points);
    if (roundPair) addAxisEnds(axisCore(a, poseA), axisCore(b, poseB), normal, speculative, points);
    return appendReduced(points, normal, out);
}

// Whether `pose`'s rotation and translation are `kept`, bit for bit.
bool samePose(const Eigen::Matrix<real, 3, 4> &kept, const Matrix4 &pose) {
    const Eigen::Matrix<real, 3, 4> now = pose.affine();
    return std::memcmp(kept.data(), now.data(), sizeof now) == 0;
}

}  // namespace

bool NormalMemo::holds(const CollisionShape &shapeA, const Matrix4 &placeA, const CollisionShape &shapeB,
                       const Matrix4 &placeB) const {
    return a == &shapeA && b == &shapeB && samePose(poseA, placeA) && samePose(poseB, placeB);
}

void NormalMemo::keep(const CollisionShape &shapeA, const Matrix4 &placeA, const CollisionShape &shapeB,
                      const Matrix4 &placeB, bool touched, const Vector3 &chosen) {
    a = &shapeA;
    b = &shapeB;
    poseA = placeA.affine();
    poseB = placeB.affine();
    touching = touched;
    normal = chosen;
}

int collide(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
            const NarrowphaseSettings &settings, std::vector<Manifold> &out, NormalMemo *memo) {
    if (a.isCompound() || b.isCompound()) return collideCompound(a, poseA, b, poseB, settings, out);
    const ShapeType typeA = a.shape().type;
    const ShapeType typeB = b.shape().type;
    if (typeA == ShapeType::Plane && typeB == ShapeType::Plane) return 0;
    if (!settings.forceFcl) {
        const int appended = nativeContact(a, poseA, b, poseB, settings, out);
        if (appended >= 0) return appended;
    }
    if (typeA == ShapeType::Heightfield || typeB == ShapeType::Heightfield) {
        // The triangles of the cells the other shape's box covers (mesh_contacts.cpp);
        // nothing for FCL to test (its geometry is the field's box). A test of its own, so
        // shapes apart by up to the touch margin get a manifold too: a body that comes to
        // rest a hair above the surface would otherwise fall into it for a whole step.
        if (a.hasTriangles() && b.hasTriangles()) return 0;
        if (typeA == ShapeType::Plane || typeB == ShapeType::Plane) return 0;
        return meshContacts(a, poseA, b, poseB, settings.speculativeDistance,
                            std::max(settings.reach, settings.touchMargin), nullptr, 0, out);
    }
    const bool withMesh = typeA == ShapeType::Mesh || typeB == ShapeType::Mesh;
    const bool withPlane = typeA == ShapeType::Plane || typeB == ShapeType::Plane;
    // Two solids get a manifold below only when FCL finds them touching or apart by less
    // than the reach: a separating axis farther apart than that (by more than FCL's
    // tolerances) rules both out, for the price of two boxes and two support points
    // instead of MPR and GJK.
    constexpr real kBoxesApartMargin = 0.001;  // m, far above libccd's 1e-6 tolerances
    if (!withMesh && !withPlane) {
        if (solidsApart(a, poseA, b, poseB, settings.reach + kBoxesApartMargin)) return 0;
        if (settings.wasApart && supportsApart(a, poseA, b, poseB, settings.reach + kBoxesApartMargin)) return 0;
        return convexContact(a, poseA, b, poseB, settings, out, memo);
    }

    RawContact raw[kMaxFclContacts];
    const int rawCount = fclContacts(a, poseA, b, poseB, contactRequest(withMesh), raw);
    if (withMesh && !withPlane)
        return meshContacts(a, poseA, b, poseB, settings.speculativeDistance, settings.reach, raw, rawCount, out);
    // A plane forced through FCL (NarrowphaseSettings::forceFcl) against a solid apart.
    if (rawCount == 0) return withMesh ? 0 : apartContact(a, poseA, b, poseB, settings.reach, out);
    const real speculative = std::max(settings.speculativeDistance, settings.reach);
    const Pair pair{a, poseA, raw[0].triangleA, b, poseB, raw[0].triangleB, speculative, settings.reach};
    return planeContact(pair, typeA == ShapeType::Plane, out);
}

}  // namespace cyclone::detail

namespace cyclone::detail {

bool intersects(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB) {
    if (a.isCompound()) {
        for (std::size_t k = 0; k < a.children().size(); ++k)
            if (intersects(*a.children()[k].shape, partPose(a, k, poseA), b, poseB)) return true;
        return false;
    }
    if (b.isCompound()) return intersects(b, poseB, a, poseA);
    if (a.shape().type == ShapeType::Heightfield || b.shape().type == ShapeType::Heightfield) {
        // Its triangles' manifolds (FCL sees only the field's box): touching when a point
        // is at or below the surface.
        static thread_local std::vector<Manifold> manifolds;
        manifolds.clear();
        NarrowphaseSettings settings;
        settings.speculativeDistance = 0;
        collide(a, poseA, b, poseB, settings, manifolds);
        for (const Manifold &m : manifolds)
            for (int k = 0; k < m.count; ++k)
                if (m.points[k].depth >= 0) return true;
        return false;
    }
    static const fcl::CollisionRequestd request = [] {
        fcl::CollisionRequestd r(1, false);
        r.gjk_solver_type = fcl::GST_LIBCCD;
        return r;
    }();
    static thread_local fcl::CollisionResultd result;
    result.clear();
    fcl::collide(a.geometry().get(), poseA, b.geometry().get(), poseB, request, result);
    return result.isCollision();
}

}  // namespace cyclone::detail
