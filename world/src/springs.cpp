// Spring forces: explicit (the seed's, once per step) or backward Euler (every sub-step).
//
// Design note. An explicit spring force, held for a whole step, is the symplectic Euler
// step of an oscillator: stable only while omega dt < 2, and beyond that the energy
// grows every step. The implicit force is the one the spring will exert at the end of
// the sub-step: F = F(x + h u') - c u', where u' is the relative velocity of the two
// attachment points after the sub-step. Linearising the spring about the current
// attachment points (stiffness K = k d d^T along the spring plus k (1 - L/l) across it
// when stretched) and writing u' = u + h W F, with u the velocity the points reach
// without this spring and W the inverse mass matrix of the two points, gives the 3x3
// system (1 + h (h K + C) W) F = F0 - (h K + C) u. For a body held at its centre of mass
// this is exactly backward Euler along the spring, whose energy shrinks by
// 1 / (1 + (omega h)^2) per sub-step whatever omega h is. An attachment off the centre of
// mass moves on a circle, not along its velocity, so a fast-turning body may gain a
// little in one step (k |stretch| (h w)^2 r at most), never beyond its starting energy in
// tests/world/integrator_test.cpp. Springs sharing a body are solved one after the
// other, each seeing the forces of those before it (one Gauss-Seidel pass).
#include <Eigen/LU>
#include <algorithm>

#include "world_impl.h"

namespace cyclone {
namespace {

Matrix3 skew(const Vector3 &v) {
    Matrix3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

// The velocity change at a point `r` from the centre of mass per unit impulse there:
// 1/m - [r]x I^-1 [r]x (world space).
Matrix3 pointInverseMass(const RigidBody &body, const Vector3 &r) {
    const Matrix3 rx = skew(r);
    return body.getInverseMass() * Matrix3::Identity() - rx * body.getInverseInertiaTensorWorld() * rx;
}

// The velocity of the point `r` from the centre of mass after h seconds of the forces
// accumulated so far (gravity, user forces, springs already solved).
Vector3 freePointVelocity(const RigidBody &body, const Vector3 &r, real h) {
    const Vector3 v = body.getVelocity() +
                      h * (body.getAcceleration() + body.getInverseMass() * body.getAccumulatedForce());
    const Vector3 w = body.getRotation() + h * (body.getInverseInertiaTensorWorld() * body.getAccumulatedTorque());
    return v + w.cross(r);
}

}  // namespace

void World::Impl::addExplicitSpringForces() {
    for (SpringRecord &s : springs) {
        if (!s.alive) continue;
        BodyRecord &a = bodies[s.settings.a.index];
        BodyRecord *b = s.settings.b ? &bodies[s.settings.b->index] : nullptr;
        const bool bSimulated = b && b->simulated;
        if (!a.simulated && !bSimulated) continue;
        if (a.quarantined || (b && b->quarantined)) continue;
        const Vector3 pa = a.body.getPointInWorldSpace(s.settings.aPoint);
        const Vector3 pb = b ? b->body.getPointInWorldSpace(s.settings.bPoint) : s.settings.bPoint;
        const Vector3 d = pa - pb;
        const real length = d.norm();
        if (!(length > 1e-12)) continue;
        const Vector3 dir = d / length;
        const Vector3 va = a.body.getVelocity() + a.body.getRotation().cross(pa - a.body.getPosition());
        const Vector3 vb = b ? Vector3(b->body.getVelocity() + b->body.getRotation().cross(pb - b->body.getPosition()))
                             : Vector3::Zero();
        const Vector3 force = -(s.settings.stiffness * (length - s.settings.restLength) +
                                s.settings.damping * (va - vb).dot(dir)) * dir;
        if (!force.allFinite()) continue;
        if (a.simulated) a.body.addForceAtPoint(force, pa);
        if (bSimulated) b->body.addForceAtPoint(-force, pb);
    }
}

void World::Impl::addImplicitSpringForces(real h) {
    for (SpringRecord &s : springs) {
        if (!s.alive) continue;
        const SpringSettings &spring = s.settings;
        BodyRecord &a = bodies[spring.a.index];
        BodyRecord *b = spring.b ? &bodies[spring.b->index] : nullptr;
        const bool bSimulated = b && b->simulated;
        if (!a.simulated && !bSimulated) continue;
        if (a.quarantined || (b && b->quarantined)) continue;
        const Vector3 pa = a.body.getPointInWorldSpace(spring.aPoint);
        const Vector3 pb = b ? b->body.getPointInWorldSpace(spring.bPoint) : spring.bPoint;

        // An end that does not move this step (static, or woken during it) is at rest.
        Vector3 u = Vector3::Zero();
        Matrix3 inverseMass = Matrix3::Zero();
        if (a.simulated) {
            const Vector3 r = pa - a.body.getPosition();
            u += freePointVelocity(a.body, r, h);
            inverseMass += pointInverseMass(a.body, r);
        }
        if (bSimulated) {
            const Vector3 r = pb - b->body.getPosition();
            u -= freePointVelocity(b->body, r, h);
            inverseMass += pointInverseMass(b->body, r);
        }

        const Vector3 delta = pa - pb;
        const real length = delta.norm();
        const real k = spring.stiffness;
        Vector3 force0;
        Matrix3 stiffness;
        Matrix3 damping = Matrix3::Zero();
        if (length > 1e-12) {
            const Vector3 d = delta / length;
            const Matrix3 along = d * d.transpose();
            force0 = -k * (length - spring.restLength) * d;
            // Across the spring the stiffness is k (1 - L/l); a compressed spring's is
            // negative (it buckles) and is left explicit.
            const real across = std::max(real(0), 1 - spring.restLength / length);
            stiffness = k * along + k * across * (Matrix3::Identity() - along);
            damping = spring.damping * along;
        } else if (spring.restLength == 0) {
            // A zero-length spring at zero length: no direction, but k x is linear.
            force0 = -k * delta;
            stiffness = k * Matrix3::Identity();
        } else {
            continue;  // no direction to push along
        }
        const Matrix3 response = h * stiffness + damping;
        const Matrix3 system = Matrix3::Identity() + h * response * inverseMass;
        const Vector3 force = system.partialPivLu().solve(force0 - response * u);
        if (!force.allFinite()) continue;
        if (a.simulated) a.body.addForceAtPoint(force, pa);
        if (bSimulated) b->body.addForceAtPoint(-force, pb);
    }
}

}  // namespace cyclone
