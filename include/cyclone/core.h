/// \file
/// Math types of the cyclone dynamics core: Eigen's, so that transforms reach FCL
/// (whose Transform3d is Eigen::Transform<double,3,Isometry>) without conversion.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cyclone/precision.h"

namespace cyclone {

/// A 3-vector: positions (m), velocities (m/s), forces (N), ...
using Vector3 = Eigen::Matrix<real, 3, 1>;
/// A rotation quaternion (w, x, y, z); unit length wherever it describes an orientation.
using Quaternion = Eigen::Quaternion<real>;
/// A 3x3 matrix: rotations and inertia tensors (kg m^2).
using Matrix3 = Eigen::Matrix<real, 3, 3>;
/// A rigid transform (rotation + translation); the type FCL calls Transform3.
using Matrix4 = Eigen::Transform<real, 3, Eigen::Isometry>;

}  // namespace cyclone
