// Scenes shared by the joint tests: chains and pendulums without contacts.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {

/// A box of half extents `half`, m, and `mass`, kg, centred at `position`; it collides
/// with the layers in `collidesWith` (none by default).
inline BodyId addBox(World &world, const Vector3 &position, const Vector3 &half, real mass,
                     std::uint32_t collidesWith = 0) {
    BodySettings s;
    s.shape = Shape::box(half);
    s.position = position;
    s.mass = mass;
    s.collidesWith = collidesWith;
    return world.addBody(s);
}

/// The settings of a joint of `type` on body `a` at `anchor` about `axis` (to the world
/// unless the caller sets b); the caller adds limits, a motor or a servo.
inline JointSettings jointSettings(JointType type, BodyId a, const Vector3 &anchor, const Vector3 &axis) {
    JointSettings j;
    j.type = type;
    j.a = a;
    j.anchor = anchor;
    j.axis = axis;
    return j;
}

/// Expects World::addJoint to refuse `j`, naming `field`.
inline void expectJointRefused(World &world, const JointSettings &j, const std::string &field) {
    try {
        world.addJoint(j);
        ADD_FAILURE() << "accepted, expected a refusal of " << field;
    } catch (const InvalidArgument &error) {
        EXPECT_EQ(error.function(), "World::addJoint");
        EXPECT_EQ(error.field(), field) << error.what();
    }
}

/// A chain of `links` boxes `linkLength` long (1 kg each) joined end to end by ball
/// joints, its first link hung from the world point `top`; with `ballMass` > 0 a sphere of
/// radius 0.3 m and that mass hangs from its last link. `horizontal` lays it out along +x
/// instead of down -y. No body collides with any other.
struct Chain {
    std::vector<BodyId> bodies;
    std::vector<JointId> joints;

    Chain(World &world, int links, real linkLength, real ballMass, bool horizontal,
          const Vector3 &top = Vector3(0, 20, 0)) {
        const Vector3 along = horizontal ? Vector3::UnitX() : Vector3(-Vector3::UnitY());
        std::optional<BodyId> previous;
        for (int i = 0; i <= links; ++i) {
            const bool ball = i == links;
            if (ball && !(ballMass > 0)) break;
            BodySettings s;
            s.collidesWith = 0;
            if (ball) {
                s.shape = Shape::sphere(0.3);
                s.mass = ballMass;
                s.position = top + along * (links * linkLength + 0.3);
            } else {
                s.shape = horizontal ? Shape::box(Vector3(linkLength / 2, 0.05, 0.05))
                                     : Shape::box(Vector3(0.05, linkLength / 2, 0.05));
                s.mass = 1;
                s.position = top + along * ((i + 0.5) * linkLength);
            }
            const BodyId body = world.addBody(s);
            JointSettings j;
            j.type = JointType::Ball;
            j.a = body;
            j.b = previous;
            j.anchor = top + along * (i * linkLength);
            joints.push_back(world.addJoint(j));
            bodies.push_back(body);
            previous = body;
        }
    }

    /// The largest error of its joints now, m.
    real largestError(const World &world) const {
        real largest = 0;
        for (const JointId &j : joints) largest = std::max(largest, world.jointState(j).error);
        return largest;
    }
};

/// Runs `steps` steps of dt and returns the largest error any joint of `chain` had after
/// any of them, m; `last` gets the largest error of the last joint.
inline real largestChainError(World &world, const Chain &chain, int steps, real dt, real *last = nullptr) {
    real largest = 0;
    real lastLargest = 0;
    for (int i = 0; i < steps; ++i) {
        world.step(dt);
        largest = std::max(largest, chain.largestError(world));
        lastLargest = std::max(lastLargest, world.jointState(chain.joints.back()).error);
    }
    if (last) *last = lastLargest;
    return largest;
}

}  // namespace cyclone::test
