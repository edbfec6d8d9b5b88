// Manifold clipping, as in Jolt's ManifoldBetweenTwoFaces: the incident feature is
// clipped against the side planes of the reference face extruded along the normal, each
// clipped point's depth is measured along the normal to the reference plane, points
// within the speculative distance are kept and reduced to four well-spread ones. A plane
// is an unbounded reference face with an exact normal and is never clipped against.
#include <algorithm>
#include <cmath>

#include "collision/contact_building.h"
#include "collision/round_side.h"

namespace cyclone::detail {
namespace {

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
// outward normal plane), if within `keep`; beyond `speculative` as a landing point.
void addClipped(const Vector3 &q, const Vector3 &n, const Vector3 &origin, const Vector3 &plane, bool referenceOnA,
                real speculative, real keep, PointSet &out) {
    const real along = n.dot(plane);
    if (std::abs(along) < kPointTolerance) return;
    if (referenceOnA) {
        // q is on B; A's face is at q + t n.
        const real t = (origin - q).dot(plane) / along;
        if (t > -keep) out.add(q + t * n, q, t, !(t > -speculative));
    } else {
        // q is on A; B's face is at q - t n.
        const real t = (q - origin).dot(plane) / along;
        if (t > -keep) out.add(q, q - t * n, t, !(t > -speculative));
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
    addClipped(q0 + (lo - s0) / ds * v, n, p0, plane, true, pair.speculative, pair.speculative, out);
    if (hi - lo > kPointTolerance)
        addClipped(q0 + (hi - s0) / ds * v, n, p0, plane, true, pair.speculative, pair.speculative, out);
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

}  // namespace

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

int appendReduced(const PointSet &points, const Vector3 &n, std::vector<Manifold> &out) {
    if (points.count == 0) return 0;
    Manifold manifold;
    const int landingCount = static_cast<int>(std::count_if(
        points.points, points.points + points.count, [](const PointSet::Point &p) { return p.landing; }));
    if (landingCount == 0 || landingCount == points.count) {
        reduce(points.points, points.count, n, manifold);
    } else {
        // The touching points are reduced on their own; the landing ones fill what is left.
        PointSet::Point touching[kMaxMerged], landing[kMaxMerged];
        int touchingCount = 0, landed = 0;
        for (int i = 0; i < points.count; ++i)
            (points.points[i].landing ? landing[landed++] : touching[touchingCount++]) = points.points[i];
        reduce(touching, touchingCount, n, manifold);
        std::sort(landing, landing + landingCount,
                  [](const PointSet::Point &x, const PointSet::Point &y) { return x.depth > y.depth; });
        for (int i = 0; i < landingCount && manifold.count < Manifold::kMaxPoints; ++i) {
            ContactPoint &p = manifold.points[manifold.count++];
            p.pointA = landing[i].pointA;
            p.pointB = landing[i].pointB;
            p.depth = landing[i].depth;
        }
    }
    out.push_back(manifold);
    return 1;
}

bool overlapAlong(const SupportFeature &fa, const SupportFeature &fb, const Vector3 &n) {
    const bool referenceOnA = fa.count >= 3;
    Vector3 buffer[kMaxClipped];
    Vector3 scratch[kMaxClipped];
    int count = 0;
    clipAgainstFace(referenceOnA ? fa : fb, referenceOnA ? n : Vector3(-n), true, referenceOnA ? fb : fa, buffer,
                    scratch, count);
    return count > 0;
}

namespace {

// Calls visit(q) for each corner of `shape` at `pose` (world) that is not already a point
// of `feature` (its supporting feature): a box's eight, a hull's vertices, and the ends of
// the side line of a capsule or cylinder that reaches farthest along `direction` (world,
// unit). Spheres, planes and meshes have none.
template <class Visit>
void forEachOtherCorner(const CollisionShape &shape, const Matrix4 &pose, const Vector3 &direction,
                        const SupportFeature &feature, const Visit &visitCorner) {
    const auto visit = [&](const Vector3 &q) {
        for (int i = 0; i < feature.count; ++i)
            if ((feature.points[i] - q).squaredNorm() < kPointTolerance * kPointTolerance) return;
        visitCorner(q);
    };
    switch (shape.shape().type) {
        case ShapeType::Box: {
            const Vector3 &h = shape.shape().halfExtents;
            for (int corner = 0; corner < 8; ++corner)
                visit(pose * Vector3(corner & 1 ? h.x() : -h.x(), corner & 2 ? h.y() : -h.y(),
                                     corner & 4 ? h.z() : -h.z()));
            break;
        }
        case ShapeType::Convex:
            for (const Vector3 &v : shape.vertices()) visit(pose * v);
            break;
        case ShapeType::Capsule:
        case ShapeType::Cylinder: {
            Vector3 end0, end1;
            if (farthestSideLine(shape, pose, direction, end0, end1)) visit(end0), visit(end1);
            break;
        }
        default: break;
    }
}

// A body tilted onto a vertex or an edge over a face turns about it as it lands, and its
// far side comes down within the step faster than the body fell (see planeContact): each
// corner of the incident shape over the reference face (`reference`, A's when
// `referenceOnA`, outward normal `plane`), `incident` being its supporting feature, is
// a point when within the pair's landingKeep().
void addFarCorners(const Pair &pair, const Vector3 &n, const SupportFeature &reference, const Vector3 &plane,
                   bool referenceOnA, const SupportFeature &incident, PointSet &out) {
    const CollisionShape &shape = referenceOnA ? pair.b : pair.a;
    const Vector3 w = referenceOnA ? n : Vector3(-n);
    forEachOtherCorner(shape, referenceOnA ? pair.poseB : pair.poseA, -w, incident, [&](const Vector3 &q) {
        SupportFeature corner;
        corner.points[0] = q;
        corner.count = 1;
        Vector3 buffer[kMaxClipped];
        Vector3 scratch[kMaxClipped];
        int count = 0;
        clipAgainstFace(reference, w, true, corner, buffer, scratch, count);
        if (count > 0)
            addClipped(q, n, reference.points[0], plane, referenceOnA, pair.speculative, pair.landingKeep(), out);
    });
}

}  // namespace

void clipFeatures(const Pair &pair, const Vector3 &n, const SupportFeature &fa, const SupportFeature &fb,
                  PointSet &out, bool pointIfApart) {
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
        // Within landingKeep(): a face landing tilted turns about its near edge and its far
        // edge comes down faster than the body fell (planeContact).
        for (int i = 0; i < count; ++i)
            addClipped(clipped[i], n, reference.points[0], plane, referenceOnA, pair.speculative, pair.landingKeep(),
                       out);
    }
    if (out.count == before && pointIfApart) pointContact(pair, n, false, out);
    // A vertex or an edge of a moving body over a face: the far corners too.
    if ((fa.count >= 3) != (fb.count >= 3) && pair.reach > 0) {
        const bool faceOnA = fa.count >= 3;
        const SupportFeature &face = faceOnA ? fa : fb;
        if ((faceOnA ? pair.a : pair.b).shape().type != ShapeType::Plane)
            addFarCorners(pair, n, face, polygonNormal(face), faceOnA, faceOnA ? fb : fa, out);
    }
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
        const bool landing = !(t > -pair.speculative);
        if (planeIsA)
            points.add(q + t * up, q, t, landing);
        else
            points.add(q, q + t * up, t, landing);
    };
    // A body tilted onto a vertex, an edge or a face's edge (a box's, a hull's, a capsule's
    // end, a rim) turns about it as it lands, and its far side comes down within the step.
    // Stopping one end of a falling rod (v) with an impulse J = m v / 4 turns it so that
    // the other end falls at 1.5 v, so points are kept within the speculative distance
    // plus the pair's reach (gaps the contact lets close and no more; a plane cannot stop
    // a body passing by), and a vertex or an edge of a moving body has the shape's other
    // corners as points too. At rest (no reach) nothing changes.
    const real keep = pair.landingKeep();
    real deepest = -keep;
    for (int i = 0; i < feature.count; ++i) {
        const Vector3 &q = feature.points[i];
        const real t = level - q.dot(up);
        if (!(t > -keep)) continue;
        add(q, t);
        deepest = std::max(deepest, t);
    }
    if (feature.count <= 2 && triangle < 0 && pair.reach > 0)
        forEachOtherCorner(other, otherPose, -up, feature, [&](const Vector3 &q) {
            const real t = level - q.dot(up);
            if (t > -keep) add(q, t);
        });
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

}  // namespace cyclone::detail
