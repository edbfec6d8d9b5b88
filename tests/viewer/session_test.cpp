// The viewer's Session without a window: scene events at their steps, restart, the mouse's
// grab (a mouse joint), the ball shot from the camera and the states that colour bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "camera.h"
#include "meshes.h"
#include "palette.h"
#include "session.h"

namespace cyclone::viewer {
namespace {

std::string scenePath(const std::string &name) { return std::string(CYCLONE_SCENES_DIR) + "/" + name + ".json"; }

// A scene file written for one test, removed after it.
class SceneFile {
public:
    SceneFile(const std::string &name, const std::string &text) : path_(testing::TempDir() + name + ".json") {
        std::ofstream(path_) << text;
    }
    ~SceneFile() { std::remove(path_.c_str()); }
    const std::string &path() const { return path_; }

private:
    std::string path_;
};

// One unit box resting on the ground (its centre at y = 0.5 m), with the default 60 Hz step.
const char *kBoxOnGround = R"({"bodies": [
  {"name": "ground", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
  {"name": "box", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 0.5, 0]}]})";

BodyId bodyNamed(const Session &session, const std::string &name) {
    const std::optional<BodyId> id = session.world().findBody(name);
    EXPECT_TRUE(id.has_value()) << name;
    return id.value_or(BodyId());
}

constexpr real kPiSquared = 9.8696044010893586188;

void runSteps(Session &session, int steps) {
    for (int i = 0; i < steps; ++i) session.singleStep();
}

TEST(ViewerSession, AppliesTheScenesEventsAtTheirSteps) {
    Session session(scenePath("sleep-wake"));
    const BodyId ball = bodyNamed(session, "ball");
    const BodyId stack2 = bodyNamed(session, "stack2");
    runSteps(session, 240);  // steps 0..239: before the set_velocity of step 240
    EXPECT_LT(session.world().body(ball).getVelocity().x(), 1.0);
    runSteps(session, 1);
    // 12 m/s set at the start of step 240; one step of sliding friction takes at most
    // mu g dt = 0.6 * 9.81 / 60 = 0.1 m/s of it.
    EXPECT_GT(session.world().body(ball).getVelocity().x(), 11.5);
    EXPECT_TRUE(session.world().contains(stack2));
    runSteps(session, 420 - 241 + 1);  // through step 420, which removes stack2
    EXPECT_FALSE(session.world().contains(stack2));
    EXPECT_EQ(session.lastProblem(), "");
}

TEST(ViewerSession, RestartRebuildsTheSceneAndKeepsTheSolverSettings) {
    Session session(scenePath("pyramid-10"));
    const std::size_t bodies = session.world().bodyCount();
    WorldSettings settings = session.world().settings();
    settings.velocityIterations = 17;
    session.setSettings(settings);
    session.shootBall(Vector3(0, 5, 20), Vector3(0, 0, -1));
    runSteps(session, 10);
    EXPECT_EQ(session.world().bodyCount(), bodies + 1);
    session.restart();
    EXPECT_EQ(session.world().bodyCount(), bodies);
    EXPECT_EQ(session.stepper().totalSteps(), 0u);
    EXPECT_EQ(session.world().settings().velocityIterations, 17);
}

TEST(ViewerSession, AdvanceRunsWholeStepsAndSingleStepExactlyOne) {
    Session session(scenePath("springs"));
    const real dt = session.stepSeconds();
    EXPECT_EQ(session.advance(dt / 2), 0);
    EXPECT_EQ(session.advance(dt / 2 + dt * real(1e-6)), 1);
    EXPECT_EQ(session.advance(real(2.5) * dt), 2);
    const std::uint64_t before = session.stepper().totalSteps();
    session.singleStep();
    EXPECT_EQ(session.stepper().totalSteps(), before + 1);
}

