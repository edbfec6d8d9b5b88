// What building a contact manifold shares between its parts: the pair under test, the
// candidate points, and the steps that the narrowphase (narrowphase.cpp), the choice of
// normal (contact_normal.cpp) and the clipping (manifold_clipping.cpp) call on each other.
#pragma once

#include <vector>

#include "collision/narrowphase.h"

namespace cyclone::detail {

inline constexpr int kMaxFclContacts = 16;
// Clipping a polygon against a polygon adds at most one vertex per side plane.
inline constexpr int kMaxClipped = 2 * SupportFeature::kMaxPoints + 2;
// Candidate points of one manifold: a few triangles' worth of clipped points.
inline constexpr int kMaxMerged = 2 * kMaxClipped + 2 * Manifold::kMaxPoints;
// FCL normals shorter than this are meaningless (coincident centres).
inline constexpr real kMinNormalLength = 1e-9;
// A face candidate wins a tie within this overlap (m): exact face normals for resting.
inline constexpr real kFacePreference = 1e-9;
// Points closer than this are one point; areas below it times a length are zero, m.
inline constexpr real kPointTolerance = 1e-6;
// Depths within this of the deepest count as equally deep, m.
inline constexpr real kDepthTie = 1e-5;
// Two segments whose directions differ by less than 2 degrees are parallel: sin(2 deg).
inline constexpr real kParallelSine = 0.03489949670250097;
// A mesh contact whose normal is within 0.5 degrees of its triangle's is a face contact:
// cos(0.5 deg).
inline constexpr real kFaceCosine = 0.9999619230641713;
// Mesh contacts whose normals agree within 2 degrees share a manifold: cos(2 deg).
inline constexpr real kMergeCosine = 0.9993908270190958;
// Faces whose alignments with the normal differ by less than this are equally aligned.
inline constexpr real kFaceTie = 1e-9;
// Faces whose normals are within 1 degree of opposite lie flat on each other: cos(1 deg).
inline constexpr real kFlatCosine = 0.9998476951563913;
// A segment within 1 degree of parallel to a face lies flat on it: sin(1 deg).
inline constexpr real kFlatSine = 0.01745240643728351;
// Edge-edge axes are tried when the two features have at most this many edge pairs.
inline constexpr int kMaxEdgePairs = 72;
// Refinement of MPR normals: how far beyond touching A is moved back (m), and how many
// times at most.
inline constexpr real kRefineMargin = 1e-3;
inline constexpr int kRefineRounds = 4;
// Halvings back towards the current normal when the nearest points overshoot.
inline constexpr int kRefineHalvings = 3;

// Candidate contact points; plain storage, filled before it is read.
struct PointSet {
    struct Point {
        Vector3 pointA, pointB;
        real depth;
        /// Kept only for a pair that may turn as it lands (beyond the speculative
        /// distance, Pair::landingKeep): it fills what the other points leave free.
        bool landing;
    };
    int count = 0;
    Point points[kMaxMerged];

    void add(const Vector3 &pointA, const Vector3 &pointB, real depth, bool landing = false) {
        if (count == kMaxMerged) return;
        Point &p = points[count++];
        p.pointA = pointA;
        p.pointB = pointB;
        p.depth = depth;
        p.landing = landing;
    }
};

// The two shapes of a test, their poses and the triangles FCL reported (-1 for none).
struct Pair {
    const CollisionShape &a;
    const Matrix4 &poseA;
    int triangleA;
    const CollisionShape &b;
    const Matrix4 &poseB;
    int triangleB;
    real speculative;
    /// How far the two may close within the step (m; 0 at rest): a body landing tilted
    /// turns about its first contact and its far side comes down faster than the body
    /// fell, so points over a face are kept within landingKeep() (manifold_clipping.cpp).
    real reach = 0;

    real landingKeep() const { return speculative + reach; }

