// Which edges and vertices of a mesh are real corners (collision/mesh_features.h).
#include <gtest/gtest.h>

#include <cmath>

#include "collision/mesh_features.h"
#include "collision_test_support.h"

namespace cyclone::test {
namespace {

using detail::activeEdgeBit;
using detail::activeVertexBit;

// The features of a compiled mesh.
std::vector<std::uint8_t> featuresOf(const std::vector<Vector3> &vertices, const std::vector<std::array<int, 3>> &triangles) {
    const auto mesh = detail::compileShape(Shape::mesh(vertices, triangles));
    std::vector<std::uint8_t> features;
    for (int t = 0; t < mesh->triangleCount(); ++t) features.push_back(mesh->activeFeatures(t));
    return features;
}

TEST(MeshFeatures, FlatSquareHasAnInnerDiagonal) {
    // Two triangles (0, 2, 1) and (0, 3, 2) share the diagonal 0-2: flat, so inactive.
    // Every other edge is on the border (one triangle): active, and so are all four
    // corners, each the end of a border edge. Triangle (0, 2, 1): edge 0 runs 0-2.
    // Triangle (0, 3, 2): edge 2 runs 2-0.
    const auto f = featuresOf({Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 0, 1), Vector3(0, 0, 1)},
                              {{0, 2, 1}, {0, 3, 2}});
    const std::uint8_t allVertices = activeVertexBit(0) | activeVertexBit(1) | activeVertexBit(2);
    EXPECT_EQ(f[0], activeEdgeBit(1) | activeEdgeBit(2) | allVertices);
    EXPECT_EQ(f[1], activeEdgeBit(0) | activeEdgeBit(1) | allVertices);
}

TEST(MeshFeatures, InnerVertexOfAFlatFanIsInactive) {
    // Four triangles around the centre 4 of a square: the spokes to 4 are shared and
    // flat (inactive), so the centre, which ends only spokes, is inactive; the rim is
    // the border. Triangle k is (k, 4, k + 1): vertex 1 of each is the centre.
    const std::vector<Vector3> v{Vector3(0, 0, 0), Vector3(0, 0, 1), Vector3(1, 0, 1), Vector3(1, 0, 0),
                                 Vector3(0.5, 0, 0.5)};
    const auto f = featuresOf(v, {{0, 4, 1}, {1, 4, 2}, {2, 4, 3}, {3, 4, 0}});
    for (int t = 0; t < 4; ++t) {
        SCOPED_TRACE(t);
        EXPECT_FALSE(f[t] & activeVertexBit(1));
        EXPECT_TRUE(f[t] & activeVertexBit(0));
        EXPECT_FALSE(f[t] & activeEdgeBit(0));  // spoke k-4
        EXPECT_FALSE(f[t] & activeEdgeBit(1));  // spoke 4-(k+1)
        EXPECT_TRUE(f[t] & activeEdgeBit(2));   // rim
    }
}

TEST(MeshFeatures, FoldIsActiveOnlyBeyondFiveDegrees) {
    // Two triangles hinged on the edge 0-1 along z, the second tilted down by `angle`:
    // their normals differ by `angle`, so the hinge is inner below 5 degrees (Jolt's
    // default threshold) and a real edge above. Triangle 0 = (0, 1, 2): edge 0 is the
    // hinge. The second is wound so that it faces the same side (runs 1-0).
    for (const auto &[degrees, active] : {std::pair{4.0, false}, std::pair{6.0, true}, std::pair{90.0, true}}) {
        SCOPED_TRACE(degrees);
        const real angle = degrees * kPi / 180;
        const std::vector<Vector3> v{Vector3(0, 0, 0), Vector3(0, 0, 1), Vector3(-1, 0, 0.5),
                                     Vector3(std::cos(angle), -std::sin(angle), 0.5)};
        const auto f = featuresOf(v, {{0, 1, 2}, {1, 0, 3}});
        EXPECT_EQ(static_cast<bool>(f[0] & activeEdgeBit(0)), active);
        EXPECT_EQ(static_cast<bool>(f[1] & activeEdgeBit(0)), active);
    }
}

}  // namespace
}  // namespace cyclone::test
