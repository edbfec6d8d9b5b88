#include "collision/heightfield.h"

#include <charconv>
#include <cstdint>
#include <limits>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "collision/mesh_features.h"
#include "cyclone/world/error.h"

namespace cyclone::detail {
namespace {

std::string heightText(real value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

[[noreturn]] void refuseHeightfield(const std::string &field, const std::string &problem) {
    throw InvalidArgument("", field, problem);
}

// The broadphase's box of a height field (compare CompoundBounds in collision_shape.cpp):
// FCL recomputes a geometry's local AABB whenever a collision object is made of it.
class HeightfieldBox : public fcl::Boxd {
public:
    explicit HeightfieldBox(const fcl::AABBd &bounds) : fcl::Boxd(bounds.max_ - bounds.min_), bounds_(bounds) {}
    void computeLocalAABB() override {
        aabb_local = bounds_;
        aabb_center = bounds_.center();
        aabb_radius = 0.5 * (bounds_.max_ - bounds_.min_).norm();
    }

private:
    fcl::AABBd bounds_;
};

// Whether two triangles' unit normals meet almost flat (an inner edge). All of a field's
// triangles face up, so they are wound consistently.
bool flatEdge(const Vector3 &a, const Vector3 &b) { return a.dot(b) > kInnerEdgeCosine; }

// The ray from o along d against the triangle c, from its front (counter-clockwise) side
// only: the distance within [0, limit] (Moller-Trumbore).
bool rayFrontTriangle(const Vector3 &o, const Vector3 &d, const Vector3 (&c)[3], real limit, real &t) {
    const Vector3 e1 = c[1] - c[0];
    const Vector3 e2 = c[2] - c[0];
    const Vector3 p = d.cross(e2);
    const real det = e1.dot(p);
    // det = -d.(e1 x e2): positive when the ray comes from the front.
    if (!(det > 0)) return false;
    const Vector3 s = o - c[0];
    const real u = s.dot(p) / det;
    if (u < 0 || u > 1) return false;
    const Vector3 q = s.cross(e1);
    const real v = d.dot(q) / det;
    if (v < 0 || u + v > 1) return false;
    const real along = e2.dot(q) / det;
    if (!(along >= 0 && along <= limit)) return false;
    t = along;
    return true;
}

}  // namespace

void validateHeightfield(const Shape &shape) {
    if (shape.rows < 2) refuseHeightfield("shape.rows", "must be >= 2, got " + std::to_string(shape.rows));
    if (shape.columns < 2) refuseHeightfield("shape.columns", "must be >= 2, got " + std::to_string(shape.columns));
    for (int k = 0; k < 2; ++k) {
        const real s = shape.spacing[k];
        if (!(std::isfinite(s) && s > 0))
            refuseHeightfield("shape.spacing[" + std::to_string(k) + "]", "must be finite and > 0, got " + heightText(s));
    }
    const long long expected = static_cast<long long>(shape.rows) * shape.columns;
    // Triangle numbers are ints: 2 (rows - 1) (columns - 1) must fit.
    if (expected > std::numeric_limits<int>::max() / 2)
        refuseHeightfield("shape.rows", "times columns must be at most " + std::to_string(std::numeric_limits<int>::max() / 2) +
                                 ", got " + std::to_string(shape.rows) + " x " + std::to_string(shape.columns));
    if (static_cast<long long>(shape.heights.size()) != expected)
        refuseHeightfield("shape.heights", "must hold rows x columns = " + std::to_string(expected) + " heights, got " +
                                    std::to_string(shape.heights.size()));
    for (std::size_t k = 0; k < shape.heights.size(); ++k)
        if (!std::isfinite(shape.heights[k]))
            refuseHeightfield("shape.heights[" + std::to_string(k) + "]", "must be finite, got " + heightText(shape.heights[k]));
}

namespace {

// The edges of a field, each named by its first sample (a, b): the row edge runs to
// (a, b + 1), the column edge to (a + 1, b), the diagonal to (a + 1, b + 1). An edge is
// inner when both triangles beside it exist and their normals meet almost flat.
struct FieldEdges {
    const HeightfieldGrid &grid;

    int cellRows() const { return grid.rows - 1; }
    // Triangle k of cell (i, j)'s unit normal (heightfield.h numbering).
    Vector3 normal(int i, int j, int k) const { return grid.normal(2 * (i * grid.cellColumns() + j) + k); }

    // Between cell (a - 1, b)'s triangle 0 and cell (a, b)'s triangle 1.
    bool rowActive(int a, int b) const {
        return a == 0 || a == cellRows() || !flatEdge(normal(a - 1, b, 0), normal(a, b, 1));
    }
    // Between cell (a, b)'s triangle 0 and cell (a, b - 1)'s triangle 1.
    bool columnActive(int a, int b) const {
        return b == 0 || b == grid.cellColumns() || !flatEdge(normal(a, b, 0), normal(a, b - 1, 1));
    }
    bool diagonalActive(int a, int b) const { return !flatEdge(normal(a, b, 0), normal(a, b, 1)); }

