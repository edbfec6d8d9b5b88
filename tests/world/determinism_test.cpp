// Determinism as a contract (after Box2D's test_determinism.c): the same scene, built
// and stepped the same way, gives bit-identical states and events. Here two worlds in
// one process, stepped in turns so that any state shared between worlds (caches, static
// scratch) would show; tests/determinism/ runs the scene runner twice, in two processes.
#include <cstring>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

bool bitsEqual(real x, real y) { return std::memcmp(&x, &y, sizeof x) == 0; }

template <class V>
bool bitsEqual(const V &x, const V &y) {
    for (int i = 0; i < x.size(); ++i)
        if (!bitsEqual(x[i], y[i])) return false;
    return true;
}

// Every shape type on a mesh floor: a stack of boxes, a pile of mixed shapes thrown in
// with spin, a spring, and a ball that falls on a sleeping stack later.
struct DeterminismScene {
    World world;
    std::vector<BodyId> ids;

    DeterminismScene() {
        BodySettings floor;
        floor.motion = Motion::Static;
        floor.shape = Shape::mesh({Vector3(-20, 0, -20), Vector3(20, 0, -20), Vector3(20, 0, 20), Vector3(-20, 0, 20)},
                                  {{0, 2, 1}, {0, 3, 2}});
        ids.push_back(world.addBody(floor));
        BodySettings wall;
        wall.motion = Motion::Static;
        wall.shape = Shape::box(Vector3(0.25, 1, 4));
        wall.position = Vector3(4, 1, 0);
        ids.push_back(world.addBody(wall));
        for (int i = 0; i < 6; ++i) {
            BodySettings box;
            box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
            box.position = Vector3(-3 + 0.01 * i, 0.5 + i, 0.02 * (i % 2));
            ids.push_back(world.addBody(box));
        }
        const Shape shapes[] = {Shape::sphere(0.35), Shape::capsule(0.25, 0.6), Shape::cylinder(0.3, 0.8),
                                Shape::convex({Vector3(0.5, 0, 0), Vector3(-0.5, 0, 0), Vector3(0, 0.5, 0),
                                               Vector3(0, -0.5, 0), Vector3(0, 0, 0.5), Vector3(0, 0, -0.5)}),
                                Shape::box(Vector3(0.4, 0.3, 0.5))};
        for (int i = 0; i < 15; ++i) {
            BodySettings s;
            s.shape = shapes[i % 5];
            s.mass = 1 + 0.5 * (i % 3);
            s.position = Vector3(1 + 0.9 * (i % 3), 1 + 1.1 * (i / 3), -1 + 0.7 * (i % 4));
            s.orientation = Quaternion(1, 0.1 * i, 0.2, -0.05 * i);  // normalised on add
            s.velocity = Vector3(1.5, 0, 0.3 * (i % 2));
            s.rotation = Vector3(0.5 * i, -1, 2);
            s.material.restitution = 0.1 * (i % 3);
            ids.push_back(world.addBody(s));
        }
        SpringSettings spring;
        spring.a = ids[7];
        spring.aPoint = Vector3(0.5, 0.5, 0);
        spring.bPoint = Vector3(-3, 8, 0);
        spring.restLength = 1.5;
        spring.stiffness = 50;
        spring.damping = 2;
        world.addSpring(spring);
    }

    void step(int index) {
        if (index == 200) {
            BodySettings ball;
            ball.shape = Shape::sphere(0.3);
            ball.position = Vector3(-3, 9, 0);
            ids.push_back(world.addBody(ball));
        }
        if (index == 260) world.applyImpulse(ids[3], Vector3(0.5, 0, 0), Vector3(-3, 1, 0.4));
        world.step(kDt);
    }
};

