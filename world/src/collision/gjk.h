// GJK distance from the origin to a convex set given by its support mapping
// (Gilbert, Johnson and Keerthi), with the closest-point-on-simplex routines of
// Ericson's Real-Time Collision Detection, 5.1.5 and 5.1.6.
#pragma once

#include <cmath>

#include "cyclone/core.h"

namespace cyclone::detail {

namespace gjk {

// Closest point to the origin of the simplex s[0..count); keeps in s only the vertices
// whose hull holds that point. Returns false when the origin is inside a tetrahedron.
inline bool closestOnTriangle(Vector3 *s, int &count, Vector3 &closest) {
    const Vector3 a = s[0], b = s[1], c = s[2];
    const Vector3 ab = b - a, ac = c - a;
    const real d1 = -ab.dot(a), d2 = -ac.dot(a);
    if (d1 <= 0 && d2 <= 0) {
        s[0] = a, count = 1, closest = a;
        return true;
    }
    const real d3 = -ab.dot(b), d4 = -ac.dot(b);
    if (d3 >= 0 && d4 <= d3) {
        s[0] = b, count = 1, closest = b;
        return true;
    }
    const real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        closest = a + d1 / (d1 - d3) * ab;
        s[0] = a, s[1] = b, count = 2;
        return true;
    }
    const real d5 = -ab.dot(c), d6 = -ac.dot(c);
    if (d6 >= 0 && d5 <= d6) {
        s[0] = c, count = 1, closest = c;
        return true;
    }
    const real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        closest = a + d2 / (d2 - d6) * ac;
        s[0] = a, s[1] = c, count = 2;
        return true;
    }
    const real va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        closest = b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
        s[0] = b, s[1] = c, count = 2;
        return true;
    }
    const real denominator = va + vb + vc;
    closest = a + (vb / denominator) * ab + (vc / denominator) * ac;
    count = 3;
    return true;
}

inline bool closestOnSimplex(Vector3 *s, int &count, Vector3 &closest) {
    if (count == 1) {
        closest = s[0];
        return true;
    }
    if (count == 2) {
        const Vector3 ab = s[1] - s[0];
        const real t = -s[0].dot(ab);
        if (t <= 0) {
            count = 1;
            closest = s[0];
        } else if (t >= ab.squaredNorm()) {
            s[0] = s[1];
            count = 1;
            closest = s[0];
        } else {
            closest = s[0] + t / ab.squaredNorm() * ab;
        }
        return true;
    }
    if (count == 3) return closestOnTriangle(s, count, closest);

    // Tetrahedron: the nearest of the faces whose plane separates the origin from the
    // opposite vertex; none means the origin is inside.
    static constexpr int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
    real best = -1;
    Vector3 bestSimplex[3];
    int bestCount = 0;
    for (const auto &f : faces) {
        const Vector3 &a = s[f[0]], &b = s[f[1]], &c = s[f[2]], &d = s[f[3]];
        const Vector3 normal = (b - a).cross(c - a);
        const real origin = -a.dot(normal);
        const real opposite = (d - a).dot(normal);
        // A nearly flat tetrahedron has no inside worth trusting: every face is a candidate.
        const bool flat = std::abs(opposite) <= 1e-9 * normal.norm() * (d - a).norm();
        if (origin * opposite > 0 && !flat) continue;
        Vector3 triangle[3] = {a, b, c};
        int n = 3;
        Vector3 p;
        closestOnTriangle(triangle, n, p);
        const real distance = p.squaredNorm();
        if (best < 0 || distance < best) {
            best = distance;
            closest = p;
            bestCount = n;
            for (int k = 0; k < n; ++k) bestSimplex[k] = triangle[k];
        }
    }
    if (best < 0) return false;
    count = bestCount;
    for (int k = 0; k < count; ++k) s[k] = bestSimplex[k];
    return true;
}

}  // namespace gjk

/// The vertices GJK ended with (at most three: the face, edge or vertex nearest the
/// origin), to start a later search of a nearby set from.
struct GjkSimplex {
    Vector3 points[4];
    int count = 0;
};

/// The point of a convex set nearest the origin. `support(d)` gives the set's point
/// furthest along the unit direction d; `start` is any direction. Returns false when the
/// origin is inside the set (or on its boundary, within the tolerance). With `warm`, the
/// search starts from its points when it has any (they must lie in the set), instead of
/// from the support along `start`, and `warm` gets the vertices it ended with.
template <typename Support>
bool closestToOrigin(const Support &support, const Vector3 &start, Vector3 &closest, GjkSimplex *warm = nullptr) {
    constexpr int kMaxIterations = 64;
    // Relative gap between the distance |v| and its lower bound v.w / |v| at which v is
    // the answer; curved sets approach it only asymptotically.
    constexpr real kRelativeTolerance = 1e-10;
    // v always lies in the simplex's hull, so each step can only bring it nearer.
    Vector3 simplex[4];
    int count = 1;
    Vector3 v;
    if (warm && warm->count > 0) {
        count = warm->count;
        for (int k = 0; k < count; ++k) simplex[k] = warm->points[k];
        gjk::closestOnSimplex(simplex, count, v);
    } else {
        v = support(start);
        simplex[0] = v;
    }
    const auto keep = [&] {
        if (!warm) return;
        warm->count = count;
        for (int k = 0; k < count; ++k) warm->points[k] = simplex[k];
    };
    for (int i = 0; i < kMaxIterations; ++i) {
        const real vv = v.squaredNorm();
        if (vv < 1e-24) {
            if (warm) warm->count = 0;
            return false;
        }
        const Vector3 w = support(-v / std::sqrt(vv));
        if (vv - v.dot(w) <= kRelativeTolerance * vv) break;
        bool known = false;
        for (int k = 0; k < count; ++k) known = known || (simplex[k] - w).squaredNorm() < 1e-24;
        if (known) break;
        simplex[count++] = w;
        Vector3 next;
        if (!gjk::closestOnSimplex(simplex, count, next)) {
            if (warm) warm->count = 0;
            return false;
        }
        // Stop when a step no longer brings v nearer.
        if (next.squaredNorm() >= vv * (1 - kRelativeTolerance)) {
            if (next.squaredNorm() < vv) v = next;
            break;
        }
        v = next;
    }
    keep();
    closest = v;
    return true;
}

/// Whether the convex set given by `support` lies farther than `gap` (m, >= 0) from the
/// origin, shown by a direction along which all of it does: GJK's lower bound v.w / |v|
/// passes `gap`. False, unsure, when its upper bound |v| comes within `gap` first, when the
/// origin is inside, or after kMaxIterations; `start` is any direction.
template <typename Support>
bool fartherThan(const Support &support, const Vector3 &start, real gap) {
    // Sets apart by more than a millimetre show it within a few iterations; the pairs
    // still unsure after these are near enough to be worth the full test.
    constexpr int kMaxIterations = 12;
    Vector3 simplex[4];
    int count = 1;
    Vector3 v = support(start);
    simplex[0] = v;
    for (int i = 0; i < kMaxIterations; ++i) {
        const real vv = v.squaredNorm();
        if (!(vv > gap * gap)) return false;
        const Vector3 direction = -v / std::sqrt(vv);
        const Vector3 w = support(direction);
        if (-direction.dot(w) > gap) return true;
        simplex[count++] = w;
        if (!gjk::closestOnSimplex(simplex, count, v)) return false;
    }
    return false;
}

}  // namespace cyclone::detail