    // Separating-axis overlap along n (A to B): how far B must move along n to clear A.
    real overlap(const Vector3 &n) const {
        return (a.supportPoint(poseA, n, triangleA) - b.supportPoint(poseB, -n, triangleB)).dot(n);
    }

    // Whether the overlap along n (unit) surely exceeds `level`, from the balls inside
    // the two shapes alone: A reaches along n at least its inner radius beyond its origin,
    // B back along -n as far, so the overlap is at least (originA - originB).n plus both
    // radii. False when unsure (a shape without an inner ball, a triangle). The margin
    // covers the rounding of both sides: a candidate it rules out is one the exact test
    // would have refused too.
    bool overlapExceeds(const Vector3 &n, real level) const {
        constexpr real kMargin = 1e-9;  // m
        const real ra = a.innerRadius(), rb = b.innerRadius();
        if (triangleA >= 0 || triangleB >= 0 || ra < 0 || rb < 0) return false;
        return (poseA.translation() - poseB.translation()).dot(n) + ra + rb > level + kMargin;
    }
};

// Unit normal of a counter-clockwise polygon (Newell), relative to its first point so
// that far-from-origin faces keep their precision.
inline Vector3 polygonNormal(const SupportFeature &f) {
    Vector3 sum = Vector3::Zero();
    for (int i = 1; i + 1 < f.count; ++i) sum += (f.points[i] - f.points[0]).cross(f.points[i + 1] - f.points[0]);
    const real length = sum.norm();
    return length > 0 ? Vector3(sum / length) : Vector3::Zero();
}

// Which normals a contact may take. Against a mesh triangle (which pushes a shape out
// to one side, mesh_contacts.cpp) a normal must not push the shape through the
// triangle: n.front >= 0, `front` being the triangle's normal towards that side turned
// into a normal from A to B. Other pairs take any direction.
struct NormalRule {
    bool oneSided = false;
    Vector3 front = Vector3::Zero();

    bool allows(const Vector3 &n) const { return !oneSided || n.dot(front) >= 0; }
};

/// The normal of one contact from FCL's normal `fclNormal`: the candidate of least
/// overlap among FCL's, the supporting faces', their edges' cross products and (for
/// cylinders) the cap's and side's, refined when FCL's normal came from MPR (`refine`),
/// and (for a cylinder with a cylinder or a capsule) the line between their cores.
/// Leaves the features along it in fa and fb, and the overlap along it in `overlap`.
Vector3 chooseNormal(const Pair &pair, const Vector3 &fclNormal, const NormalRule &rule, bool refine,
                     SupportFeature &fa, SupportFeature &fb, real &overlap);

/// Whether features fa and fb, seen along n, overlap: the one clipped against the side
/// planes of the other (a polygon, A's when both are) keeps some of itself.
bool overlapAlong(const SupportFeature &fa, const SupportFeature &fb, const Vector3 &n);

/// Keeps at most four points of `in` (the deepest, the farthest from it, the one
/// spanning the largest triangle with those two, the one adding the most area).
void reduce(const PointSet::Point *in, int count, const Vector3 &n, Manifold &out);

/// Appends the manifold reduced from `points` along `n` to `out` (landing points only
/// where the others leave room, deepest first); returns how many were appended (0 when
/// there are no points).
int appendReduced(const PointSet &points, const Vector3 &n, std::vector<Manifold> &out);

/// Builds the contact points of features fa (A's along n) and fb (B's along -n). When
/// clipping leaves none (the features do not overlap along n), the shapes' nearest points
/// along n, unless `pointIfApart` is false.
void clipFeatures(const Pair &pair, const Vector3 &n, const SupportFeature &fa, const SupportFeature &fb,
                  PointSet &out, bool pointIfApart = true);

/// A plane against anything: exact normal, every incident point measured to the plane.
int planeContact(const Pair &pair, bool planeIsA, std::vector<Manifold> &out);

}  // namespace cyclone::detail
