// Spring forces, at the start of every sub-step of h seconds: explicit (the seed's) or
// backward Euler, per spring (SpringSet::chooseForces).
//
// Design note. An explicit spring force makes each sub-step a symplectic Euler step of
// the oscillator: stable only while omega h < 2, and beyond that the energy grows every
// step. The implicit force is the one the spring will exert at the end of
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
// tests/world/dynamics/integrator_test.cpp. Springs sharing a body are coupled: each is solved
// with the others' current forces, in kImplicitSpringPasses passes warm-started with the
// last sub-step's forces (block Gauss-Seidel). At rest the warm start is the solution, so
// a chain hangs exactly where its springs carry the weight below them.
//
// Which springs are implicit. With NewtonEulerImplicit, all of them. Otherwise a spring of
// SpringForce::Automatic is implicit when omega h > WorldSettings::explicitSpringLimit,
// omega^2 being the largest load of its moving ends: a body's load is the sum over its
// springs of k (w_a + w_b), w the inverse mass of each moving end at its attachment point
// along the spring (1/m + (r x d) . I^-1 (r x d)). That is omega^2 exactly for one spring
// (k (1/m_a + 1/m_b)), for a body held by several springs along one line, and for the
// highest mode of a long chain (4 k / m); explicit springs far below the limit are left
// as they are, and keep their energy.
#include "dynamics/springs.h"

#include <algorithm>

namespace cyclone::detail {
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

// The inverse mass of `body` at `r` from its centre of mass along the unit vector d.
real inverseMassAlong(const RigidBody &body, const Vector3 &r, const Vector3 &d) {
    const Vector3 arm = r.cross(d);
    return body.getInverseMass() + arm.dot(body.getInverseInertiaTensorWorld() * arm);
}

// The part of an implicit spring's sub-step that stays fixed through the passes: its
// ends' motion, the attachment points, the spring's force there and its 3x3 system.
// False when the spring pushes nothing: neither end moves, an end is isolated, or it has
// no direction to push along.
bool implicitSystem(const SpringSettings &spring, const BodyStore &bodies, real h, ImplicitSpring &is) {
    const BodyRecord &a = bodies[spring.a.index];
    const BodyRecord *b = spring.b ? &bodies[spring.b->index] : nullptr;
    const bool bSimulated = b && b->simulated;
    if ((!a.simulated && !bSimulated) || a.isolated || (b && b->isolated)) return false;
    is.aMoves = a.simulated;
    is.bMoves = bSimulated;
    is.pa = a.body.getPointInWorldSpace(spring.aPoint);
    is.pb = b ? b->body.getPointInWorldSpace(spring.bPoint) : spring.bPoint;
    // An end that does not move this step (static, or woken during it) is at rest.
    Matrix3 inverseMass = Matrix3::Zero();
    if (is.aMoves) inverseMass += pointInverseMass(a.body, is.pa - a.body.getPosition());
    if (is.bMoves) inverseMass += pointInverseMass(b->body, is.pb - b->body.getPosition());

    const Vector3 delta = is.pa - is.pb;
    const real length = delta.norm();
    const real k = spring.stiffness;
    Matrix3 stiffness;
    Matrix3 damping = Matrix3::Zero();
    if (length > 1e-12) {
        const Vector3 d = delta / length;
        const Matrix3 along = d * d.transpose();
        is.force0 = -k * (length - spring.restLength) * d;
        // Across the spring the stiffness is k (1 - L/l); a compressed spring's is
        // negative (it buckles) and is left explicit.
        const real across = std::max(real(0), 1 - spring.restLength / length);
        stiffness = k * along + k * across * (Matrix3::Identity() - along);
        damping = spring.damping * along;
    } else if (spring.restLength == 0) {
        // A zero-length spring at zero length: no direction, but k x is linear.
        is.force0 = -k * delta;
        stiffness = k * Matrix3::Identity();
    } else {
        return false;
    }
    is.response = h * stiffness + damping;
    is.system.compute(Matrix3::Identity() + h * is.response * inverseMass);
    return true;
}

// The velocity of a's attachment point relative to b's after h seconds of the forces
// accumulated so far (each moving end's; an end at rest contributes none).
Vector3 freeRelativeVelocity(const BodyStore &bodies, const SpringSettings &spring, const ImplicitSpring &is, real h) {
    Vector3 u = Vector3::Zero();
    if (is.aMoves) {
        const RigidBody &a = bodies[spring.a.index].body;
        u += freePointVelocity(a, is.pa - a.getPosition(), h);
    }
    if (is.bMoves) {
        const RigidBody &b = bodies[spring.b->index].body;
        u -= freePointVelocity(b, is.pb - b.getPosition(), h);
    }
    return u;
}

}  // namespace

