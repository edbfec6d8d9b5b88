/// \file
/// LockedAxes: the world axes a body may not move along or turn about (2D bodies in a 3D
/// world, upright characters).
#pragma once

#include "cyclone/core.h"

namespace cyclone {

/// World axes along which a dynamic body may not move (x, y, z) and about which it may not
/// turn (rx, ry, rz). Contacts, joints, springs, forces and gravity never move it along a
/// locked axis: its velocity there stays zero and its position and orientation keep, along
/// and about those axes, what they were when the step began. {z, rx, ry} keeps a body in
/// its x-y plane, turning only about z (a 2D body); {rx, rz} keeps it upright.
struct LockedAxes {
    bool x = false;   ///< No motion along world x.
    bool y = false;   ///< No motion along world y.
    bool z = false;   ///< No motion along world z.
    bool rx = false;  ///< No turning about world x.
    bool ry = false;  ///< No turning about world y.
    bool rz = false;  ///< No turning about world z.

    /// Whether any axis is locked.
    bool any() const { return x || y || z || rx || ry || rz; }
    /// Whether the two lock the same axes.
    bool operator==(const LockedAxes &o) const {
        return x == o.x && y == o.y && z == o.z && rx == o.rx && ry == o.ry && rz == o.rz;
    }
    /// Whether the two lock different axes.
    bool operator!=(const LockedAxes &o) const { return !(*this == o); }
};

}  // namespace cyclone
