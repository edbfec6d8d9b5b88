// A ball rolling fast on a plane keeps its height: within a step its contact's depth is
// read at its deepest point, not at a point fixed on the ball that turns away from the
// plane as it rolls.
#include <cmath>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A 0.25 m ball rolling at 4.3 m/s (w = v / r = 17.2 rad/s about -z) at the defaults (4
// sub-steps of h = dt / 4). Nothing presses it into the plane but gravity, which the
// contact holds: its centre stays within the 1 mm of r (a converged resting
// contact is one slop deep plus a sub-step's fall, g h^2: 0.2 + 0.17 mm), and after its
// first step its vertical speed within 0.01 m/s. Before, the anchor fixed on the ball rose
// r (1 - cos(w t)) within a step (0.6 mm after one sub-step, 5.8 mm after three), the
// depths read from it let the ball fall through the later sub-steps, and it sat 2.7 mm low.
TEST(RollingDepth, AFastBallRollingOnAPlaneKeepsItsHeight) {
    WorldFixture f(noSleep());
    f.ground();
    const real r = 0.25;
    const BodyId ball = f.sphere(Vector3(0, r, 0), r);
    f.world.setVelocity(ball, Vector3(4.3, 0, 0));
    f.world.setRotation(ball, Vector3(0, 0, -4.3 / r));
    for (int i = 0; i < 120; ++i) {
        f.world.step(kDt);
        SCOPED_TRACE("step " + std::to_string(i));
        EXPECT_NEAR(f.position(ball).y(), r, 0.001);
        if (i > 0) {
            EXPECT_LE(std::abs(f.world.body(ball).getVelocity().y()), 0.01);
        }
    }
    EXPECT_GT(f.position(ball).x(), 4);  // still rolling: 2 s at about 4.3 m/s
}

}  // namespace
}  // namespace cyclone::test
