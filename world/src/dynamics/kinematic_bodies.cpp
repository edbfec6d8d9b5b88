#include "dynamics/kinematic_bodies.h"

#include "contacts/pair_cache.h"
#include "world/body_store.h"

namespace cyclone::detail {

void KinematicBodies::beginStep(BodyStore &bodies, const PairCache &pairs, BodyTransitions transitions) {
    bodies.moving.clear();
    for (std::uint32_t index : bodies.kinematic) {
        BodyRecord &r = bodies[index];
        const bool moving = !r.isolated && movesAt(r.body.getVelocity(), r.body.getRotation());
        if (moving && !r.moving) startMoving(bodies, pairs, transitions, index);
        if (!moving && r.moving) {
            r.moving = false;
            r.body.setAwake(false);  // its velocities are zero already
            transitions.setTree(index, Tree::Static);
        }
        r.solverIndex = 0;
        if (moving) bodies.moving.push_back(index);
    }
}

void KinematicBodies::number(BodyStore &bodies) {
    const std::size_t simulated = bodies.simulated.size();
    for (std::size_t k = 0; k < bodies.moving.size(); ++k)
        bodies[bodies.moving[k]].solverIndex = static_cast<int>(simulated + k) + 1;
}

void KinematicBodies::startMoving(BodyStore &bodies, const PairCache &pairs, BodyTransitions transitions,
                                  std::uint32_t index) {
    BodyRecord &r = bodies[index];
    if (r.moving || r.isolated) return;
    r.moving = true;
    r.body.setAwake(true);
    if (r.object) r.object->place(r.body.getTransform(), kBroadphaseMargin);
    transitions.setTree(index, Tree::Awake);
    // What rested on it must follow from the first step it moves.
    for (std::uint32_t p : r.pairs) {
        const PairState &pair = pairs[p];
        const std::uint32_t other = pair.a == index ? pair.b : pair.a;
        if (!bodies[other].immovable) transitions.wake(other);
    }
}

void KinematicBodies::integrate(BodyStore &bodies, real h) {
    for (std::uint32_t index : bodies.moving) {
        RigidBody &body = bodies[index].body;
        body.setPosition(body.getPosition() + h * body.getVelocity());
        const Vector3 w = body.getRotation();
        const real angle = w.norm() * h;
        if (angle > 0) body.setOrientation(Quaternion(Eigen::AngleAxis<real>(angle, w.normalized())) * body.getOrientation());
    }
}

}  // namespace cyclone::detail
