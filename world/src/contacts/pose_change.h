// How far a pose moved: the test behind every "hardly moved, keep what was computed"
// shortcut of the step (manifold reuse, Jacobian reuse).
#pragma once

#include <cmath>

#include "cyclone/core.h"

namespace cyclone::detail {

/// Body B's pose seen from body A: its position in A's frame and its orientation relative
/// to A's.
struct RelativePose {
    Vector3 position = Vector3::Zero();
    Quaternion orientation = Quaternion::Identity();
};

/// Whether a pose moved less than `tolerance`: shift + |angle| radius < tolerance, with
/// the angle Eigen's AngleAxis gives for `turn`, 2 atan2(|v|, |w|) of its vector and
/// scalar parts. As atan x <= x, that angle is at most 2 |v|_1 / |w| (the factor
/// 1 + 1e-9 covers rounding, a few ulps, by far), and rounding is monotonic: when that
/// bound passes, or the shift alone fails, the answer is known without the atan2 a
/// settled scene would otherwise pay for every pair every step.
inline bool movedLess(real shift, const Quaternion &turn, real radius, real tolerance) {
    if (!(shift < tolerance)) return false;
    const real w = std::abs(turn.w());
    // The bound times |w| (> 0), so that no division waits on the quaternion product.
    if (w > 0 && 2 * turn.vec().lpNorm<1>() * (1 + 1e-9) * radius < (tolerance - shift) * w) return true;
    return shift + std::abs(Eigen::AngleAxis<real>(turn).angle()) * radius < tolerance;
}

}  // namespace cyclone::detail
