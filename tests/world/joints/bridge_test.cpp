// A rope bridge: 20 planks joined edge to edge by pairs of ball joints, hung between two
// world points, a load 25 times a plank's mass dropped on its middle.
#include <cmath>

#include "joints/joint_fixture.h"

namespace cyclone::test {
namespace {

// Plank i (1 kg, 0.4 m along its length, 1.2 m wide) runs from P_i to P_i+1 at the angle
// a_i = -0.5 + i / 19 rad (from -0.5 to +0.5: a sagging arc); P_0 = (0, 10, 0). Each
// junction, and each end to the world, is two ball joints at the plank's edges
// (z = +-0.5). A 25 kg box (25:1) is dropped from 5 cm onto the two middle planks. The
// joints hold the arc's length exactly, so every gap stays at the solver's tolerance: over
// 10 s at most 1 cm (the bound), and the load stays on the bridge (above the
// middle planks' lowest point).
TEST(Bridge, TwentyPlanksHoldA25To1LoadWithinACentimetre) {
    World world;
    std::vector<Vector3> points{Vector3(0, 10, 0)};
    std::vector<BodyId> planks;
    std::vector<JointId> joints;
    const auto join = [&](BodyId a, std::optional<BodyId> b, const Vector3 &at) {
        for (const real z : {-0.5, 0.5}) {
            JointSettings j;
            j.type = JointType::Ball;
            j.a = a;
            j.b = b;
            j.anchor = at + Vector3(0, 0, z);
            joints.push_back(world.addJoint(j));
        }
    };
    for (int i = 0; i < 20; ++i) {
        const real angle = -0.5 + i / 19.0;
        points.push_back(points.back() + 0.4 * Vector3(std::cos(angle), std::sin(angle), 0));
        BodySettings s;
        s.shape = Shape::box(Vector3(0.2, 0.03, 0.6));
        s.mass = 1;
        s.position = 0.5 * (points[i] + points[i + 1]);
        s.orientation = Quaternion(Eigen::AngleAxis<real>(angle, Vector3::UnitZ()));
        planks.push_back(world.addBody(s));
        join(planks.back(), i == 0 ? std::nullopt : std::optional<BodyId>(planks[i - 1]), points[i]);
    }
    join(planks.back(), std::nullopt, points.back());
    const Vector3 middle = points[10];
    BodySettings load;
    load.shape = Shape::box(Vector3(0.25, 0.25, 0.25));
    load.mass = 25;
    load.position = middle + Vector3(0, 0.03 + 0.25 + 0.05, 0);
    const BodyId box = world.addBody(load);
    real widest = 0;
    for (int step = 0; step < 600; ++step) {
        world.step(kDt);
        for (const JointId j : joints) widest = std::max(widest, world.jointState(j).error);
    }
    EXPECT_LE(widest, 0.01);
    const real lowest = std::min(world.body(planks[9]).getPosition().y(), world.body(planks[10]).getPosition().y());
    EXPECT_GT(world.body(box).getPosition().y(), lowest);
}

}  // namespace
}  // namespace cyclone::test