    // Whether one of the edges that meet at sample (a, b) is active.
    bool sampleActive(int a, int b) const {
        const bool right = b < grid.cellColumns(), left = b > 0, down = a < cellRows(), up = a > 0;
        return (right && rowActive(a, b)) || (left && rowActive(a, b - 1)) || (down && columnActive(a, b)) ||
               (up && columnActive(a - 1, b)) || (down && right && diagonalActive(a, b)) ||
               (up && left && diagonalActive(a - 1, b - 1));
    }
};

}  // namespace

std::uint8_t HeightfieldGrid::activeFeatures(int t) const {
    const FieldEdges edges{*this};
    const int cell = t / 2;
    const int i = cell / cellColumns();
    const int j = cell % cellColumns();
    // Edge e of each triangle runs from its corner e to corner e + 1 (heightfield.h).
    const bool active[2][3] = {{edges.columnActive(i, j), edges.rowActive(i + 1, j), edges.diagonalActive(i, j)},
                               {edges.diagonalActive(i, j), edges.columnActive(i, j + 1), edges.rowActive(i, j)}};
    const int di[2][3] = {{0, 1, 1}, {0, 1, 0}};
    const int dj[2][3] = {{0, 0, 1}, {0, 1, 1}};
    std::uint8_t features = 0;
    for (int e = 0; e < 3; ++e) {
        if (active[t % 2][e]) features |= activeEdgeBit(e);
        if (edges.sampleActive(i + di[t % 2][e], j + dj[t % 2][e])) features |= activeVertexBit(e);
    }
    return features;
}

std::vector<real> copyHeights(const std::vector<real> &heights) {
    std::vector<real> copy;
    copy.reserve(heights.size());
#if defined(MADV_HUGEPAGE)
    // The buffer is fresh and untouched: advise its 2 MB-aligned part before writing it.
    constexpr std::uintptr_t huge = std::uintptr_t(1) << 21;
    const auto begin = reinterpret_cast<std::uintptr_t>(copy.data());
    const std::uintptr_t first = (begin + huge - 1) & ~(huge - 1);
    const std::uintptr_t last = (begin + heights.size() * sizeof(real)) & ~(huge - 1);
    if (last > first) madvise(reinterpret_cast<void *>(first), last - first, MADV_HUGEPAGE);  // a hint: may fail
#endif
    copy.assign(heights.begin(), heights.end());
    return copy;
}

std::shared_ptr<fcl::CollisionGeometryd> heightfieldBounds(const HeightfieldGrid &grid) {
    const auto count = static_cast<std::size_t>(grid.rows) * grid.columns;
    const auto [low, high] = std::minmax_element(grid.heights, grid.heights + count);
    const fcl::AABBd bounds(Vector3(0, *low, 0), Vector3(grid.cellColumns() * grid.dx, *high, (grid.rows - 1) * grid.dz));
    auto geometry = std::make_shared<HeightfieldBox>(bounds);
    geometry->computeLocalAABB();
    return geometry;
}

bool rayHeightfield(const Vector3 &o, const Vector3 &d, const HeightfieldGrid &grid, const fcl::AABBd &box, real limit,
                    real &t, Vector3 &n) {
    const Vector3 &low = box.min_;
    const Vector3 &high = box.max_;
    // The stretch of the ray inside the field's box.
    real enter = 0, leave = limit;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0) {
            if (o[k] < low[k] || o[k] > high[k]) return false;
            continue;
        }
        real t1 = (low[k] - o[k]) / d[k], t2 = (high[k] - o[k]) / d[k];
        if (t1 > t2) std::swap(t1, t2);
        enter = std::max(enter, t1);
        leave = std::min(leave, t2);
    }
    if (!(enter <= leave)) return false;
    // Walk the cells under the ray from `enter` (x along columns j, z along rows i).
    const Vector3 start = o + enter * d;
    int j = static_cast<int>(std::clamp(std::floor(start.x() / grid.dx), real(0), real(grid.cellColumns() - 1)));
    int i = static_cast<int>(std::clamp(std::floor(start.z() / grid.dz), real(0), real(grid.rows - 2)));
    const int stepJ = d.x() > 0 ? 1 : -1, stepI = d.z() > 0 ? 1 : -1;
    const real inf = std::numeric_limits<real>::infinity();
    // The ray's distance to the cell's far side along x and z, and per cell.
    const auto boundary = [&](int cell, int step, real spacing, real origin, real direction) {
        if (direction == 0) return inf;
        return ((cell + (step > 0 ? 1 : 0)) * spacing - origin) / direction;
    };
    real nextJ = boundary(j, stepJ, grid.dx, o.x(), d.x());
    real nextI = boundary(i, stepI, grid.dz, o.z(), d.z());
    const real deltaJ = d.x() == 0 ? inf : grid.dx / std::abs(d.x());
    const real deltaI = d.z() == 0 ? inf : grid.dz / std::abs(d.z());
    for (int visited = 0; visited < grid.rows + grid.columns; ++visited) {
        bool found = false;
        for (int k = 0; k < 2; ++k) {
            const int triangle = 2 * (i * grid.cellColumns() + j) + k;
            Vector3 corners[3];
            int ids[3];
            grid.triangle(triangle, corners, ids);
            real along;
            if (!rayFrontTriangle(o, d, corners, found ? t : limit, along)) continue;
            t = along;
            n = grid.normal(triangle);
            found = true;
        }
        if (found) return true;
        // The next cell: across whichever side the ray meets first.
        if (nextJ < nextI) {
            if (nextJ > leave) return false;
            j += stepJ, nextJ += deltaJ;
            if (j < 0 || j >= grid.cellColumns()) return false;
        } else {
            if (nextI > leave) return false;
            i += stepI, nextI += deltaI;
            if (i < 0 || i >= grid.rows - 1) return false;
        }
    }
    return false;
}

}  // namespace cyclone::detail
