#include "trace_writer.h"

#include <cstdio>

namespace cyclone::scene {

namespace {

// %.17g: seventeen significant digits read back as the same double.
void appendNumber(std::string &line, real value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, ",%.17g", value);
    line += buffer;
}

}  // namespace

TraceWriter::TraceWriter(std::ostream &out) : out_(out) { out_ << kTraceHeader << '\n'; }

void TraceWriter::write(std::int64_t step, real time, const std::string &name, const RigidBody &body,
                        const Vector3 &frameOffset) {
    std::string line = std::to_string(step);
    appendNumber(line, time);
    line += ',';
    line += csvField(name);
    const Vector3 p = body.getPosition() + frameOffset;
    const Quaternion q = body.getOrientation();
    const Vector3 w = body.getRotation();
    const Vector3 v = body.getVelocity() + w.cross(frameOffset);
    for (real x : {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}) {
        appendNumber(line, x);
    }
    line += body.getAwake() ? ",1\n" : ",0\n";
    out_ << line;
}

std::string csvField(const std::string &field) {
    if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
    std::string quotedField = "\"";
    for (char c : field) {
        if (c == '"') quotedField += '"';
        quotedField += c;
    }
    return quotedField + "\"";
}

}  // namespace cyclone::scene
