// Box against box: the exact separating-axis test that chooses a contact normal without
// FCL. The manifold is then clipped from the boxes' supporting faces by the narrowphase.
#pragma once

#include "cyclone/core.h"

namespace cyclone::detail {

// Edges within this sine of parallel give no axis of their own (their cross product is
// a face axis, or noise).
inline constexpr real kParallelEdgeSine = 1e-6;

/// The axis of least overlap between box A (half extents `halfA` at `poseA`) and box B
/// (`halfB` at `poseB`), among the 15 candidate axes: A's 3 face normals, B's 3 and the
/// 9 cross products of their edges. Returns false when some axis separates them by more
/// than `reach` (overlap < -reach; touching is a contact, as in FCL). Otherwise `normal` is
/// unit, world space, from A to B, and `overlap` (m, >= -reach) is how far B must move along
/// it to clear A; negative for boxes apart along it (a speculative contact), where the axis
/// is the one that separates them most. Face axes win exact
/// ties, B's over A's; an edge axis wins only when its overlap is clearly smaller
/// (box_box.cpp says by how much), so that the normal of a resting or sliding contact
/// does not flicker between nearly equal axes.
bool boxBoxAxis(const Vector3 &halfA, const Matrix4 &poseA, const Vector3 &halfB, const Matrix4 &poseB,
                Vector3 &normal, real &overlap, real reach = 0);

}  // namespace cyclone::detail
