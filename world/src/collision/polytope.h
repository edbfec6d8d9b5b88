// Boxes and convex hulls as polytopes: the faces and edges a separating-axis test of two
// of them walks (polytope.cpp), so that box-hull and hull-hull pairs get their normal
// without FCL, as box-box pairs do (box_box.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cyclone/core.h"

namespace cyclone::detail {

/// An edge of a polytope: a corner on it and the two faces that meet along it, with
/// `arc` = normals[face1] x normals[face0] (unit, along the edge): on the Gauss map, the
/// pole of the arc of the edge's normals, from face0's to face1's.
struct PolytopeEdge {
    std::int16_t corner = 0;  // a hull has at most kMaxHullVertices corners, 2 x as many faces
    std::int16_t face0 = 0, face1 = 0;
    Vector3 arc = Vector3::Zero();
};

/// What a hull keeps beside its corners and face normals for the separating-axis test.
struct HullEdges {
    std::vector<real> offsets;  ///< normals[f] . x of face f's points.
    std::vector<PolytopeEdge> edges;
    Vector3 inside = Vector3::Zero();  ///< A point inside (the corners' mean).
    real innerRadius = 0;              ///< Radius of a ball about `inside` that the hull holds, m.
};

/// The edges of a hull: `faces` are corner-index loops, `normals` their outward unit
/// normals. An edge shared by two coplanar faces is left out.
HullEdges makeHullEdges(const std::vector<Vector3> &corners, const std::vector<std::vector<int>> &faces,
                        const std::vector<Vector3> &normals);

/// A convex polytope in its shape's frame, as the separating-axis test reads it: views of
/// a hull's data, or of a box's corners in a BoxCorners and the edges all boxes share.
struct Polytope {
    const Vector3 *corners = nullptr;
    std::size_t cornerCount = 0;
    const Vector3 *normals = nullptr;  ///< Outward unit normal of each face.
    const real *offsets = nullptr;
    std::size_t faceCount = 0;
    const PolytopeEdge *edges = nullptr;
    std::size_t edgeCount = 0;
    Vector3 inside = Vector3::Zero();
    real innerRadius = 0;
    bool empty() const { return cornerCount == 0; }
};

/// Room for a box's corners and face offsets, which its Polytope views.
struct BoxCorners {
    Vector3 corners[8];
    real offsets[6];
};

/// The polytope of a box of half extents `half` (its corners written to `room`).
Polytope boxPolytope(const Vector3 &half, BoxCorners &room);

/// The polytope of a hull of these corners and face normals.
Polytope hullPolytope(const std::vector<Vector3> &corners, const std::vector<Vector3> &normals, const HullEdges &edges);

class CollisionShape;

/// The polytope of a box (its corners written to `room`) or of a convex hull; empty for
/// other shapes.
Polytope polytopeOf(const CollisionShape &shape, BoxCorners &room);

/// The polytopes polytopeAxis takes: at most kMaxPolytopeEdges edges each and
/// kMaxPolytopeEdgePairs edge pairs, where its cost is measured below FCL's (30-edge rocks
/// against each other, docs/contacts_and_sleep.md); FCL tests the others.
inline constexpr std::size_t kMaxPolytopeEdges = 96;
inline constexpr std::size_t kMaxPolytopeEdgePairs = 1024;
bool separatingAxesSuit(const Polytope &a, const Polytope &b);

/// The axis of least overlap between polytope A at `poseA` and polytope B at `poseB`,
/// among A's face normals, B's and the cross products of the edge pairs that form a face
/// of the Minkowski difference, with the contract of boxBoxAxis: false when some axis
/// separates them by more than `reach`; otherwise `normal` (unit, world, A to B) and
/// `overlap` (m, >= -reach), negative for polytopes apart along it. Face axes win ties
/// within kFacePreference, B's over A's. Both must suit (separatingAxesSuit).
bool polytopeAxis(const Polytope &a, const Matrix4 &poseA, const Polytope &b, const Matrix4 &poseB,
                  Vector3 &normal, real &overlap, real reach = 0);

}  // namespace cyclone::detail