TEST(ViewerSession, TheGrabLiftsABodyAndLetsItFall) {
    const SceneFile file("grab", kBoxOnGround);
    Session session(file.path());
    const BodyId box = bodyNamed(session, "box");

    EXPECT_FALSE(session.grab(Vector3(5, 5, 5), Vector3(0, 1, 0))) << "a ray that meets nothing holds nothing";
    EXPECT_FALSE(session.grab(Vector3(5, 5, 5), Vector3(0, -1, 0))) << "the ground is static: not held";
    ASSERT_TRUE(session.grab(Vector3(0, 5, 0), Vector3(0, -1, 0)));
    EXPECT_EQ(session.grabbed()->body, box);
    EXPECT_NEAR(session.grabbed()->target.y(), 1.0, 1e-9) << "held where the ray met the top face";

    const JointId joint = session.grabbed()->joint;
    ASSERT_TRUE(session.world().contains(joint));
    EXPECT_EQ(session.world().jointSettings(joint).type, JointType::Mouse);

    session.moveGrab(Vector3(0, 3, 0));
    runSteps(session, 180);
    // Hanging from its top face's centre on the grab's pull of 5 Hz (omega = 10 pi rad/s,
    // the stiffness m omega^2): the pull stretches g / omega^2 = 9.9 mm under the weight,
    // so the centre settles at 3 - 0.0099 - 0.5 = 2.4901 m (the oscillation, damped at
    // zeta omega = 22 /s, is gone after 3 s).
    EXPECT_NEAR(session.world().body(box).getPosition().y(), 3 - 9.81 / (100 * kPiSquared) - 0.5, 1e-4);
    EXPECT_NEAR(session.world().body(box).getPosition().x(), 0, 1e-6);

    session.moveGrab(Vector3(0, std::nan(""), 0));  // refused by the World: the target stays
    EXPECT_EQ(session.grabbed()->target, Vector3(0, 3, 0));

    session.release();
    EXPECT_FALSE(session.grabbed().has_value());
    EXPECT_FALSE(session.world().contains(joint));
    runSteps(session, 120);
    EXPECT_NEAR(session.world().body(box).getPosition().y(), 0.5, 0.02) << "fell back to the ground";
}

TEST(ViewerSession, TheRayThroughABoxsPixelGrabsThatBox) {
    // What a click does: the camera's ray through the pixel where a box appears holds it.
    Session session(scenePath("pyramid-20"));
    OrbitCamera camera;
    camera.frame(sceneBounds(session.world()), 1280.0f / 720.0f);
    for (const char *name : {"r19b0", "r0b0", "r7b3"}) {
        const BodyId box = bodyNamed(session, name);
        const std::optional<Eigen::Vector2f> pixel =
            camera.project(session.world().body(box).getPosition().cast<float>(), 1280, 720);
        ASSERT_TRUE(pixel.has_value());
        const Ray ray = camera.ray(pixel->x(), pixel->y(), 1280, 720);
        ASSERT_TRUE(session.grab(ray.origin.cast<real>(), ray.direction.cast<real>())) << name;
        EXPECT_EQ(session.grabbed()->body, box) << name;
    }
}

TEST(ViewerSession, ShootsABallAlongTheGivenDirection) {
    const SceneFile file("shoot", kBoxOnGround);
    Session session(file.path());
    const std::size_t bodies = session.world().bodyCount();
    BallSettings ball;
    session.shootBall(Vector3(0, 2, 10), Vector3(0, 0, -2), ball);
    ASSERT_EQ(session.world().bodyCount(), bodies + 1);
    const BodyId shot = session.world().bodies().back();
    EXPECT_EQ(session.world().shape(shot).type, ShapeType::Sphere);
    EXPECT_NEAR(session.world().body(shot).getVelocity().z(), -ball.speed, 1e-9);
    EXPECT_NEAR(session.world().body(shot).getMass(), ball.mass, 1e-9);
}

TEST(ViewerSession, ColoursFollowTheBodysState) {
    const SceneFile file("states", kBoxOnGround);
    Session session(file.path());
    const BodyId ground = bodyNamed(session, "ground");
    const BodyId box = bodyNamed(session, "box");
    EXPECT_EQ(session.state(ground), BodyState::Static);
    EXPECT_EQ(session.state(box), BodyState::Awake);
    session.world().setAwake(box, false);
    EXPECT_EQ(session.state(box), BodyState::Asleep);
}

