// The per-step trace (CSV): one row per dynamic body per recorded step, numbers with
// enough digits to read back the same doubles.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "cyclone/body.h"

namespace cyclone::scene {

/// The trace's header line, exactly as the scene-format contract gives it.
inline constexpr const char *kTraceHeader = "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,awake";

class TraceWriter {
public:
    /// Writes the header to `out`; rows follow with write().
    explicit TraceWriter(std::ostream &out);
    /// One row: the body's state after step `step` (0-based), at `time` seconds. With a
    /// `frameOffset` (world space, m, from the centre of mass to a compound's frame), the
    /// row gives that frame's position and its origin's velocity.
    void write(std::int64_t step, real time, const std::string &name, const RigidBody &body,
               const Vector3 &frameOffset = Vector3::Zero());

private:
    std::ostream &out_;
};

/// `field` as one CSV field: quoted (quotes doubled) when it holds a comma, a quote or a
/// line break.
std::string csvField(const std::string &field);

}  // namespace cyclone::scene
