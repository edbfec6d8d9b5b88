#include "collision/heightfield.h"

#include <charconv>
#include <limits>
#include <string>

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

// The unit normals of the two triangles of each cell of row i: 2 j + k for cell (i, j).
void rowNormals(const HeightfieldGrid &grid, int i, std::vector<Vector3> &out) {
    out.resize(2 * static_cast<std::size_t>(grid.cellColumns()));
    for (int j = 0; j < grid.cellColumns(); ++j) {
        const Vector3 a = grid.sample(i, j), b = grid.sample(i + 1, j), c = grid.sample(i + 1, j + 1),
                      d = grid.sample(i, j + 1);
        out[2 * static_cast<std::size_t>(j)] = (b - a).cross(c - a).normalized();
        out[2 * static_cast<std::size_t>(j) + 1] = (c - a).cross(d - a).normalized();
    }
}

}  // namespace

std::vector<std::uint8_t> heightfieldActiveFeatures(const HeightfieldGrid &grid) {
    const int cellRows = grid.rows - 1;
    const int cellColumns = grid.cellColumns();
    std::vector<std::uint8_t> features(static_cast<std::size_t>(grid.triangleCount()), 0);
    std::vector<char> vertexActive(static_cast<std::size_t>(grid.rows) * grid.columns, 0);
    // Rows i - 1, i and i + 1 of triangle normals, each computed once.
    std::vector<Vector3> above, here, below;
    rowNormals(grid, 0, here);
    for (int i = 0; i < cellRows; ++i) {
        if (i + 1 < cellRows) rowNormals(grid, i + 1, below);
        for (int j = 0; j < cellColumns; ++j) {
            const auto at = [](const std::vector<Vector3> &row, int cell, int k) {
                return row[2 * static_cast<std::size_t>(cell) + static_cast<std::size_t>(k)];
            };
            const Vector3 &lower = at(here, j, 0);
            const Vector3 &upper = at(here, j, 1);
            // Edge e of each triangle, and the triangle across it (none at the border).
            const bool diagonal = !flatEdge(lower, upper);
            const bool active[2][3] = {
                {j == 0 || !flatEdge(lower, at(here, j - 1, 1)), i + 1 == cellRows || !flatEdge(lower, at(below, j, 1)),
                 diagonal},
                {diagonal, j + 1 == cellColumns || !flatEdge(upper, at(here, j + 1, 0)),
                 i == 0 || !flatEdge(upper, at(above, j, 0))}};
            // Sample numbers of each triangle's corners (heightfield.h).
            const int s = i * grid.columns + j;
            const int ids[2][3] = {{s, s + grid.columns, s + grid.columns + 1}, {s, s + grid.columns + 1, s + 1}};
            const auto t = static_cast<std::size_t>(2 * (i * cellColumns + j));
            for (int k = 0; k < 2; ++k)
                for (int e = 0; e < 3; ++e) {
                    if (!active[k][e]) continue;
                    features[t + static_cast<std::size_t>(k)] |= activeEdgeBit(e);
                    vertexActive[static_cast<std::size_t>(ids[k][e])] = 1;
                    vertexActive[static_cast<std::size_t>(ids[k][(e + 1) % 3])] = 1;
                }
        }
        std::swap(above, here);
        std::swap(here, below);
    }
    for (int i = 0; i < cellRows; ++i)
        for (int j = 0; j < cellColumns; ++j) {
            const int s = i * grid.columns + j;
            const int ids[2][3] = {{s, s + grid.columns, s + grid.columns + 1}, {s, s + grid.columns + 1, s + 1}};
            const auto t = static_cast<std::size_t>(2 * (i * cellColumns + j));
            for (int k = 0; k < 2; ++k)
                for (int v = 0; v < 3; ++v)
                    if (vertexActive[static_cast<std::size_t>(ids[k][v])])
                        features[t + static_cast<std::size_t>(k)] |= activeVertexBit(v);
        }
    return features;
}

std::shared_ptr<fcl::CollisionGeometryd> heightfieldBounds(const HeightfieldGrid &grid) {
    const auto count = static_cast<std::size_t>(grid.rows) * grid.columns;
    const auto [low, high] = std::minmax_element(grid.heights, grid.heights + count);
    const fcl::AABBd bounds(Vector3(0, *low, 0), Vector3(grid.cellColumns() * grid.dx, *high, (grid.rows - 1) * grid.dz));
    auto geometry = std::make_shared<HeightfieldBox>(bounds);
    geometry->computeLocalAABB();
    return geometry;
}

bool rayHeightfield(const Vector3 &o, const Vector3 &d, const HeightfieldGrid &grid, real limit, real &t,
                    Vector3 &n) {
    const auto count = static_cast<std::size_t>(grid.rows) * grid.columns;
    const auto [lowest, highest] = std::minmax_element(grid.heights, grid.heights + count);
    const Vector3 low(0, *lowest, 0);
    const Vector3 high(grid.cellColumns() * grid.dx, *highest, (grid.rows - 1) * grid.dz);
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
