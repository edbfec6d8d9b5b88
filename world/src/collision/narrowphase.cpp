// Narrowphase: FCL says whether two shapes touch; the manifold is built here.
//
// FCL (libccd) returns one contact for most pairs, and its normal comes from MPR for
// curved shapes and convex polytopes: close, but tilted enough to rock a box resting on
// a face, and for shapes against triangles often far off. So FCL's normal is only one
// candidate, with the normals of the two supporting faces, the cross products of their
// edges and, for cylinders, the cap and side normals; the candidate along which the
// shapes' projections overlap least wins, since that overlap bounds the penetration
// from above (separating axes). Ties go to a face, so resting contacts get the exact
// face normal. Where FCL used MPR, the winner is then refined: the pair moved apart
// along it no longer touches, and GJK's nearest points give the surfaces' common normal.
//
// The manifold is clipped as in Jolt's ManifoldBetweenTwoFaces: the incident feature is
// clipped against the side planes of the reference face extruded along the normal, each
// clipped point's depth is measured along the normal to the reference plane, points
// within the speculative distance are kept and reduced to four well-spread ones. A plane
// is an unbounded reference face with an exact normal and is never clipped against.
//
// Meshes give one FCL contact per triangle. Triangles are one-sided, as Jolt's are by
// default: a shape is only pushed out to the side a triangle's counter-clockwise winding
// faces, never through it. A contact whose normal is its triangle's normal is a face
// contact and claims the triangle's vertices; an edge or vertex contact on vertices that
// face contacts already claimed is an internal edge of a surface (two triangles of a
// floor) and is dropped, as in Jolt's InternalEdgeRemovingCollector. The remaining
// contacts are merged into one manifold per normal.
//
// Everything here lives in fixed-size arrays on the stack; only FCL allocates (see
// shape_contact.cpp for which of its calls still do).
#include "collision/narrowphase.h"

#include <algorithm>
#include <cmath>

#include "collision/box_box.h"
#include "collision/gjk.h"
#include "collision/shape_contact.h"
#include "collision/sphere_pairs.h"