// Sensors and kinematic bodies have colours of their own, unlike every other state's.
TEST(ViewerSession, SensorsAndKinematicBodiesHaveTheirOwnColours) {
    Session session(scenePath("trigger-zone"));
    EXPECT_EQ(session.state(bodyNamed(session, "zone")), BodyState::Sensor);
    EXPECT_EQ(session.state(bodyNamed(session, "bird")), BodyState::Kinematic);
    const BodyState states[] = {BodyState::Static, BodyState::Awake, BodyState::Asleep, BodyState::NonFinite,
                                BodyState::Kinematic, BodyState::Sensor};
    for (BodyState x : states)
        for (BodyState y : states) {
            if (x == y) continue;
            const Rgb a = stateColor(x), b = stateColor(y);
            EXPECT_TRUE(a.r != b.r || a.g != b.g || a.b != b.b);
        }
}

TEST(ViewerSession, SpringLinesJoinTheSpringsEnds) {
    Session session(scenePath("springs"));
    const std::vector<Vector3> lines = session.springLines();
    ASSERT_EQ(lines.size(), 4u);  // two springs
    // The first is anchored at the world point (0, 6, 0), from the top of "upper" (0, 4.25, 0).
    EXPECT_TRUE(lines[0].isApprox(Vector3(0, 4.25, 0)));
    EXPECT_TRUE(lines[1].isApprox(Vector3(0, 6, 0)));
}

TEST(ViewerSession, ABadSceneFileIsRefusedWithItsName) {
    const SceneFile file("bad", R"({"bodies": [{"name": "b", "shape": {"type": "box", "half_extents": [1, 1, 1]}, "mass": -1}]})");
    try {
        Session session(file.path());
        FAIL() << "a negative mass was accepted";
    } catch (const scene::SceneError &error) {
        EXPECT_NE(std::string(error.what()).find(file.path()), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("bodies[0] (\"b\").mass"), std::string::npos) << error.what();
    }
}

// The issue's "positon": the viewer warns as the runner does, naming the body, and with
// strict (--strict) refuses the scene at that place.
TEST(ViewerSession, AnUnknownFieldIsWarnedAboutAndRefusedWhenStrict) {
    const SceneFile file("typo", R"({"bodies": [{"name": "crate", "shape": {"type": "box", "half_extents": [1, 1, 1]},
                                    "positon": [0, 3, 0]}]})");
    const Session session(file.path());
    EXPECT_EQ(session.warnings(), file.path() + ": bodies[0] (\"crate\").positon: unknown field; did you mean \"position\"?\n");
    try {
        Session strict(file.path(), true);
        FAIL() << "--strict accepted an unknown field";
    } catch (const scene::SceneError &error) {
        EXPECT_EQ(error.path(), file.path() + ": bodies[0] (\"crate\").positon");
        EXPECT_EQ(error.message(), "unknown field; did you mean \"position\"? (refused by --strict)");
    }
    EXPECT_EQ(Session(scenePath("pyramid-20")).warnings(), "");
}

// F5 keeps the state, F9 rewinds to it: the scene plays again from there, events
// included (step 240's set_velocity, step 420's remove), to the same bits.
TEST(ViewerSession, RewindPlaysTheSceneAgainFromTheKeptState) {
    Session session(scenePath("sleep-wake"));
    const BodyId ball = bodyNamed(session, "ball");
    const BodyId stack2 = bodyNamed(session, "stack2");
    EXPECT_FALSE(session.rewind());
    runSteps(session, 200);
    session.keep();
    runSteps(session, 240);  // through step 439: the ball thrown, stack2 removed
    EXPECT_FALSE(session.world().contains(stack2));
    const Vector3 first = session.world().body(ball).getPosition();
    ASSERT_TRUE(session.rewind());
    EXPECT_EQ(session.sceneStep(), 200);
    EXPECT_TRUE(session.world().contains(stack2));
    EXPECT_LT(session.world().body(ball).getVelocity().x(), 1.0);
    runSteps(session, 240);
    EXPECT_FALSE(session.world().contains(stack2));
    const Vector3 again = session.world().body(ball).getPosition();
    EXPECT_EQ(std::memcmp(first.data(), again.data(), sizeof first), 0);
}

}  // namespace
}  // namespace cyclone::viewer