int SpringSet::chooseForces(BodyStore &bodies, const WorldSettings &settings, real h) {
    const bool allImplicit = settings.integrator == Integrator::NewtonEulerImplicit;
    const real limit = settings.explicitSpringLimit / h;  // omega, 1/s
    // The load of every spring's ends, zeroed then summed; other bodies' entries are unused.
    load_.resize(bodies.size());
    for (const SpringRecord &s : records) {
        if (!s.alive) continue;
        load_[s.settings.a.index] = 0;
        if (s.settings.b) load_[s.settings.b->index] = 0;
    }
    const auto moves = [&](const BodyRecord *r) { return r && r->simulated && !r->isolated; };
    for (const SpringRecord &s : records) {
        if (!s.alive || allImplicit || s.settings.force == SpringForce::Explicit) continue;
        BodyRecord &a = bodies[s.settings.a.index];
        BodyRecord *b = s.settings.b ? &bodies[s.settings.b->index] : nullptr;
        if (!moves(&a) && !moves(b)) continue;
        const Vector3 pa = a.body.getPointInWorldSpace(s.settings.aPoint);
        const Vector3 pb = b ? b->body.getPointInWorldSpace(s.settings.bPoint) : s.settings.bPoint;
        const Vector3 delta = pa - pb;
        const real length = delta.norm();
        // Without a direction, the centres' inverse masses (a zero-length spring at rest).
        const Vector3 d = length > 1e-12 ? Vector3(delta / length) : Vector3::Zero();
        real w = 0;
        if (moves(&a)) w += inverseMassAlong(a.body, pa - a.body.getPosition(), d);
        if (moves(b)) w += inverseMassAlong(b->body, pb - b->body.getPosition(), d);
        if (moves(&a)) load_[s.settings.a.index] += s.settings.stiffness * w;
        if (moves(b)) load_[s.settings.b->index] += s.settings.stiffness * w;
    }
    int count = 0;
    for (SpringRecord &s : records) {
        if (!s.alive) continue;
        s.implicit = allImplicit;
        if (!allImplicit && s.settings.force == SpringForce::Automatic) {
            real load = load_[s.settings.a.index];
            if (s.settings.b) load = std::max(load, load_[s.settings.b->index]);
            s.implicit = load > limit * limit;
        }
        count += s.implicit ? 1 : 0;
    }
    return count;
}

void SpringSet::addExplicitForces(BodyStore &bodies) {
    for (SpringRecord &s : records) {
        if (!s.alive || s.implicit) continue;
        BodyRecord &a = bodies[s.settings.a.index];
        BodyRecord *b = s.settings.b ? &bodies[s.settings.b->index] : nullptr;
        const bool bSimulated = b && b->simulated;
        if (!a.simulated && !bSimulated) continue;
        if (a.isolated || (b && b->isolated)) continue;
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
        s.implicitForce = force;
    }
}

void SpringSet::addImplicitForces(BodyStore &bodies, real h) {
    solving.clear();
    for (std::uint32_t index = 0; index < records.size(); ++index) {
        SpringRecord &s = records[index];
        if (!s.alive || !s.implicit) continue;
        ImplicitSpring is;
        is.spring = index;
        if (implicitSystem(s.settings, bodies, h, is)) solving.push_back(is);
        else s.implicitForce.setZero();
    }
    if (solving.empty()) return;

    const auto apply = [&](const ImplicitSpring &is, const Vector3 &force) {
        const SpringSettings &spring = records[is.spring].settings;
        if (is.aMoves) bodies[spring.a.index].body.addForceAtPoint(force, is.pa);
        if (is.bMoves) bodies[spring.b->index].body.addForceAtPoint(-force, is.pb);
    };
    // Warm start: the forces of the last sub-step, which at rest are already the answer.
    for (const ImplicitSpring &is : solving) apply(is, records[is.spring].implicitForce);
    // Each pass solves every spring for the velocity its points reach with the others'
    // current forces (block Gauss-Seidel); one pass is exact for a spring alone.
    for (int pass = 0; pass < kImplicitSpringPasses; ++pass) {
        for (const ImplicitSpring &is : solving) {
            SpringRecord &s = records[is.spring];
            apply(is, -s.implicitForce);
            const Vector3 u = freeRelativeVelocity(bodies, s.settings, is, h);
            const Vector3 force = is.system.solve(is.force0 - is.response * u);
            s.implicitForce = force.allFinite() ? force : Vector3::Zero();
            apply(is, s.implicitForce);
        }
    }
}

}  // namespace cyclone::detail