namespace cyclone::detail {
namespace {

constexpr int kMaxFclContacts = 16;
// Clipping a polygon against a polygon adds at most one vertex per side plane.
constexpr int kMaxClipped = 2 * SupportFeature::kMaxPoints + 2;
// Candidate points of one manifold: a few triangles' worth of clipped points.
constexpr int kMaxMerged = 2 * kMaxClipped + 2 * Manifold::kMaxPoints;
// FCL normals shorter than this are meaningless (coincident centres).
constexpr real kMinNormalLength = 1e-9;
// A face candidate wins a tie within this overlap (m): exact face normals for resting.
constexpr real kFacePreference = 1e-9;
// Points closer than this are one point; areas below it times a length are zero, m.
constexpr real kPointTolerance = 1e-6;
// Depths within this of the deepest count as equally deep, m.
constexpr real kDepthTie = 1e-5;
// Two segments whose directions differ by less than 2 degrees are parallel: sin(2 deg).
constexpr real kParallelSine = 0.03489949670250097;
// A mesh contact whose normal is within 0.5 degrees of its triangle's is a face contact:
// cos(0.5 deg).
constexpr real kFaceCosine = 0.9999619230641713;
// Mesh contacts whose normals agree within 2 degrees share a manifold: cos(2 deg).
constexpr real kMergeCosine = 0.9993908270190958;
// Faces whose alignments with the normal differ by less than this are equally aligned.
constexpr real kFaceTie = 1e-9;
// Faces whose normals are within 1 degree of opposite lie flat on each other: cos(1 deg).
constexpr real kFlatCosine = 0.9998476951563913;
// A segment within 1 degree of parallel to a face lies flat on it: sin(1 deg).
constexpr real kFlatSine = 0.01745240643728351;
// Edge-edge axes are tried when the two features have at most this many edge pairs.
constexpr int kMaxEdgePairs = 72;
// Refinement of MPR normals: how far beyond touching A is moved back (m), and how many
// times at most.
constexpr real kRefineMargin = 1e-3;
constexpr int kRefineRounds = 4;
// Halvings back towards the current normal when the nearest points overshoot.
constexpr int kRefineHalvings = 3;

fcl::CollisionRequestd makeRequest(size_t maxContacts) {
    fcl::CollisionRequestd request(maxContacts, true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    return request;
}

// Candidate contact points; plain storage, filled before it is read.
struct PointSet {
    struct Point {
        Vector3 pointA, pointB;
        real depth;
    };
    int count = 0;
    Point points[kMaxMerged];

    void add(const Vector3 &pointA, const Vector3 &pointB, real depth) {
        if (count == kMaxMerged) return;
        Point &p = points[count++];
        p.pointA = pointA;
        p.pointB = pointB;
        p.depth = depth;
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

    // Separating-axis overlap along n (A to B): how far B must move along n to clear A.
    real overlap(const Vector3 &n) const {
        return (a.supportPoint(poseA, n, triangleA) - b.supportPoint(poseB, -n, triangleB)).dot(n);
    }
};

// Unit normal of a counter-clockwise polygon (Newell), relative to its first point so
// that far-from-origin faces keep their precision.
Vector3 polygonNormal(const SupportFeature &f) {
    Vector3 sum = Vector3::Zero();
    for (int i = 1; i + 1 < f.count; ++i) sum += (f.points[i] - f.points[0]).cross(f.points[i + 1] - f.points[0]);
    const real length = sum.norm();
    return length > 0 ? Vector3(sum / length) : Vector3::Zero();
}

// The choice behind reduce() and contactOrder(): at most `most` (<= 4) of `count`
// points, given their B-side positions and depths, in the order reduce() lists them.
// Count is an int, or std::integral_constant for a count known when compiling (its
// loops then unroll).
template <class Count, class PointB, class Depth>
int spreadOrder(Count count, int most, const Vector3 &n, const PointB &pointB, const Depth &depth, int chosen[4]) {
    if (count <= 0 || most <= 0) return 0;
    chosen[0] = 0;
    chosen[1] = chosen[2] = chosen[3] = -1;
    real deepest = depth(0);
    Vector3 centre = Vector3::Zero();
    for (int i = 0; i < count; ++i) {
        deepest = std::max(deepest, depth(i));
        centre += pointB(i);
    }
    centre /= count;
    real best = -1;
    for (int i = 0; i < count; ++i) {
        if (depth(i) < deepest - kDepthTie) continue;
        const real d = (pointB(i) - centre).squaredNorm();
        if (d > best) best = d, chosen[0] = i;
    }
    if (most == 1) return 1;
    // The searches below skip the points already chosen: their distance or area is zero
    // (up to a fused multiply-add's rounding, far below the tolerances), so they could
    // never win. A reused manifold's order is worked out every step.
    const Vector3 p0 = pointB(chosen[0]);
    best = kPointTolerance * kPointTolerance;
    for (int i = 0; i < count; ++i) {
        if (i == chosen[0]) continue;
        const real d = (pointB(i) - p0).squaredNorm();
        if (d > best) best = d, chosen[1] = i;
    }
    if (chosen[1] < 0) return 1;
    if (most == 2) return 2;
    const Vector3 edge = pointB(chosen[1]) - p0;
    best = kPointTolerance * edge.norm();
    for (int i = 0; i < count; ++i) {
        if (i == chosen[0] || i == chosen[1]) continue;
        const real area = std::abs(edge.cross(pointB(i) - p0).dot(n));
        if (area > best) best = area, chosen[2] = i;
    }
    if (chosen[2] < 0) return 2;
    if (most == 3) return 3;
    const Vector3 corners[3] = {p0, pointB(chosen[1]), pointB(chosen[2])};
    const real orientation = (corners[1] - corners[0]).cross(corners[2] - corners[0]).dot(n) > 0 ? 1 : -1;
    best = kPointTolerance * edge.norm();
    for (int i = 0; i < count; ++i) {
        real added = 0;
        for (int e = 0; e < 3; ++e) {
            const Vector3 &from = corners[e];
            const Vector3 &to = corners[(e + 1) % 3];
            added += std::max<real>(0, -orientation * (to - from).cross(pointB(i) - from).dot(n));
        }
        if (added > best) best = added, chosen[3] = i;
    }
    return chosen[3] < 0 ? 3 : 4;
}

// Keeps at most four points of `in`: the deepest, the farthest from it, the one
// spanning the largest triangle with those two, and the one adding the most area.
// Among equally deep points (a flat contact) the first is the one farthest from their
// centre, a corner rather than a point where a mesh's triangles split the face.
void reduce(const PointSet::Point *in, int count, const Vector3 &n, Manifold &out) {
    out.count = 0;
    out.normal = n;
    int chosen[4];
    const int found = spreadOrder(
        count, Manifold::kMaxPoints, n, [&](int i) -> const Vector3 & { return in[i].pointB; }, [&](int i) { return in[i].depth; }, chosen);
    for (int k = 0; k < found; ++k) {
        ContactPoint &p = out.points[out.count++];
        p.pointA = in[chosen[k]].pointA;
        p.pointB = in[chosen[k]].pointB;
        p.depth = in[chosen[k]].depth;
    }
}

// Appends the manifold reduced from `points` along `n` to `out`; returns how many were
// appended (0 when there are no points).
int appendReduced(const PointSet &points, const Vector3 &n, std::vector<Manifold> &out) {
    if (points.count == 0) return 0;
    Manifold manifold;
    reduce(points.points, points.count, n, manifold);
    out.push_back(manifold);
    return 1;
}

// One point: the support point of whichever feature is a point, depth by overlap.
void pointContact(const Pair &pair, const Vector3 &n, bool pointOnB, PointSet &out) {
    const real depth = pair.overlap(n);
    if (!(depth > -pair.speculative)) return;
    if (pointOnB) {
        const Vector3 pointB = pair.b.supportPoint(pair.poseB, -n, pair.triangleB);
        out.add(pointB + depth * n, pointB, depth);
    } else {
        const Vector3 pointA = pair.a.supportPoint(pair.poseA, n, pair.triangleA);
        out.add(pointA, pointA - depth * n, depth);
    }
}

// Adds incident point q with its depth along n to the reference plane (point origin,
// outward normal plane), if within the speculative distance.
void addClipped(const Vector3 &q, const Vector3 &n, const Vector3 &origin, const Vector3 &plane, bool referenceOnA,
                real speculative, PointSet &out) {
    const real along = n.dot(plane);
    if (std::abs(along) < kPointTolerance) return;
    if (referenceOnA) {
        // q is on B; A's face is at q + t n.
        const real t = (origin - q).dot(plane) / along;
        if (t > -speculative) out.add(q + t * n, q, t);
    } else {
        // q is on A; B's face is at q - t n.
        const real t = (q - origin).dot(plane) / along;
        if (t > -speculative) out.add(q, q - t * n, t);
    }
}

// Segment against segment: parallel ones give their overlap, crossing ones one point.
void clipSegments(const Pair &pair, const Vector3 &n, const SupportFeature &fa, const SupportFeature &fb,
                  PointSet &out) {
    const Vector3 &p0 = fa.points[0];
    const Vector3 u = fa.points[1] - p0;
    const Vector3 v = fb.points[1] - fb.points[0];
    const real lu = u.norm();
    const real lv = v.norm();
    if (lu < kPointTolerance || lv < kPointTolerance) return pointContact(pair, n, false, out);
    if (u.cross(v).norm() > kParallelSine * lu * lv) {
        // Closest points of the two lines, clamped to the segments.
        const Vector3 w = p0 - fb.points[0];
        const real uu = lu * lu, uv = u.dot(v), vv = lv * lv, uw = u.dot(w), vw = v.dot(w);
        const real denominator = uu * vv - uv * uv;
        real s = std::clamp((uv * vw - vv * uw) / denominator, real(0), real(1));
        const real t = std::clamp((uv * s + vw) / vv, real(0), real(1));
        s = std::clamp((uv * t - uw) / uu, real(0), real(1));
        const Vector3 pointA = p0 + s * u;
        const real depth = pair.overlap(n);
        if (depth > -pair.speculative) out.add(pointA, pointA - depth * n, depth);
        return;
    }
    // Parallel: A's segment is the reference; its "face" is the plane through it
    // that is closest to perpendicular to n.
    const Vector3 axis = u / lu;
    Vector3 plane = n - n.dot(axis) * axis;
    if (plane.norm() < kPointTolerance) return pointContact(pair, n, false, out);
    plane.normalize();
    const Vector3 &q0 = fb.points[0];
    const real s0 = (q0 - p0).dot(axis);
    const real s1 = (fb.points[1] - p0).dot(axis);
    const real ds = s1 - s0;
    if (std::abs(ds) < kPointTolerance) return;
    const real lo = std::max<real>(0, std::min(s0, s1));
    const real hi = std::min<real>(lu, std::max(s0, s1));
    if (hi < lo) return;
    addClipped(q0 + (lo - s0) / ds * v, n, p0, plane, true, pair.speculative, out);
    if (hi - lo > kPointTolerance) addClipped(q0 + (hi - s0) / ds * v, n, p0, plane, true, pair.speculative, out);
}

// Clips the incident feature against the side planes of the reference polygon,
// extruded along n; `w` is the reference face's outward side of n (n on A, -n on B).
const Vector3 *clipAgainstFace(const SupportFeature &reference, const Vector3 &w, bool clipSides,
                               const SupportFeature &incident, Vector3 *buffer, Vector3 *scratch, int &count) {
    count = incident.count;
    std::copy(incident.points, incident.points + count, buffer);
    if (!clipSides) return buffer;
    const bool segment = count == 2;
    real distance[kMaxClipped];
    for (int e = 0; e < reference.count && count > 0; ++e) {
        const Vector3 &origin = reference.points[e];
        const Vector3 side = (reference.points[e + 1 < reference.count ? e + 1 : 0] - origin).cross(w);
        if (side.squaredNorm() < kPointTolerance * kPointTolerance * kPointTolerance * kPointTolerance) continue;
        bool outside = false;
        for (int i = 0; i < count; ++i) {
            distance[i] = (buffer[i] - origin).dot(side);
            outside = outside || distance[i] > 0;
        }
        if (!outside) continue;
        if (segment) {
            const real d0 = distance[0], d1 = distance[1];
            if (d0 > 0 && d1 > 0) {
                count = 0;
            } else if (d0 > 0) {
                buffer[0] += d0 / (d0 - d1) * (buffer[1] - buffer[0]);
            } else {
                buffer[1] += d1 / (d1 - d0) * (buffer[0] - buffer[1]);
            }
            continue;
        }
        // Sutherland-Hodgman against one plane, into the other buffer.
        int kept = 0;
        for (int i = 0; i < count; ++i) {
            const int j = i + 1 < count ? i + 1 : 0;
            const real dc = distance[i], dn = distance[j];
            if (dc <= 0 && kept < kMaxClipped) scratch[kept++] = buffer[i];
            if (((dc < 0 && dn > 0) || (dc > 0 && dn < 0)) && kept < kMaxClipped)
                scratch[kept++] = buffer[i] + dc / (dc - dn) * (buffer[j] - buffer[i]);
        }
        count = kept;
        std::swap(buffer, scratch);
    }
    return buffer;
}

// Whether features fa and fb, seen along n, overlap: the one clipped against the side
// planes of the other (a polygon, A's when both are) keeps some of itself.
bool overlapAlong(const SupportFeature &fa, const SupportFeature &fb, const Vector3 &n) {
    const bool referenceOnA = fa.count >= 3;
    Vector3 buffer[kMaxClipped];
    Vector3 scratch[kMaxClipped];
    int count = 0;
    clipAgainstFace(referenceOnA ? fa : fb, referenceOnA ? n : Vector3(-n), true, referenceOnA ? fb : fa, buffer,
                    scratch, count);
    return count > 0;
}

// Builds the contact points of features fa (A's along n) and fb (B's along -n).
void clipFeatures(const Pair &pair, const Vector3 &n, const SupportFeature &fa, const SupportFeature &fb,
                  PointSet &out) {
    const int before = out.count;
    if (fa.count <= 1 || fb.count <= 1) {
        pointContact(pair, n, fb.count == 1 && fa.count != 1, out);
    } else if (fa.count == 2 && fb.count == 2) {
        clipSegments(pair, n, fa, fb, out);
    } else {
        const Vector3 normalA = fa.count >= 3 ? polygonNormal(fa) : Vector3::Zero();
        const Vector3 normalB = fb.count >= 3 ? polygonNormal(fb) : Vector3::Zero();
        const real alignA = fa.count >= 3 ? normalA.dot(n) : -2;
        const real alignB = fb.count >= 3 ? -normalB.dot(n) : -2;
        // Equally aligned faces (resting flat): the one with fewer sides clips faster.
        const bool referenceOnA =
            std::abs(alignA - alignB) < kFaceTie ? fa.count <= fb.count : alignA > alignB;
        const SupportFeature &reference = referenceOnA ? fa : fb;
        const SupportFeature &incident = referenceOnA ? fb : fa;
        const CollisionShape &referenceShape = referenceOnA ? pair.a : pair.b;
        const bool unbounded = referenceShape.shape().type == ShapeType::Plane;
        Vector3 buffer[kMaxClipped];
        Vector3 scratch[kMaxClipped];
        int count = 0;
        const Vector3 *clipped =
            clipAgainstFace(reference, referenceOnA ? n : Vector3(-n), !unbounded, incident, buffer, scratch, count);
        const Vector3 &plane = referenceOnA ? normalA : normalB;
        for (int i = 0; i < count; ++i)
            addClipped(clipped[i], n, reference.points[0], plane, referenceOnA, pair.speculative, out);
    }
    if (out.count == before) pointContact(pair, n, false, out);
}

// A plane against anything: exact normal, every incident point measured to the plane.
int planeContact(const Pair &pair, bool planeIsA, std::vector<Manifold> &out) {
    const CollisionShape &plane = planeIsA ? pair.a : pair.b;
    const Matrix4 &planePose = planeIsA ? pair.poseA : pair.poseB;
    const CollisionShape &other = planeIsA ? pair.b : pair.a;
    const Matrix4 &otherPose = planeIsA ? pair.poseB : pair.poseA;
    const int triangle = planeIsA ? pair.triangleB : pair.triangleA;
    const Vector3 up = planePose.linear() * plane.planeNormal();
    const real level = up.dot(planePose.translation()) + plane.planeOffset();
    SupportFeature feature;
    other.supportingFeature(otherPose, -up, triangle, feature);
    PointSet points;
    auto add = [&](const Vector3 &q, real t) {
        if (planeIsA)
            points.add(q + t * up, q, t);
        else
            points.add(q, q + t * up, t);
    };
    real deepest = -pair.speculative;
    for (int i = 0; i < feature.count; ++i) {
        const Vector3 &q = feature.points[i];
        const real t = level - q.dot(up);
        if (!(t > -pair.speculative)) continue;
        add(q, t);
        deepest = std::max(deepest, t);
    }
    // A convex face with more corners than a feature holds is thinned and may have lost
    // its deepest corner; other features hold theirs (or, a cylinder's cap tilted less
    // than a degree, miss it by a fraction of a millimetre for steadier points).
    if (other.shape().type == ShapeType::Convex || points.count == 0) {
        const Vector3 q = other.supportPoint(otherPose, -up, triangle);
        const real t = level - q.dot(up);
        if (t > deepest + kPointTolerance) add(q, t);
    }
    return appendReduced(points, planeIsA ? up : Vector3(-up), out);
}

// Which normals a contact may take. Against a mesh triangle (one-sided: shapes are
// pushed out to the side its counter-clockwise winding faces) a normal must not push
// the shape through the triangle: n.front >= 0, `front` being the triangle's normal
// turned into a normal from A to B. Other pairs take any direction.
struct NormalRule {
    bool oneSided = false;
    Vector3 front = Vector3::Zero();

    bool allows(const Vector3 &n) const { return !oneSided || n.dot(front) >= 0; }
};

// Improves the normal n (unit, A to B; overlap f along it) the way a separating pair
// finds its normal: A moved back along n by f plus a margin no longer touches B, and
// GJK's nearest points of the two then lie where the surfaces meet, so the line between
// them is the surfaces' common normal there. For curved surfaces less deep than their
// radius of curvature each round brings n closer to the true normal; flat faces give
// theirs at once. A new normal is taken only if it lowers the overlap.
Vector3 refineNormal(const Pair &pair, const NormalRule &rule, Vector3 n, real &f) {
    for (int round = 0; round < kRefineRounds && f > 0; ++round) {
        const Vector3 shift = (f + kRefineMargin) * n;
        auto support = [&](const Vector3 &d) {
            return Vector3(pair.a.supportPoint(pair.poseA, d, pair.triangleA) - shift -
                           pair.b.supportPoint(pair.poseB, -d, pair.triangleB));
        };
        Vector3 closest;
        if (!closestToOrigin(support, -n, closest)) break;
        const real distance = closest.norm();
        if (!(distance > kPointTolerance * kRefineMargin)) break;
        // At a ridge of A - B (a cylinder's rim, a box's edge) the nearest points may
        // overshoot: then try halfway back towards n.
        Vector3 candidate = -closest / distance;
        if ((candidate - n).squaredNorm() < kPointTolerance * kPointTolerance) break;
        real value = 0;
        bool improved = false;
        for (int halving = 0; halving <= kRefineHalvings && !improved; ++halving) {
            if (halving > 0) candidate = (candidate + n).normalized();
            if (!rule.allows(candidate)) continue;
            value = pair.overlap(candidate);
            improved = value < f - kPointTolerance * kPointTolerance;
        }
        if (!improved) break;
        n = candidate;
        f = value;
    }
    return n;
}

// The normal of one FCL contact: among FCL's, the supporting faces', the cross products
// of their edges and (for cylinders) the cap's and side's, the one of least overlap,
// then refined when FCL's normal came from MPR (`refine`). Leaves the features along the chosen normal in fa
// and fb, and the overlap along it in `overlap`.
Vector3 chooseNormal(const Pair &pair, const Vector3 &fclNormal, const NormalRule &rule, bool refine,
                     SupportFeature &fa, SupportFeature &fb, real &overlap) {
    // FCL's normal of a shape against a triangle can point anywhere, even backwards;
    // the triangle's own normal is the start then.
    const Vector3 start = rule.allows(fclNormal) ? fclNormal : rule.front;
    Vector3 best = start;
    real bestOverlap = pair.overlap(start);
    bool bestFlat = false;
    auto consider = [&](const Vector3 &candidate, real preference, bool flat) {
        if (!rule.allows(candidate)) return;
        const real o = pair.overlap(candidate);
        if (o <= bestOverlap + preference) {
            best = candidate;
            bestOverlap = o;
            bestFlat = flat;
        }
    };
    if (rule.oneSided) consider(rule.front, kFacePreference, false);

    // The candidates that the features along `direction` suggest.
    Vector3 featureDirection = Vector3::Zero();
    auto probe = [&](const Vector3 &direction) {
        pair.a.supportingFeature(pair.poseA, direction, pair.triangleA, fa);
        pair.b.supportingFeature(pair.poseB, -direction, pair.triangleB, fb);
        featureDirection = direction;
        const Vector3 normalA = fa.count >= 3 ? polygonNormal(fa) : Vector3::Zero();
        const Vector3 normalB = fb.count >= 3 ? Vector3(-polygonNormal(fb)) : Vector3::Zero();
        // Two faces, or a segment (a capsule's or cylinder's side) and a face, parallel
        // and overlapping seen along the normal lie flat on each other: the face normal
        // needs no refining.
        bool flat = normalA.dot(normalB) > kFlatCosine;
        if ((fa.count == 2 && fb.count >= 3) || (fb.count == 2 && fa.count >= 3)) {
            // A curved side touches a face along its support line along the face's
            // normal, which may not be the line along `direction`.
            const Vector3 &face = fa.count >= 3 ? normalA : normalB;
            SupportFeature sa, sb;
            pair.a.supportingFeature(pair.poseA, face, pair.triangleA, sa);
            pair.b.supportingFeature(pair.poseB, -face, pair.triangleB, sb);
            const SupportFeature &line = sa.count == 2 ? sa : sb;
            flat = line.count == 2 && (sa.count >= 3 || sb.count >= 3) &&
                   std::abs((line.points[1] - line.points[0]).normalized().dot(face)) < kFlatSine &&
                   overlapAlong(sa, sb, face);
        }
        if (normalA.dot(direction) > 0) consider(normalA, kFacePreference, flat);
        if (normalB.dot(direction) > 0) consider(normalB, kFacePreference, flat);
        if (flat) return;
        // Edge against edge: the separating-axis candidates of the two features' edges.
        const int edgesA = fa.count >= 3 ? fa.count : fa.count - 1;
        const int edgesB = fb.count >= 3 ? fb.count : fb.count - 1;
        if (edgesA > 0 && edgesB > 0 && edgesA * edgesB <= kMaxEdgePairs) {
            for (int i = 0; i < edgesA; ++i) {
                const Vector3 ea = fa.points[i + 1 < fa.count ? i + 1 : 0] - fa.points[i];
                for (int j = 0; j < edgesB; ++j) {
                    const Vector3 axis = ea.cross(fb.points[j + 1 < fb.count ? j + 1 : 0] - fb.points[j]);
                    const real length = axis.norm();
                    if (length < kPointTolerance * kPointTolerance) continue;
                    consider(axis.dot(direction) >= 0 ? Vector3(axis / length) : Vector3(-axis / length), 0, false);
                }
            }
        }
        // A cylinder's rim is a ridge where refinement stalls: its cap and side normals,
        // the faces either side of it, are candidates too, and so are the rim's tangent
        // crossed with the other feature's edges.
        for (int side = 0; side < 2; ++side) {
            const CollisionShape &shape = side == 0 ? pair.a : pair.b;
            if (shape.shape().type != ShapeType::Cylinder) continue;
            const Vector3 axis = (side == 0 ? pair.poseA : pair.poseB).linear().col(2);
            const Vector3 outward = side == 0 ? direction : Vector3(-direction);
            const real along = axis.dot(outward);
            const Vector3 cap = along >= 0 ? axis : Vector3(-axis);
            const Vector3 radial = outward - along * axis;
            consider(side == 0 ? cap : Vector3(-cap), 0, false);
            if (radial.norm() < kPointTolerance) continue;
            consider(side == 0 ? radial.normalized() : Vector3(-radial.normalized()), 0, false);
            const Vector3 tangent = axis.cross(radial);
            const SupportFeature &other = side == 0 ? fb : fa;
            const int edges = other.count >= 3 ? other.count : other.count - 1;
            for (int e = 0; e < edges && edges <= SupportFeature::kMaxPoints; ++e) {
                const Vector3 axisOfEdge =
                    tangent.cross(other.points[e + 1 < other.count ? e + 1 : 0] - other.points[e]);
                const real length = axisOfEdge.norm();
                if (length < kPointTolerance * kPointTolerance) continue;
                consider(axisOfEdge.dot(direction) >= 0 ? Vector3(axisOfEdge / length) : Vector3(-axisOfEdge / length), 0,
                         false);
            }
        }
    };
    probe(start);
    // MPR's normal can be far off, even backwards (a small hull resting on a large box got
    // the box's side or bottom face, 1.1 m or 2.3 m deep instead of 0.4 m), and the
    // features along it then suggest nothing better. Every face axis of a box or hull is
    // a separating-axis candidate too; when one wins, its features are probed as well.
    const Vector3 before = best;
    for (int side = 0; side < 2; ++side) {
        const CollisionShape &shape = side == 0 ? pair.a : pair.b;
        const Matrix3 rotation = (side == 0 ? pair.poseA : pair.poseB).linear();
        const real sign = side == 0 ? 1 : -1;
        if (shape.shape().type == ShapeType::Box) {
            for (int k = 0; k < 3; ++k) {
                consider(sign * rotation.col(k), kFacePreference, false);
                consider(-sign * rotation.col(k), kFacePreference, false);
            }
        } else if (shape.shape().type == ShapeType::Convex) {
            for (const Vector3 &normal : shape.faceNormals()) consider(sign * (rotation * normal), kFacePreference, false);
        }
    }
    if (best != before) probe(best);
    // Against a triangle, the shape's face that lies on it may not be the one FCL's
    // normal points at: look along the triangle's normal too.
    if (rule.oneSided && start != rule.front) probe(rule.front);
    // A cylinder's rim point moves with the direction: look again from the new best.
    const bool cylinder = pair.a.shape().type == ShapeType::Cylinder || pair.b.shape().type == ShapeType::Cylinder;
    for (int again = 0; again < 2 && cylinder && best != featureDirection && !bestFlat; ++again) probe(best);

    if (refine && !bestFlat) {
        // The overlap has a local minimum at every face of A - B; FCL's normal may lie
        // in the basin of a lower one than the best candidate's, so descend from both.
        Vector3 other = start;
        real otherOverlap = pair.overlap(start);
        best = refineNormal(pair, rule, best, bestOverlap);
        if (start != best) {
            other = refineNormal(pair, rule, other, otherOverlap);
            if (otherOverlap < bestOverlap) best = other, bestOverlap = otherOverlap;
        }
    }
    if (best != featureDirection) {
        pair.a.supportingFeature(pair.poseA, best, pair.triangleA, fa);
        pair.b.supportingFeature(pair.poseB, -best, pair.triangleB, fb);
    }
    overlap = bestOverlap;
    return best;
}

// Whether FCL's libccd solver has an exact routine for the pair; the others go through
// MPR, whose normal is only a starting point.
bool exactInFcl(ShapeType a, ShapeType b) {
    if (a == ShapeType::Sphere) std::swap(a, b);
    if (b == ShapeType::Sphere) return a != ShapeType::Convex;
    return a == ShapeType::Box && b == ShapeType::Box;
}

// One contact reported by FCL, oriented from A to B.
struct RawContact {
    Vector3 normal;
    real depth;
    int triangleA;
    int triangleB;
};

struct MeshContact {
    Vector3 normal;
    real depth;
    int triangleA;
    int triangleB;
    bool face;
    bool kept;
};

int meshContacts(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                 real speculative, const RawContact *raw, int rawCount, std::vector<Manifold> &out) {
    // The mesh whose triangles claim vertices: B when it is a mesh, else A.
    const bool meshIsB = b.shape().type == ShapeType::Mesh;
    const CollisionShape &mesh = meshIsB ? b : a;
    const Matrix4 &meshPose = meshIsB ? poseB : poseA;
    const int triangles = static_cast<int>(mesh.faces().size());
    // FCL's normals against triangles, even its exact sphere-triangle ones, describe
    // the triangle alone; refinement finds each triangle's own best normal.
    const bool refine = true;

    MeshContact contacts[kMaxFclContacts];
    int count = 0;
    for (int i = 0; i < rawCount; ++i) {
        const int triangle = meshIsB ? raw[i].triangleB : raw[i].triangleA;
        if (triangle < 0 || triangle >= triangles) continue;
        const Pair pair{a, poseA, raw[i].triangleA, b, poseB, raw[i].triangleB, speculative};
        const Vector3 triangleNormal = meshPose.linear() * mesh.faceNormals()[triangle];
        NormalRule rule;
        rule.oneSided = true;
        rule.front = meshIsB ? Vector3(-triangleNormal) : triangleNormal;
        MeshContact &c = contacts[count];
        SupportFeature fa, fb;
        c.normal = chooseNormal(pair, raw[i].normal, rule, refine, fa, fb, c.depth);
        if (!(c.depth > -speculative)) continue;
        c.triangleA = raw[i].triangleA;
        c.triangleB = raw[i].triangleB;
        c.face = c.normal.dot(rule.front) > kFaceCosine;
        c.kept = true;
        ++count;
    }

    // Face contacts first, then the rest deepest first, as Jolt orders them.
    std::sort(contacts, contacts + count, [](const MeshContact &x, const MeshContact &y) {
        return x.face != y.face ? x.face : x.depth > y.depth;
    });
    int claimed[3 * kMaxFclContacts];
    int claimedCount = 0;
    auto isClaimed = [&](int vertex) { return std::find(claimed, claimed + claimedCount, vertex) != claimed + claimedCount; };
    for (int i = 0; i < count; ++i) {
        MeshContact &c = contacts[i];
        const std::vector<int> &t = mesh.faces()[meshIsB ? c.triangleB : c.triangleA];
        if (!c.face) {
            // The triangle's feature touching the other shape: its vertices furthest
            // towards that shape.
            const Vector3 towards = meshPose.linear().transpose() * (meshIsB ? Vector3(-c.normal) : c.normal);
            real top = -1e300;
            for (int k = 0; k < 3; ++k) top = std::max(top, mesh.vertices()[t[k]].dot(towards));
            bool covered = true;
            for (int k = 0; k < 3; ++k)
                if (mesh.vertices()[t[k]].dot(towards) > top - kPointTolerance && !isClaimed(t[k])) covered = false;
            if (covered) {
                c.kept = false;
                continue;
            }
        }
        for (int k = 0; k < 3; ++k)
            if (!isClaimed(t[k])) claimed[claimedCount++] = t[k];
    }

    // One manifold per normal: the clipped points of all its triangles, reduced once so
    // that the points where triangles split a face do not crowd out its corners.
    int appended = 0;
    for (int i = 0; i < count; ++i) {
        if (!contacts[i].kept) continue;
        const Vector3 normal = contacts[i].normal;
        PointSet points;
        for (int j = i; j < count; ++j) {
            MeshContact &c = contacts[j];
            if (!c.kept || c.normal.dot(normal) < kMergeCosine) continue;
            c.kept = false;
            if (points.count + kMaxClipped > kMaxMerged) {
                // Rarely many triangles: keep the best four so far and go on.
                Manifold partial;
                reduce(points.points, points.count, normal, partial);
                points.count = 0;
                for (int k = 0; k < partial.count; ++k)
                    points.add(partial.points[k].pointA, partial.points[k].pointB, partial.points[k].depth);
            }
            // Clipped along the manifold's normal, so that every point's depth is
            // measured along the normal the manifold reports.
            const Pair pair{a, poseA, c.triangleA, b, poseB, c.triangleB, speculative};
            SupportFeature fa, fb;
            a.supportingFeature(poseA, normal, c.triangleA, fa);
            b.supportingFeature(poseB, -normal, c.triangleB, fb);
            clipFeatures(pair, normal, fa, fb, points);
        }
        appended += appendReduced(points, normal, out);
    }
    return appended;
}

// The pairs with a test of their own, which FCL would only have told touch: the
// manifolds they append are the ones the FCL path builds (the same normal, by least
// overlap, and the same clipping). Returns the number appended, or -1 for a pair that
// needs FCL.
int nativeContact(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                  real speculative, std::vector<Manifold> &out) {
    const ShapeType typeA = a.shape().type;
    const ShapeType typeB = b.shape().type;
    const Pair pair{a, poseA, -1, b, poseB, -1, speculative};
    if (typeA == ShapeType::Plane || typeB == ShapeType::Plane) {
        // A solid shape's support point is exact: it touches the half-space when that
        // point lies on or below the surface (as in FCL). A mesh needs FCL's triangles.
        const bool planeIsA = typeA == ShapeType::Plane;
        const CollisionShape &plane = planeIsA ? a : b;
        const Matrix4 &planePose = planeIsA ? poseA : poseB;
        const CollisionShape &other = planeIsA ? b : a;
        if (other.shape().type == ShapeType::Mesh) return -1;
        const Vector3 up = planePose.linear() * plane.planeNormal();
        const real level = up.dot(planePose.translation()) + plane.planeOffset();
        const Vector3 deepest = other.supportPoint(planeIsA ? poseB : poseA, -up, -1);
        if (!(level - deepest.dot(up) >= 0)) return 0;
        return planeContact(pair, planeIsA, out);
    }
    if (typeA == ShapeType::Box && typeB == ShapeType::Box) {
        Vector3 normal;
        real overlap = 0;
        if (!boxBoxAxis(a.shape().halfExtents, poseA, b.shape().halfExtents, poseB, normal, overlap)) return 0;
        SupportFeature fa, fb;
        a.supportingFeature(poseA, normal, -1, fa);
        b.supportingFeature(poseB, -normal, -1, fb);
        PointSet points;
        clipFeatures(pair, normal, fa, fb, points);
        return appendReduced(points, normal, out);
    }
    if (typeA == ShapeType::Sphere || typeB == ShapeType::Sphere) {
        const bool sphereIsA = typeA == ShapeType::Sphere;
        const CollisionShape &sphere = sphereIsA ? a : b;
        const CollisionShape &other = sphereIsA ? b : a;
        const Vector3 centre = (sphereIsA ? poseA : poseB).translation();
        const Matrix4 &otherPose = sphereIsA ? poseB : poseA;
        Manifold manifold;
        bool hit = false;
        if (other.shape().type == ShapeType::Sphere)
            hit = sphereSphere(sphere.shape().radius, centre, other.shape().radius, otherPose.translation(), manifold);
        else if (other.shape().type == ShapeType::Box)
            hit = sphereBox(sphere.shape().radius, centre, other.shape().halfExtents, otherPose, manifold);
        else
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
    return -1;
}

}  // namespace

void contactOrder(const Vector3 *pointB, const real *depth, int count, const Vector3 &normal, int *order) {
    // The last of `count` points goes last whether spreadOrder would choose it or not (it
    // is the only one left, and unchosen points follow the chosen ones): choosing one
    // point fewer gives the same order and skips the costliest search.
    int chosen[4];
    const auto pointOf = [&](int i) -> const Vector3 & { return pointB[i]; };
    const auto depthOf = [&](int i) { return depth[i]; };
    // A face's four corners, the common case, with the loops unrolled.
    const int found = count == 4 ? spreadOrder(std::integral_constant<int, 4>(), 3, normal, pointOf, depthOf, chosen)
                                 : spreadOrder(count, count - 1, normal, pointOf, depthOf, chosen);
    unsigned taken = 0;
    for (int k = 0; k < found; ++k) taken |= 1u << chosen[k];
    int next = 0;  // the first point not chosen and not yet listed
    for (int k = 0; k < count; ++k) {
        if (k < found) {
            order[k] = chosen[k];
            continue;
        }
        while (taken >> next & 1u) ++next;
        order[k] = next++;
    }
}

int collide(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
            const NarrowphaseSettings &settings, std::vector<Manifold> &out) {
    const ShapeType typeA = a.shape().type;
    const ShapeType typeB = b.shape().type;
    if (typeA == ShapeType::Plane && typeB == ShapeType::Plane) return 0;
    if (!settings.forceFcl) {
        const int appended = nativeContact(a, poseA, b, poseB, settings.speculativeDistance, out);
        if (appended >= 0) return appended;
    }
    const bool withMesh = typeA == ShapeType::Mesh || typeB == ShapeType::Mesh;

    static const fcl::CollisionRequestd shapeRequest = makeRequest(4);
    static const fcl::CollisionRequestd meshRequest = makeRequest(kMaxFclContacts);
    // Reused so that its contact vector keeps its capacity between calls.
    static thread_local fcl::CollisionResultd result;
    result.clear();
    collideShapes(a.geometry().get(), poseA, b.geometry().get(), poseB, withMesh ? meshRequest : shapeRequest,
                  result);

    RawContact raw[kMaxFclContacts];
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
    if (rawCount == 0) return 0;

    if (typeA == ShapeType::Plane || typeB == ShapeType::Plane) {
        const Pair pair{a, poseA, raw[0].triangleA, b, poseB, raw[0].triangleB, settings.speculativeDistance};
        return planeContact(pair, typeA == ShapeType::Plane, out);
    }
    if (withMesh) return meshContacts(a, poseA, b, poseB, settings.speculativeDistance, raw, rawCount, out);

    // Convex pairs touch along one normal; FCL's extra box-box points are rebuilt by
    // clipping from its deepest contact.
    int deepest = 0;
    for (int i = 1; i < rawCount; ++i)
        if (raw[i].depth > raw[deepest].depth) deepest = i;
    const Pair pair{a, poseA, -1, b, poseB, -1, settings.speculativeDistance};
    SupportFeature fa, fb;
    real overlap = 0;
    const Vector3 normal =
        chooseNormal(pair, raw[deepest].normal, NormalRule(), !exactInFcl(typeA, typeB), fa, fb, overlap);
    PointSet points;
    clipFeatures(pair, normal, fa, fb, points);
    return appendReduced(points, normal, out);
}

}  // namespace cyclone::detail
