// Before the solve: the ground's pose, and the bodies that run into a character.
//
// A character's capsule is immovable to the contact solver, which would stop a crate
// thrown at it dead. So before the solve, each awake dynamic body that will meet the
// capsule within the step, moving into it across up, shares its momentum with the
// character as in an inelastic collision with a body of the character's mass: the body
// keeps the common speed, and the character gets it as a push (CharacterRecord::push),
// which the ground then slows. Bodies meeting it from above or below (resting on its
// head, lifting it) are left to the solver and to the carrying.
#include <cmath>

#include "character/character_record.h"
#include "queries/queries.h"
#include "world/body_store.h"

namespace cyclone::detail {
namespace {

constexpr real kReach = 1;  // bodies farther than this from the capsule are not looked at, m

void keepGroundPose(const BodyStore &bodies, CharacterRecord &c) {
    if (c.groundBody && bodies.contains(*c.groundBody)) c.groundStart = bodies[c.groundBody->index].body.getTransform();
}

// The impulse that brings a body of inverse mass `bodyInverse` and the character to one
// speed when they approach at `approach`, N s.
real sharedImpulse(real approach, real bodyInverse, real characterMass) {
    return approach / (bodyInverse + 1 / characterMass);
}

void shareMomentum(const Vector3 &gravity, BodyStore &bodies, const QueryScene &queries, CharacterRecord &c, real dt,
                   std::vector<BodyId> &near) {
    const Vector3 up = characterUp(gravity);
    const Quaternion upright = uprightFor(up);
    const Vector3 centre = capsuleCentre(c, up, c.feet);
    QueryFilter filter = characterFilter(bodies, c);
    filter.staticBodies = false;
    filter.kinematicBodies = false;
    overlap(queries, Shape::capsule(c.settings.radius + kReach, c.capsule.length), centre, upright, near, filter);
    for (const BodyId id : near) {
        BodyRecord &b = bodies[id.index];
        if (!b.body.getAwake()) continue;
        const Vector3 relative = b.body.getVelocity() - c.velocity;
        if (!(relative.norm() * dt > 1e-9)) continue;
        QueryFilter only = filter;
        only.accept = [id](BodyId other) { return other == id; };
        const auto hit = shapeCast(queries, c.capsule, centre, upright, -relative * dt, only);
        if (!hit) continue;
        Vector3 n = hit->normal - up * hit->normal.dot(up);
        if (n.norm() < 0.5) continue;
        n.normalize();
        // The character walking into the body is the body being pushed (character_motion.cpp).
        const real approach = b.body.getVelocity().dot(n) - std::max(real(0), c.velocity.dot(n));
        if (!(approach > 0)) continue;
        // At the centre of mass: where along a face it touches is arbitrary.
        const real impulse = sharedImpulse(approach, b.body.getInverseMass(), c.settings.mass);
        b.body.addVelocity(-n * (impulse * b.body.getInverseMass()));
        c.push += n * (impulse / c.settings.mass);
    }
}

}  // namespace

void Characters::beginStep(const Vector3 &gravity, BodyStore &bodies, const QueryScene &queries, real dt) {
    for (CharacterRecord &c : records) {
        if (!c.alive) continue;
        keepGroundPose(bodies, c);
        shareMomentum(gravity, bodies, queries, c, dt, near_);
    }
}

}  // namespace cyclone::detail
