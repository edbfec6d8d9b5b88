// Qhull computes the hull with its default facet merging (no 'Qt'), so coplanar
// triangles come back as one polygon facet; we only re-order each facet's vertices
// into a counter-clockwise loop, which Qhull does not guarantee for merged facets.
#include "collision/convex_hull.h"

#include <libqhull_r/qhull_ra.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace cyclone::detail {
namespace {

// Points closer than this fraction of the cloud's extent to the plane of three of them
// are coplanar: such a hull has no volume worth simulating.
constexpr real kFlatTolerance = 1e-9;

bool spansVolume(const std::vector<Vector3> &points) {
    if (points.size() < 4) return false;
    const Vector3 &p0 = points[0];
    size_t i1 = 0;
    real best = 0;
    for (size_t i = 1; i < points.size(); ++i) {
        const real d = (points[i] - p0).squaredNorm();
        if (d > best) best = d, i1 = i;
    }
    const real extent = std::sqrt(best);
    if (!(extent > 0)) return false;
    const Vector3 axis = (points[i1] - p0) / extent;
    size_t i2 = 0;
    best = 0;
    for (size_t i = 1; i < points.size(); ++i) {
        const real d = (points[i] - p0).cross(axis).squaredNorm();
        if (d > best) best = d, i2 = i;
    }
    if (!(std::sqrt(best) > kFlatTolerance * extent)) return false;
    const Vector3 normal = axis.cross(points[i2] - p0).normalized();
    best = 0;
    for (size_t i = 1; i < points.size(); ++i) best = std::max(best, std::abs((points[i] - p0).dot(normal)));
    return best > kFlatTolerance * extent;
}

// Qhull reports precision warnings and errors on a stream; a library must not write to
// the program's stderr (the caller turns a failure into an InvalidArgument), so they go
// to /dev/null, opened once.
FILE *qhullMessages() {
    static FILE *sink = std::fopen("/dev/null", "w");
    return sink != nullptr ? sink : stderr;
}

}  // namespace

bool computeConvexHull(const std::vector<Vector3> &points, ConvexHull &hull) {
    hull = ConvexHull();
    if (!spansVolume(points)) return false;

    std::vector<coordT> coordinates(points.size() * 3);
    for (size_t i = 0; i < points.size(); ++i)
        for (int k = 0; k < 3; ++k) coordinates[3 * i + k] = points[i][k];

    qhT qhull;
    qhT *qh = &qhull;
    qh_zero(qh, qhullMessages());
    char options[] = "qhull Qx";
    const int exitCode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False, options,
                                      nullptr, qhullMessages());
    bool ok = exitCode == 0;
    if (ok) {
        std::vector<int> hullIndex(points.size(), -1);
        facetT *facet;
        vertexT *vertex, **vertexp;
        FORALLfacets {
            const Vector3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
            std::vector<int> face;
            Vector3 centre = Vector3::Zero();
            FOREACHvertex_(facet->vertices) {
                const int input = qh_pointid(qh, vertex->point);
                if (hullIndex[input] < 0) {
                    hullIndex[input] = static_cast<int>(hull.vertices.size());
                    hull.vertices.push_back(points[input]);
                }
                face.push_back(hullIndex[input]);
                centre += points[input];
            }
            centre /= static_cast<real>(face.size());
            const Vector3 u = normal.unitOrthogonal();
            const Vector3 v = normal.cross(u);
            std::vector<std::pair<real, int>> byAngle;
            for (int index : face) {
                const Vector3 r = hull.vertices[index] - centre;
                byAngle.emplace_back(std::atan2(r.dot(v), r.dot(u)), index);
            }
            std::sort(byAngle.begin(), byAngle.end());
            for (size_t k = 0; k < face.size(); ++k) face[k] = byAngle[k].second;
            hull.faces.push_back(std::move(face));
            hull.normals.push_back(normal.normalized());
        }
        ok = hull.faces.size() >= 4;
    }
    qh_freeqhull(qh, !qh_ALL);
    int currentLong = 0, totalLong = 0;
    qh_memfreeshort(qh, &currentLong, &totalLong);
    if (!ok) hull = ConvexHull();
    return ok;
}

std::vector<Vector3> spreadSubset(const std::vector<Vector3> &points, int count, real &cover) {
    cover = 0;
    if (points.empty() || count <= 0) return {};
    if (points.size() <= static_cast<size_t>(count)) return points;
    Vector3 centroid = Vector3::Zero();
    for (const Vector3 &p : points) centroid += p;
    centroid /= static_cast<real>(points.size());
    // nearest[i]: squared distance from point i to the nearest chosen point so far (to the
    // centroid before the first is chosen, so that the first is the farthest from it).
    std::vector<real> nearest(points.size());
    for (size_t i = 0; i < points.size(); ++i) nearest[i] = (points[i] - centroid).squaredNorm();
    std::vector<Vector3> chosen;
    chosen.reserve(static_cast<size_t>(count));
    for (;;) {
        size_t far = 0;
        for (size_t i = 1; i < points.size(); ++i)
            if (nearest[i] > nearest[far]) far = i;
        if (static_cast<int>(chosen.size()) == count) {
            cover = std::sqrt(nearest[far]);
            return chosen;
        }
        const Vector3 next = points[far];
        const bool first = chosen.empty();
        chosen.push_back(next);
        for (size_t i = 0; i < points.size(); ++i) {
            const real d = (points[i] - next).squaredNorm();
            nearest[i] = first ? d : std::min(nearest[i], d);
        }
    }
}

void polyhedronMassProperties(const std::vector<Vector3> &vertices, const std::vector<std::vector<int>> &faces,
                              real &volume, Matrix3 &unitInertia, Vector3 &centroid) {
    // Each fan triangle (a, b, c) with the origin spans a signed tetrahedron whose
    // second moment about the origin is V/20 (aa' + bb' + cc' + ss'), s = a + b + c.
    volume = 0;
    Matrix3 secondMoment = Matrix3::Zero();
    Vector3 firstMoment = Vector3::Zero();  // each tetrahedron's centroid is s / 4
    for (const std::vector<int> &face : faces) {
        const Vector3 &a = vertices[face[0]];
        for (size_t k = 1; k + 1 < face.size(); ++k) {
            const Vector3 &b = vertices[face[k]];
            const Vector3 &c = vertices[face[k + 1]];
            const real v = a.dot(b.cross(c)) / 6;
            const Vector3 s = a + b + c;
            volume += v;
            firstMoment += v / 4 * s;
            secondMoment += v / 20 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
        }
    }
    secondMoment /= volume;
    centroid = firstMoment / volume;
    unitInertia = secondMoment.trace() * Matrix3::Identity() - secondMoment;
}

}  // namespace cyclone::detail
