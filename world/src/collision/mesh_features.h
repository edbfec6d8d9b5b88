// Which edges and vertices of a triangle mesh are real corners of its surface. Two
// triangles that meet at an edge almost flat (a floor split in triangles, a gently
// curved surface) make an inner edge: a contact there would push a shape along the
// edge's normal, a bump the surface does not have, so such contacts take the
// triangle's face normal instead (see mesh_contacts.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/core.h"

namespace cyclone::detail {

/// Bit k of a triangle's features: its edge from vertex k to vertex k + 1 (mod 3) is active.
inline constexpr std::uint8_t activeEdgeBit(int k) { return static_cast<std::uint8_t>(1u << k); }
/// Bit 3 + k of a triangle's features: its vertex k is active.
inline constexpr std::uint8_t activeVertexBit(int k) { return static_cast<std::uint8_t>(1u << (3 + k)); }

/// Neighbouring triangles whose normals are within this angle of each other meet at an
/// inactive (inner) edge: cos(5 deg), as Jolt's default active-edge threshold.
inline constexpr real kInnerEdgeCosine = 0.9961946980917455;

/// The active features of each triangle of a mesh (`faces` index `vertices`, `normals`
/// their unit normals): an edge is active unless exactly two triangles share it and
/// their normals, taken with a consistent winding, are within kInnerEdgeCosine; a vertex
/// is active when any edge that ends at it is.
std::vector<std::uint8_t> meshActiveFeatures(const std::vector<Vector3> &vertices,
                                             const std::vector<std::vector<int>> &faces,
                                             const std::vector<Vector3> &normals);

}  // namespace cyclone::detail
