// A rope of light beads holding a heavy ball (issue 61, row 1): twenty 0.1 kg beads
// 0.25 m apart on distance or ball joints, a 100 kg ball at the end (1:1000), hung from a
// world point and released lying horizontal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "joint_fixture.h"

namespace cyclone::test {
namespace {

constexpr int kBeads = 20;
constexpr real kGap = 0.25;  // m between neighbours' centres

struct BeadRope {
    std::vector<BodyId> bodies;  // the beads, then the ball
    std::vector<JointId> joints;

    BeadRope(World &world, JointType type) {
        const Vector3 top(0, 5, 0);
        std::optional<BodyId> previous;
        for (int i = 0; i <= kBeads; ++i) {
            const bool ball = i == kBeads;
            BodySettings s;
            s.shape = Shape::sphere(ball ? 0.2 : 0.05);
            s.mass = ball ? 100 : 0.1;
            s.position = top + Vector3(kGap * (i + 1), 0, 0);
            const BodyId body = world.addBody(s);
            JointSettings j;
            j.type = type;
            j.a = body;
            j.b = previous;
            j.anchor = s.position;
            if (type == JointType::Distance) j.anchorB = top + Vector3(kGap * i, 0, 0);
            joints.push_back(world.addJoint(j));
            bodies.push_back(body);
            previous = body;
        }
    }
};

// The joints are rigid (a distance joint's length is its length at creation), so every
// neighbour stays kGap from the next: within 1 mm over 10 s, as a chain of boxes does.
// With no damping of the joints the swing keeps going; it may not gain energy: the
// kinetic energy stays below the potential energy given up (m g times the drop of each
// body), within 1 % of the ball's 100 kg x 9.81 x 5.25 m.
TEST(BeadRope, HeavyBallOnLightBeadsKeepsEveryGapWithinAMillimetre) {
    for (const JointType type : {JointType::Distance, JointType::Ball}) {
        SCOPED_TRACE(type == JointType::Distance ? "distance joints" : "ball joints");
        WorldSettings settings = noSleep();
        World world(settings);
        const BeadRope rope(world, type);
        std::vector<real> startHeight;
        for (BodyId b : rope.bodies) startHeight.push_back(world.body(b).getPosition().y());
        const real g = -settings.gravity.y();
        real worstGap = 0, worstGain = -1e300;
        for (int step = 0; step < 600; ++step) {
            world.step(kDt);
            real kinetic = 0, released = 0;
            Vector3 previous(0, 5, 0);
            for (std::size_t k = 0; k < rope.bodies.size(); ++k) {
                const RigidBody &body = world.body(rope.bodies[k]);
                const Vector3 p = body.getPosition();
                worstGap = std::max(worstGap, std::abs((p - previous).norm() - kGap));
                previous = p;
                // A solid sphere's moment of inertia is 2/5 m r^2.
                const real radius = k + 1 == rope.bodies.size() ? 0.2 : 0.05;
                kinetic += 0.5 * body.getMass() *
                           (body.getVelocity().squaredNorm() + 0.4 * radius * radius * body.getRotation().squaredNorm());
                released += body.getMass() * g * (startHeight[k] - p.y());
            }
            worstGain = std::max(worstGain, kinetic - released);
        }
        EXPECT_LT(worstGap, 1e-3);
        EXPECT_LT(worstGain, 0.01 * 100 * g * 5.25);
    }
}

}  // namespace
}  // namespace cyclone::test