::testing::AssertionResult sameState(const DeterminismScene &x, const DeterminismScene &y) {
    if (x.ids.size() != y.ids.size()) return ::testing::AssertionFailure() << "different body counts";
    for (std::size_t i = 0; i < x.ids.size(); ++i) {
        const RigidBody &a = x.world.body(x.ids[i]);
        const RigidBody &b = y.world.body(y.ids[i]);
        if (!bitsEqual(a.getPosition(), b.getPosition()) ||
            !bitsEqual(a.getOrientation().coeffs(), b.getOrientation().coeffs()) ||
            !bitsEqual(a.getVelocity(), b.getVelocity()) || !bitsEqual(a.getRotation(), b.getRotation()) ||
            a.getAwake() != b.getAwake())
            return ::testing::AssertionFailure() << "body " << i << " differs";
    }
    const WorldEvents &e = x.world.events();
    const WorldEvents &f = y.world.events();
    if (e.contactBegins.size() != f.contactBegins.size() || e.contactEnds.size() != f.contactEnds.size() ||
        e.fellAsleep != f.fellAsleep || e.wokeUp != f.wokeUp)
        return ::testing::AssertionFailure() << "events differ";
    for (std::size_t i = 0; i < e.contactBegins.size(); ++i) {
        const ContactBegin &p = e.contactBegins[i];
        const ContactBegin &q = f.contactBegins[i];
        if (p.a != q.a || p.b != q.b || !bitsEqual(p.point, q.point) || !bitsEqual(p.normal, q.normal) ||
            !bitsEqual(p.depth, q.depth) || !bitsEqual(p.approachSpeed, q.approachSpeed))
            return ::testing::AssertionFailure() << "contact begin " << i << " differs";
    }
    for (std::size_t i = 0; i < e.contactEnds.size(); ++i)
        if (e.contactEnds[i].a != f.contactEnds[i].a || e.contactEnds[i].b != f.contactEnds[i].b)
            return ::testing::AssertionFailure() << "contact end " << i << " differs";
    return ::testing::AssertionSuccess();
}

TEST(Determinism, TwoWorldsSteppedInTurnsAreBitIdentical) {
    DeterminismScene x, y;
    int begins = 0, sleeps = 0, wakes = 0;
    for (int i = 0; i < 480; ++i) {
        x.step(i);
        y.step(i);
        ASSERT_TRUE(sameState(x, y)) << "after step " << i + 1;
        begins += static_cast<int>(x.world.events().contactBegins.size());
        sleeps += static_cast<int>(x.world.events().fellAsleep.size());
        wakes += static_cast<int>(x.world.events().wokeUp.size());
    }
    // The scene exercises what is compared: contacts, sleep and wake.
    EXPECT_GT(begins, 20);
    EXPECT_GT(sleeps, 0);
    EXPECT_GT(wakes, 0);
}

// A world built after another has run (other addresses, warm caches) runs the same.
TEST(Determinism, AWorldBuiltLaterRunsTheSame) {
    std::vector<std::vector<real>> first;
    auto run = [](std::vector<std::vector<real>> *record, const std::vector<std::vector<real>> *check) {
        DeterminismScene s;
        for (int i = 0; i < 300; ++i) {
            s.step(i);
            std::vector<real> state;
            for (BodyId id : s.ids) {
                const RigidBody &b = s.world.body(id);
                const Quaternion q = b.getOrientation();
                for (const Vector3 &v : {b.getPosition(), b.getVelocity(), b.getRotation()})
                    state.insert(state.end(), v.data(), v.data() + 3);
                state.insert(state.end(), q.coeffs().data(), q.coeffs().data() + 4);
            }
            if (record) record->push_back(state);
            if (check) {
                const std::vector<real> &expected = (*check)[i];
                ASSERT_EQ(state.size(), expected.size());
                ASSERT_EQ(std::memcmp(state.data(), expected.data(), state.size() * sizeof(real)), 0)
                    << "after step " << i + 1;
            }
        }
    };
    run(&first, nullptr);
    run(nullptr, &first);
}

}  // namespace
}  // namespace cyclone::test
