// A height field: a grid of samples whose cells are two triangles each, read in closed
// form from the heights alone. Nothing per triangle is stored: a triangle's normal and
// active features (mesh_features.h) are computed from the heights around it when a query
// asks, so a 1024 x 1024 field costs the 8 bytes of its heights per sample and loads in
// the time of copying them; queries visit only the cells under the box or ray they are
// given.
//
// Triangle t of cell c = i (columns - 1) + j is 2c + k: k = 0 holds samples
// (i, j), (i+1, j), (i+1, j+1), k = 1 holds (i, j), (i+1, j+1), (i, j+1); both wound
// counter-clockwise seen from above, so their normals face the side the solid is not.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <fcl/fcl.h>

#include "cyclone/world/shape.h"

namespace cyclone::detail {

/// A view of a height field's description (the shape must outlive it).
struct HeightfieldGrid {
    int rows = 0;
    int columns = 0;
    real dx = 1;
    real dz = 1;
    const real *heights = nullptr;

    explicit HeightfieldGrid(const Shape &shape)
        : rows(shape.rows), columns(shape.columns), dx(shape.spacing[0]), dz(shape.spacing[1]),
          heights(shape.heights.data()) {}

    int cellColumns() const { return columns - 1; }
    int triangleCount() const { return 2 * (rows - 1) * (columns - 1); }
    real height(int i, int j) const { return heights[static_cast<std::size_t>(i) * columns + j]; }
    Vector3 sample(int i, int j) const { return Vector3(j * dx, height(i, j), i * dz); }

    /// Triangle t's corners (shape frame) and their sample numbers i columns + j.
    void triangle(int t, Vector3 (&corners)[3], int (&ids)[3]) const {
        const int cell = t / 2;
        const int i = cell / cellColumns();
        const int j = cell % cellColumns();
        const int di[2][3] = {{0, 1, 1}, {0, 1, 0}};
        const int dj[2][3] = {{0, 0, 1}, {0, 1, 1}};
        for (int k = 0; k < 3; ++k) {
            const int a = i + di[t % 2][k];
            const int b = j + dj[t % 2][k];
            corners[k] = sample(a, b);
            ids[k] = a * columns + b;
        }
    }

    /// Triangle t's unit normal, facing up (the side away from the solid).
    Vector3 normal(int t) const {
        Vector3 c[3];
        int ids[3];
        triangle(t, c, ids);
        return (c[1] - c[0]).cross(c[2] - c[0]).normalized();
    }

    /// Triangle t's active edges and vertices (mesh_features.h): the bits
    /// meshActiveFeatures gives the same triangles as a mesh. A cell's diagonal and the
    /// edges between cells are inner where the two triangles' normals are within
    /// kInnerEdgeCosine; the field's border edges are active; a sample is active when
    /// one of the six edges that meet at it is. Reads the normals of at most the 12
    /// triangles around t's corners.
    std::uint8_t activeFeatures(int t) const;

    /// Calls visit(t) for each triangle of the cells whose column of samples meets the
    /// box [low, high] (shape frame): the cells under its x-z extent whose heights are
    /// not all above high.y or all below low.y. Stops when visit returns false.
    template <class Visit>
    void forEachTriangleIn(const Vector3 &low, const Vector3 &high, Visit visit) const {
        int i0, i1, j0, j1;
        if (!cellRange(low.z(), high.z(), dz, rows - 1, i0, i1) || !cellRange(low.x(), high.x(), dx, columns - 1, j0, j1))
            return;
        for (int i = i0; i <= i1; ++i) {
            for (int j = j0; j <= j1; ++j) {
                const real a = height(i, j), b = height(i + 1, j), c = height(i, j + 1), d = height(i + 1, j + 1);
                if (std::min(std::min(a, b), std::min(c, d)) > high.y()) continue;
                if (std::max(std::max(a, b), std::max(c, d)) < low.y()) continue;
                const int cell = i * cellColumns() + j;
                if (!visit(2 * cell) || !visit(2 * cell + 1)) return;
            }
        }
    }

    /// The cells [first, last] (of `cells`, spacing `step`) that [low, high] overlaps;
    /// false when none.
    static bool cellRange(real low, real high, real step, int cells, int &first, int &last) {
        if (!(high >= 0 && low <= step * cells)) return false;
        first = static_cast<int>(std::clamp(std::floor(low / step), real(0), real(cells - 1)));
        last = static_cast<int>(std::clamp(std::floor(high / step), real(0), real(cells - 1)));
        return true;
    }
};

/// Checks a height field's rows, columns, spacing and heights; throws InvalidArgument
/// with function "" and the field (e.g. "shape.heights[12]") as compileShape does.
void validateHeightfield(const Shape &shape);

/// A copy of a field's heights for its compiled shape. Where the system has them (Linux's
/// transparent huge pages, on request), in 2 MB pages: a 1024 x 1024 field's 8 MB
/// otherwise costs 2048 page faults, most of the time of adding it to a World.
std::vector<real> copyHeights(const std::vector<real> &heights);

/// The broadphase's geometry of a height field: a box whose local AABB is the field's
/// (x in [0, (columns-1) dx], z in [0, (rows-1) dz], y between the lowest and highest
/// sample). Only boxes are read from it: the triangles are what collide.
std::shared_ptr<fcl::CollisionGeometryd> heightfieldBounds(const HeightfieldGrid &grid);

/// The first triangle the ray from `o` along `d` (shape frame, unit) hits from above
/// within `limit`: its distance `t` and unit normal `n`, by a walk over the cells under
/// the ray (a 2D digital differential analyser) from the ray's entry into `box`, the
/// field's box (heightfieldBounds' local AABB).
bool rayHeightfield(const Vector3 &o, const Vector3 &d, const HeightfieldGrid &grid, const fcl::AABBd &box, real limit,
                    real &t, Vector3 &n);

}  // namespace cyclone::detail
