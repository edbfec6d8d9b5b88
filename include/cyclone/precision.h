/// \file
/// Numeric precision of the cyclone dynamics core.
#pragma once

namespace cyclone {

/// Scalar type of every quantity in the library (double precision).
using real = double;

}  // namespace cyclone
