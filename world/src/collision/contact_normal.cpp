// Choosing a contact's normal. FCL (libccd) returns one contact for most pairs, and its
// normal comes from MPR for curved shapes and convex polytopes: close, but tilted enough
// to rock a box resting on a face, and for shapes against triangles often far off. So
// FCL's normal is only one candidate, with the normals of the two supporting faces, the
// cross products of their edges and, for cylinders, the cap and side normals; the
// candidate along which the shapes' projections overlap least wins, since that overlap
// bounds the penetration from above (separating axes). Ties go to a face, so resting
// contacts get the exact face normal. Where FCL used MPR, the winner is then refined:
// the pair moved apart along it no longer touches, and GJK's nearest points give the
// surfaces' common normal (for a cylinder with a sphere, capsule or cylinder, Newton's
// method on their closed-form support functions does it). A cylinder with a cylinder or
// a capsule also has the line between their cores as a candidate.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "collision/contact_building.h"
#include "collision/cylinder_pairs.h"
#include "collision/gjk.h"
#include "collision/round_normal.h"

namespace cyclone::detail {
namespace {

// The radius a sphere or capsule adds around its core (its centre, its axis segment); 0
// for other shapes, which are their own core.
real coreRadius(const CollisionShape &shape) {
    const ShapeType type = shape.shape().type;
    return type == ShapeType::Sphere || type == ShapeType::Capsule ? shape.shape().radius : 0;
}

// The support point of the shape's core along d (supportPoint less the radius along d).
Vector3 coreSupport(const CollisionShape &shape, const Matrix4 &pose, const Vector3 &d, int triangle) {
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

// Improves the normal n (unit, A to B; overlap f along it) the way a separating pair
// finds its normal: A moved back along n by f plus a margin no longer touches B, and
// GJK's nearest points of the two then lie where the surfaces meet, so the line between
// them is the surfaces' common normal there. For curved surfaces less deep than their
// radius of curvature each round brings n closer to the true normal; flat faces give
// theirs at once. A new normal is taken only if it lowers the overlap. A sphere's or a
// capsule's nearest points lie a radius out from its core's along the same line, so GJK
// runs on the cores: on a point or a segment it ends in a few iterations, where on the
// round surface it creeps towards the answer (25-50 iterations in a mixed pile).
//
// `simplex` holds vertices in the unshifted cores' difference (any such point, moved by
// a round's shift, lies in that round's set): a round starts from the vertices the last
// search ended with and leaves its own there. A round so started takes a few iterations
// where a fresh search takes 20-30.
Vector3 refineNormal(const Pair &pair, const NormalRule &rule, Vector3 n, real &f, GjkSimplex &simplex) {
    const real radii = coreRadius(pair.a) + coreRadius(pair.b);
    for (int round = 0; round < kRefineRounds && f > 0; ++round) {
        const Vector3 shift = (f + kRefineMargin) * n;
        auto support = [&](const Vector3 &d) {
            return Vector3(coreSupport(pair.a, pair.poseA, d, pair.triangleA) - shift -
                           coreSupport(pair.b, pair.poseB, -d, pair.triangleB));
        };
        for (int k = 0; k < simplex.count; ++k) simplex.points[k] -= shift;
        Vector3 closest;
        if (!closestToOrigin(support, -n, closest, &simplex)) break;
        for (int k = 0; k < simplex.count; ++k) simplex.points[k] += shift;
        const real distance = closest.norm();
        if (!(distance - radii > kPointTolerance * kRefineMargin)) break;
        // At a ridge of A - B (a cylinder's rim, a box's edge) the nearest points may
        // overshoot: then try halfway back towards n.
        Vector3 candidate = -closest / distance;
        if ((candidate - n).squaredNorm() < kPointTolerance * kPointTolerance) break;
        real value = 0;
        bool improved = false;
        for (int halving = 0; halving <= kRefineHalvings && !improved; ++halving) {
            if (halving > 0) candidate = (candidate + n).normalized();
            if (!rule.allows(candidate) || pair.overlapExceeds(candidate, f - kPointTolerance * kPointTolerance)) continue;
            value = pair.overlap(candidate);
            improved = value < f - kPointTolerance * kPointTolerance;
        }
        if (!improved) break;
        n = candidate;
        f = value;
    }
    return n;
}

// Descends from n (overlap f) to the nearest normal of less overlap: by Newton's method
// on the support functions for round pairs with a cylinder (round_normal.cpp), by GJK
// for the others and where Newton's method does not settle.
Vector3 descend(const Pair &pair, const NormalRule &rule, Vector3 n, real &f, GjkSimplex &simplex) {
    if (f > 0 && !rule.oneSided && roundNormalPair(pair.a.shape().type, pair.b.shape().type) &&
        roundNormal(pair, n, f))
        return n;
    return refineNormal(pair, rule, n, f, simplex);
}

// The search for the normal of least overlap: candidates are offered one at a time and
// the best is kept (a face wins a tie within kFacePreference). The supporting features
// along the last direction probed are left in fa and fb.
class NormalSearch {
public:
    NormalSearch(const Pair &pair, const NormalRule &rule, const Vector3 &start, SupportFeature &fa,
                 SupportFeature &fb)
        : best(start), bestOverlap(pair.overlap(start)), pair_(pair), rule_(rule), fa_(fa), fb_(fb) {}

    Vector3 best;
    real bestOverlap;
    bool bestFlat = false;  ///< The best is a face lying flat on the other feature: no refining.
    Vector3 featureDirection = Vector3::Zero();  ///< The direction fa and fb were taken along.

    void consider(const Vector3 &candidate, real preference, bool flat) {
        if (!rule_.allows(candidate) || pair_.overlapExceeds(candidate, bestOverlap + preference)) return;
        const real o = pair_.overlap(candidate);
        if (o <= bestOverlap + preference) {
            best = candidate;
            bestOverlap = o;
            bestFlat = flat;
        }
    }

    // The candidates that the features along `direction` suggest. `direction` may be
    // `best` itself, which then moves as better candidates are found.
    void probe(const Vector3 &direction) {
        pair_.a.supportingFeature(pair_.poseA, direction, pair_.triangleA, fa_);
        pair_.b.supportingFeature(pair_.poseB, -direction, pair_.triangleB, fb_);
        featureDirection = direction;
        const Vector3 normalA = fa_.count >= 3 ? polygonNormal(fa_) : Vector3::Zero();
        const Vector3 normalB = fb_.count >= 3 ? Vector3(-polygonNormal(fb_)) : Vector3::Zero();
        const bool flat = lieFlat(normalA, normalB);
        if (normalA.dot(direction) > 0) consider(normalA, kFacePreference, flat);
        if (normalB.dot(direction) > 0) consider(normalB, kFacePreference, flat);
        if (flat) return;
        considerEdgePairs(direction);
        considerCylinderRims(direction);
    }

    // MPR's normal can be far off, even backwards (a small hull resting on a large box got
    // the box's side or bottom face, 1.1 m or 2.3 m deep instead of 0.4 m), and the
    // features along it then suggest nothing better: every face axis of a box or hull is
    // a candidate too.
    void considerFaceAxes() {
        for (int side = 0; side < 2; ++side) {
            const CollisionShape &shape = side == 0 ? pair_.a : pair_.b;
            const Matrix3 rotation = (side == 0 ? pair_.poseA : pair_.poseB).linear();
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
    }

private:
    // Two faces, or a segment (a capsule's or cylinder's side) and a face, parallel and
    // overlapping seen along the normal lie flat on each other: the face normal needs no
    // refining.
    bool lieFlat(const Vector3 &normalA, const Vector3 &normalB) const {
        bool flat = normalA.dot(normalB) > kFlatCosine;
        if ((fa_.count == 2 && fb_.count >= 3) || (fb_.count == 2 && fa_.count >= 3)) {
            // A curved side touches a face along its support line along the face's
            // normal, which may not be the line along the probed direction.
            const Vector3 &face = fa_.count >= 3 ? normalA : normalB;
            SupportFeature sa, sb;
            pair_.a.supportingFeature(pair_.poseA, face, pair_.triangleA, sa);
            pair_.b.supportingFeature(pair_.poseB, -face, pair_.triangleB, sb);
            const SupportFeature &line = sa.count == 2 ? sa : sb;
            flat = line.count == 2 && (sa.count >= 3 || sb.count >= 3) &&
                   std::abs((line.points[1] - line.points[0]).normalized().dot(face)) < kFlatSine &&
                   overlapAlong(sa, sb, face);
        }
        return flat;
    }

    // Edge against edge: the separating-axis candidates of the two features' edges.
    void considerEdgePairs(const Vector3 &direction) {
        const int edgesA = fa_.count >= 3 ? fa_.count : fa_.count - 1;
        const int edgesB = fb_.count >= 3 ? fb_.count : fb_.count - 1;
        if (edgesA <= 0 || edgesB <= 0 || edgesA * edgesB > kMaxEdgePairs) return;
        for (int i = 0; i < edgesA; ++i) {
            const Vector3 ea = fa_.points[i + 1 < fa_.count ? i + 1 : 0] - fa_.points[i];
            for (int j = 0; j < edgesB; ++j) {
                const Vector3 axis = ea.cross(fb_.points[j + 1 < fb_.count ? j + 1 : 0] - fb_.points[j]);
                const real length = axis.norm();
                if (length < kPointTolerance * kPointTolerance) continue;
                consider(axis.dot(direction) >= 0 ? Vector3(axis / length) : Vector3(-axis / length), 0, false);
            }
        }
    }

    // A cylinder's rim is a ridge where refinement stalls: its cap and side normals, the
    // faces either side of it, are candidates too, and so are the rim's tangent crossed
    // with the other feature's edges.
    void considerCylinderRims(const Vector3 &direction) {
        for (int side = 0; side < 2; ++side) {
            const CollisionShape &shape = side == 0 ? pair_.a : pair_.b;
            if (shape.shape().type != ShapeType::Cylinder) continue;
            const Vector3 axis = (side == 0 ? pair_.poseA : pair_.poseB).linear().col(2);
            const Vector3 outward = side == 0 ? direction : Vector3(-direction);
            const real along = axis.dot(outward);
            const Vector3 cap = along >= 0 ? axis : Vector3(-axis);
            const Vector3 radial = outward - along * axis;
            consider(side == 0 ? cap : Vector3(-cap), 0, false);
            if (radial.norm() < kPointTolerance) continue;
            consider(side == 0 ? radial.normalized() : Vector3(-radial.normalized()), 0, false);
            const Vector3 tangent = axis.cross(radial);
            const SupportFeature &other = side == 0 ? fb_ : fa_;
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
    }

    const Pair &pair_;
    const NormalRule &rule_;
    SupportFeature &fa_;
    SupportFeature &fb_;
};

}  // namespace

Vector3 chooseNormal(const Pair &pair, const Vector3 &fclNormal, const NormalRule &rule, bool refine,
                     SupportFeature &fa, SupportFeature &fb, real &overlap) {
    // FCL's normal of a shape against a triangle can point anywhere, even backwards;
    // the triangle's own normal is the start then.
    const Vector3 start = rule.allows(fclNormal) ? fclNormal : rule.front;
    NormalSearch search(pair, rule, start, fa, fb);
    if (rule.oneSided) search.consider(rule.front, kFacePreference, false);

    // 1. The features along the start, and every face axis; a winning face axis's
    //    features are probed as well.
    search.probe(start);
    const Vector3 before = search.best;
    search.considerFaceAxes();
    if (search.best != before) search.probe(search.best);
    // 2. Against a triangle, the shape's face that lies on it may not be the one FCL's
    //    normal points at: look along the triangle's normal too.
    if (rule.oneSided && start != rule.front) search.probe(rule.front);
    // 3. A cylinder's rim point moves with the direction: look again from the new best
    //    (not for round pairs, whose Newton descent follows the rim itself).
    const bool cylinder = (pair.a.shape().type == ShapeType::Cylinder || pair.b.shape().type == ShapeType::Cylinder) &&
                          !(refine && roundNormalPair(pair.a.shape().type, pair.b.shape().type));
    for (int again = 0; again < 2 && cylinder && search.best != search.featureDirection && !search.bestFlat; ++again)
        search.probe(search.best);

    // 4. Refinement. The overlap has a local minimum at every face of A - B; FCL's normal
    //    may lie in the basin of a lower one than the best candidate's, so descend from both.
    //    (Rarely lower by more than 0.1 mm, but without it mixed1000 piles reached 24 mm
    //    deep and 2 of 33 never slept: docs/experiments.md.)
    Vector3 best = search.best;
    real bestOverlap = search.bestOverlap;
    if (refine && !search.bestFlat) {
        GjkSimplex simplex;
        best = descend(pair, rule, best, bestOverlap, simplex);
        if (start != best) {
            real otherOverlap = pair.overlap(start);
            const Vector3 other = descend(pair, rule, start, otherOverlap, simplex);
            if (otherOverlap < bestOverlap) best = other, bestOverlap = otherOverlap;
        }
    }
    // 5. A cylinder against a cylinder or a capsule: MPR's start can leave every candidate
    //    far off (a capsule under a cylinder's rim got a normal pointing down through it,
    //    1 m deep), so the line between the cores' closest points is one more candidate,
    //    taken as it is.
    if (cylinderRoundPair(pair.a.shape().type, pair.b.shape().type)) {
        const Vector3 cores = coreLine(axisCore(pair.a, pair.poseA), axisCore(pair.b, pair.poseB));
        const real coresOverlap = cores != Vector3::Zero() && rule.allows(cores) ? pair.overlap(cores) : bestOverlap;
        if (coresOverlap < bestOverlap) best = cores, bestOverlap = coresOverlap;
    }
    // 6. The features along the normal chosen, for clipping. They are those along it bit
    //    for bit (a zero's sign may change an angle), so that the normal alone gives them
    //    again (NormalMemo).
    if (std::memcmp(best.data(), search.featureDirection.data(), sizeof(Vector3)) != 0) {
        pair.a.supportingFeature(pair.poseA, best, pair.triangleA, fa);
        pair.b.supportingFeature(pair.poseB, -best, pair.triangleB, fb);
    }
    overlap = bestOverlap;
    return best;
}

}  // namespace cyclone::detail
