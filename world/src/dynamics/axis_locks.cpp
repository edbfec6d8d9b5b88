#include "dynamics/axis_locks.h"

#include <cmath>

#include "solver/contact_solver.h"
#include "world/body_store.h"

namespace cyclone::detail {
namespace {

// 1 for each free axis, 0 for each locked one.
Vector3 freeTranslations(const LockedAxes &l) { return Vector3(!l.x, !l.y, !l.z); }
Vector3 freeRotations(const LockedAxes &l) { return Vector3(!l.rx, !l.ry, !l.rz); }

// The twist of `turn` about the unit axis `axis`: the rotation about it whose quaternion
// is turn's projected onto (w, axis), normalised; none when that projection is zero (a
// half turn about a perpendicular axis).
Quaternion twistAbout(const Quaternion &turn, const Vector3 &axis) {
    const Vector3 along = axis * axis.dot(turn.vec());
    Quaternion twist(turn.w(), along.x(), along.y(), along.z());
    const real norm = twist.norm();
    if (!(norm > 0)) return Quaternion::Identity();
    twist.coeffs() /= norm;
    return twist;
}

}  // namespace

Vector3 freeLinear(const LockedAxes &locks, const Vector3 &v) { return v.cwiseProduct(freeTranslations(locks)); }

Vector3 freeAngular(const LockedAxes &locks, const Vector3 &w) { return w.cwiseProduct(freeRotations(locks)); }

Quaternion freeTurn(const LockedAxes &locks, const Quaternion &turn) {
    const Vector3 free = freeRotations(locks);
    const int freeCount = static_cast<int>(free.sum());
    if (freeCount == 3) return turn;
    if (freeCount == 0) return Quaternion::Identity();
    if (freeCount == 1) return twistAbout(turn, free);
    const Vector3 locked = Vector3::Ones() - free;
    return (turn * twistAbout(turn, locked).conjugate()).normalized();
}

void lockSolverBody(const LockedAxes &locks, SolverBody &body) {
    if (locks.x && locks.y && locks.z) body.invMass = 0;
    const Vector3 free = freeRotations(locks);
    body.invInertia = free.asDiagonal() * body.invInertia * free.asDiagonal();
}

void AxisLocks::beginStep(const BodyStore &bodies) {
    starts_.clear();
    if (bodies.lockedCount == 0) return;
    for (std::uint32_t index : bodies.simulated) {
        const BodyRecord &r = bodies[index];
        if (r.locked.any()) starts_.push_back({index, r.body.getPosition(), r.body.getOrientation()});
    }
}

void AxisLocks::hold(BodyStore &bodies) const {
    for (const Start &start : starts_) {
        BodyRecord &r = bodies[start.body];
        if (r.isolated) continue;
        const LockedAxes &locks = r.locked;
        r.body.setVelocity(freeLinear(locks, r.body.getVelocity()));
        r.body.setRotation(freeAngular(locks, r.body.getRotation()));
        const Vector3 free = freeTranslations(locks);
        const Vector3 position = r.body.getPosition();
        r.body.setPosition(position.cwiseProduct(free) + start.position.cwiseProduct(Vector3::Ones() - free));
        if (!(locks.rx || locks.ry || locks.rz)) continue;
        const Quaternion turn = r.body.getOrientation() * start.orientation.conjugate();
        r.body.setOrientation(freeTurn(locks, turn) * start.orientation);
    }
}

}  // namespace cyclone::detail
