#include "collision/mesh_features.h"

#include <algorithm>

namespace cyclone::detail {
namespace {

// One side of an edge: the triangle, which of its edges, and whether that triangle runs
// along it from the lower vertex index to the higher.
struct EdgeSide {
    int low;
    int high;
    int triangle;
    int edge;
    bool ascending;
};

}  // namespace

std::vector<std::uint8_t> meshActiveFeatures(const std::vector<Vector3> &vertices,
                                             const std::vector<std::vector<int>> &faces,
                                             const std::vector<Vector3> &normals) {
    std::vector<EdgeSide> sides;
    sides.reserve(3 * faces.size());
    for (std::size_t t = 0; t < faces.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const int from = faces[t][k];
            const int to = faces[t][(k + 1) % 3];
            sides.push_back({std::min(from, to), std::max(from, to), static_cast<int>(t), k, from < to});
        }
    }
    // Sorted by edge, the sides of one edge lie together (triangle order breaks ties, so
    // the result does not depend on the sort's stability).
    std::sort(sides.begin(), sides.end(), [](const EdgeSide &x, const EdgeSide &y) {
        if (x.low != y.low) return x.low < y.low;
        if (x.high != y.high) return x.high < y.high;
        return x.triangle != y.triangle ? x.triangle < y.triangle : x.edge < y.edge;
    });

    std::vector<std::uint8_t> features(faces.size(), 0);
    std::vector<char> vertexActive(vertices.size(), 0);
    for (std::size_t first = 0; first < sides.size();) {
        std::size_t end = first + 1;
        while (end < sides.size() && sides[end].low == sides[first].low && sides[end].high == sides[first].high) ++end;
        bool active = true;
        if (end - first == 2) {
            const EdgeSide &x = sides[first];
            const EdgeSide &y = sides[first + 1];
            // Consistently wound neighbours run along their shared edge in opposite
            // directions; one that runs the same way faces the other side.
            const real sign = x.ascending != y.ascending ? 1 : -1;
            active = !(sign * normals[x.triangle].dot(normals[y.triangle]) > kInnerEdgeCosine);
        }
        for (std::size_t s = first; s < end; ++s) {
            if (!active) continue;
            features[sides[s].triangle] |= activeEdgeBit(sides[s].edge);
            vertexActive[sides[s].low] = 1;
            vertexActive[sides[s].high] = 1;
        }
        first = end;
    }
    for (std::size_t t = 0; t < faces.size(); ++t)
        for (int k = 0; k < 3; ++k)
            if (vertexActive[faces[t][k]]) features[t] |= activeVertexBit(k);
    return features;
}

}  // namespace cyclone::detail
