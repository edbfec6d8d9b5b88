#include "world/mass_range.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <sstream>
#include <string>

#include "cyclone/world/settings.h"
#include "world/validation.h"

namespace cyclone::detail {
namespace {

// An inertia tensor as the refusals print it: its rows, three digits each.
std::string showInertia(const Matrix3 &inertia) {
    std::ostringstream shown;
    shown.precision(3);
    shown << "[" << inertia.row(0) << "; " << inertia.row(1) << "; " << inertia.row(2) << "]";
    return shown.str();
}

}  // namespace

void requireSolvableMass(const char *function, real mass, const Matrix3 &inertia, real boundingRadius) {
    requirePositive(function, "mass", mass);
    if (!(mass >= kMinMass && mass <= kMaxMass))
        refuse(function, "mass", "must be in [1e-100, 1e100] kg (the solver's range), got " + show(mass));
    if (!inertia.allFinite() || !(boundingRadius > 0)) return;  // the tensor's own check refuses it
    // The moments are scaled before the eigen-solve so that tensors near the ends of the
    // double range are not squared out of it.
    const real scale = inertia.cwiseAbs().maxCoeff();
    if (!(scale > 0)) return;
    const Eigen::SelfAdjointEigenSolver<Matrix3> eigen(inertia / scale, Eigen::EigenvaluesOnly);
    const Vector3 moments = eigen.eigenvalues();
    if (!(moments.minCoeff() > 0)) return;  // not positive definite: refused as such
    // Divided step by step: R^2 alone may leave the double range for extreme shapes.
    const real lowest = moments.minCoeff() * scale / boundingRadius / boundingRadius;
    const real highest = moments.maxCoeff() * scale / boundingRadius / boundingRadius;
    if (lowest >= kMinMass && highest <= kMaxMass) return;
    refuse(function, "inertia",
           "gives principal moments over the squared bounding radius (R = " + show(boundingRadius) + " m) from " +
               show(lowest) + " to " + show(highest) + " kg; the solver's range is [1e-100, 1e100] kg, got " +
               showInertia(inertia));
}

void requireInertiaNearShape(const char *function, const Matrix3 &inertia, const Matrix3 &shapeInertia) {
    // The smallest ratio of the two moments over all axes a: the smallest eigenvalue of
    // the pencil inertia x = lambda shapeInertia x. Both are scaled by the shape's largest
    // moment (the mass range keeps it a normal double), which leaves lambda as it is.
    const real scale = shapeInertia.cwiseAbs().maxCoeff();
    if (!(scale > 0) || !inertia.allFinite()) return;
    const Matrix3 reference = shapeInertia / scale;
    if (!(Eigen::LLT<Matrix3>(reference).info() == Eigen::Success)) return;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix3> pencil(inertia / scale, reference, Eigen::EigenvaluesOnly);
    if (pencil.info() != Eigen::Success) return;
    const real lowest = pencil.eigenvalues().minCoeff();
    if (lowest >= kMinInertiaFraction || !(lowest > 0)) return;  // not positive definite: refused as such
    refuse(function, "inertia",
           "has a moment of " + show(lowest) +
               " times the shape's at uniform density about some axis; the solver holds contacts from " +
               show(kMinInertiaFraction) + " times it up, got " + showInertia(inertia));
}

Matrix3 withMomentFloor(const Matrix3 &inertia) {
    const real scale = inertia.cwiseAbs().maxCoeff();
    if (!(scale > 0) || !inertia.allFinite()) return inertia;  // refused by the mass checks
    const Eigen::SelfAdjointEigenSolver<Matrix3> eigen(inertia / scale);
    if (eigen.info() != Eigen::Success) return inertia;
    const Vector3 moments = eigen.eigenvalues();
    const real floor = kMinMomentRatio * moments.maxCoeff();
    if (!(moments.minCoeff() < floor)) return inertia;
    const Matrix3 &axes = eigen.eigenvectors();
    const Matrix3 raised = axes * moments.cwiseMax(floor).asDiagonal() * axes.transpose();
    return scale * Matrix3(0.5 * (raised + raised.transpose()));
}

}  // namespace cyclone::detail
