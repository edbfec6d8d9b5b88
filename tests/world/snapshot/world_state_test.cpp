// World::saveState and World::restoreState: a restored World steps on bit for bit as the
// World that saved did (or one that never saved), in itself or in a second World built by
// the same calls; foreign and damaged states are refused and change nothing; a state takes
// at most 1 KB a body on an awake mixed pile, and a quarter of that for bodies asleep apart.
#include <gtest/gtest.h>

#include <cstring>

#include "cyclone/world.h"
#include "mixed_pile.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

constexpr int kSaveStep = 100;
constexpr int kAfter = 150;

// A mixed pile (every shape pair, contacts and sleep), a chain of three boxes hanging
// from a static beam by hinges and balls (joints), a spring pulling a sphere, and a row
// of boxes added asleep beside the pile that the chain's swing does not reach: joints,
// contacts, sleeping and waking bodies in one World.
struct RollbackScene {
    World world;
    std::vector<BodyId> ids;
    std::vector<JointId> joints;

    explicit RollbackScene(int threads) : world(settingsWith(threads)) {
        ids = addMixedPile(world, 4, 2);
        BodySettings beam;
        beam.motion = Motion::Static;
        beam.shape = Shape::box(Vector3(0.5, 0.1, 0.1));
        beam.position = Vector3(0, 5, 4);
        const BodyId top = world.addBody(beam);
        BodyId previous = top;
        for (int k = 0; k < 3; ++k) {
            BodySettings link;
            link.shape = Shape::box(Vector3(0.1, 0.3, 0.1));
            link.position = Vector3(0.4 * (k + 1), 5, 4);  // level with the beam: the chain swings down
            link.orientation = Quaternion(Eigen::AngleAxis<real>(1.5707963267948966, Vector3::UnitZ()));
            const BodyId id = world.addBody(link);
            JointSettings joint;
            joint.type = k == 0 ? JointType::Hinge : JointType::Ball;
            joint.a = previous == top ? id : previous;
            joint.b = previous == top ? top : id;
            joint.anchor = Vector3(0.4 * k + 0.2, 5, 4);
            joint.axis = Vector3::UnitZ();
            joints.push_back(world.addJoint(joint));
            ids.push_back(id);
            previous = id;
        }
        BodySettings ball;
        ball.shape = Shape::sphere(0.2);
        ball.position = Vector3(-3, 3, 4);
        const BodyId ballId = world.addBody(ball);
        ids.push_back(ballId);
        SpringSettings spring;
        spring.a = ballId;
        spring.bPoint = Vector3(-3, 5, 4);
        spring.stiffness = 40;
        spring.restLength = 1;
        world.addSpring(spring);
        for (int k = 0; k < 4; ++k) {
            BodySettings sleeper;
            sleeper.shape = Shape::box(Vector3(0.2, 0.2, 0.2));
            sleeper.position = Vector3(-3 + 0.5 * k, 0.2, -4);
            sleeper.awake = false;
            ids.push_back(world.addBody(sleeper));
        }
    }

    static WorldSettings settingsWith(int threads) {
        WorldSettings s;
        s.threads = threads;
        return s;
    }

    void run(int steps) {
        for (int i = 0; i < steps; ++i) world.step(kDt);
    }
};

// Every dynamic quantity of the listed bodies, as bits.
std::vector<std::uint8_t> stateBits(const World &world, const std::vector<BodyId> &ids) {
    std::vector<std::uint8_t> bits;
    const auto add = [&](const real *data, int n) {
        const auto *b = reinterpret_cast<const std::uint8_t *>(data);
        bits.insert(bits.end(), b, b + n * sizeof(real));
    };
    for (BodyId id : ids) {
        const RigidBody &b = world.body(id);
        const Vector3 p = b.getPosition(), v = b.getVelocity(), w = b.getRotation();
        const Quaternion q = b.getOrientation();
        add(p.data(), 3);
        add(v.data(), 3);
        add(w.data(), 3);
        add(q.coeffs().data(), 4);
        bits.push_back(b.getAwake());
    }
    return bits;
}

// The states after each of `steps` steps.
std::vector<std::vector<std::uint8_t>> trajectory(RollbackScene &scene, int steps) {
    std::vector<std::vector<std::uint8_t>> states;
    for (int i = 0; i < steps; ++i) {
        scene.world.step(kDt);
        states.push_back(stateBits(scene.world, scene.ids));
    }
    return states;
}

::testing::AssertionResult sameTrajectory(const std::vector<std::vector<std::uint8_t>> &got,
                                          const std::vector<std::vector<std::uint8_t>> &expected) {
    if (got.size() != expected.size()) return ::testing::AssertionFailure() << "lengths differ";
    for (std::size_t i = 0; i < got.size(); ++i)
        if (got[i] != expected[i]) return ::testing::AssertionFailure() << "differs after step " << i + 1 << " of the run on";
    return ::testing::AssertionSuccess();
}

class WorldState : public ::testing::TestWithParam<int> {
protected:
    // The run of a World that never saves: steps kSaveStep + 1 to kSaveStep + kAfter.
    std::vector<std::vector<std::uint8_t>> reference() {
        RollbackScene scene(GetParam());
        scene.run(kSaveStep);
        return trajectory(scene, kAfter);
    }
};

TEST_P(WorldState, RestoredRunIsBitIdenticalToOneThatNeverSaved) {
    const auto expected = reference();
    RollbackScene scene(GetParam());
    scene.run(kSaveStep);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    // Saving changes nothing.
    ASSERT_TRUE(sameTrajectory(trajectory(scene, kAfter), expected));
    scene.world.restoreState(state);
    ASSERT_TRUE(sameTrajectory(trajectory(scene, kAfter), expected));
    // The scene has what the state must carry at the save: joints, contacts, sleepers.
    RollbackScene probe(GetParam());
    probe.run(kSaveStep);
    EXPECT_GT(probe.world.stats().contacts, 20);
    int asleep = 0;
    for (BodyId id : probe.ids) asleep += !probe.world.body(id).getAwake();
    EXPECT_GT(asleep, 0);
    EXPECT_TRUE(probe.world.contains(probe.joints[2]));
}

TEST_P(WorldState, SecondWorldBuiltTheSameWayRunsOnTheSame) {
    const auto expected = reference();
    RollbackScene first(GetParam());
    first.run(kSaveStep);
    const std::vector<std::uint8_t> state = first.world.saveState();
    RollbackScene second(GetParam());  // built by the same calls, never stepped
    second.world.restoreState(state);
    ASSERT_TRUE(sameTrajectory(trajectory(second, kAfter), expected));
}

TEST_P(WorldState, BodyAddedAfterTheSaveIsGoneAndRemovedOneIsBack) {
    const auto expected = reference();
    RollbackScene scene(GetParam());
    scene.run(kSaveStep);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    BodySettings falling;
    falling.shape = Shape::box(Vector3(0.3, 0.3, 0.3));
    falling.position = Vector3(0, 4, 0);
    const BodyId added = scene.world.addBody(falling);
    const BodyId removed = scene.ids[3];
    scene.world.removeBody(removed);
    scene.world.removeJoint(scene.joints[1]);
    scene.run(40);
    scene.world.restoreState(state);
    EXPECT_FALSE(scene.world.contains(added));
    EXPECT_TRUE(scene.world.contains(removed));
    EXPECT_TRUE(scene.world.contains(scene.joints[1]));
    EXPECT_EQ(scene.world.bodyCount(), scene.ids.size() + 6);  // the plane, four walls and the beam
    ASSERT_TRUE(sameTrajectory(trajectory(scene, kAfter), expected));
}

// A body given options after it was added (no gravity, a user value), removed after the
// save and its slot taken by a new body: it comes back with them. Without gravity it rises after the restore as it did in
// the run that never saved (with gravity it would fall from the first step on).
TEST_P(WorldState, RemovedBodyComesBackWithItsOptions) {
    const auto withOptions = [](RollbackScene &scene) {
        scene.world.setGravityScale(scene.ids[3], 0);
        scene.world.setUserData(scene.ids[3], 42);
        scene.world.setVelocity(scene.ids[3], Vector3(0, 0.5, 0));
    };
    RollbackScene reference(GetParam());
    reference.run(kSaveStep);
    withOptions(reference);
    const auto expected = trajectory(reference, kAfter);

    RollbackScene scene(GetParam());
    scene.run(kSaveStep);
    withOptions(scene);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    scene.world.removeBody(scene.ids[3]);
    BodySettings box;  // takes the removed body's slot, with the default options
    box.shape = Shape::box(Vector3(0.2, 0.2, 0.2));
    box.position = Vector3(0, 4, 0);
    const BodyId added = scene.world.addBody(box);
    ASSERT_EQ(added.index, scene.ids[3].index);
    scene.run(10);
    scene.world.restoreState(state);
    EXPECT_EQ(scene.world.userData(scene.ids[3]), 42u);
    ASSERT_TRUE(sameTrajectory(trajectory(scene, kAfter), expected));
}

// Axes locked on the pile's bodies after step 100: their slots keep the Jacobians made
// without the locks (a slot holds while its bodies hardly move), which the state cannot
// make again from the bodies as they are (a locked body's solver inverse inertia is zero
// about its locked axes). Those slots are stored whole (1280 bytes of rows and couplings
// each at least, where a slot made again takes under 200), and the run goes on as the one
// that never saved.
TEST_P(WorldState, SlotsThatCannotBeMadeAgainAreStoredWhole) {
    LockedAxes turnless;
    turnless.rx = turnless.ry = turnless.rz = true;
    const auto lockPile = [&](RollbackScene &scene) {
        for (int k = 0; k < 32; ++k) scene.world.setLockedAxes(scene.ids[k], turnless);
    };
    RollbackScene reference(GetParam());
    reference.run(kSaveStep);
    const std::size_t unlockedBytes = reference.world.saveState().size();
    lockPile(reference);
    const auto expected = trajectory(reference, kAfter);

    RollbackScene scene(GetParam());
    scene.run(kSaveStep);
    lockPile(scene);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    // The locked bodies' options take 32 x 70 bytes more (gravity scale, locks, surface
    // velocity, one-way direction, user data: 8 + 6 + 24 + 24 + 8); beyond them, at least
    // two slots stored whole.
    EXPECT_GT(state.size(), unlockedBytes + 32 * 70 + 2 * 1280);
    scene.run(40);
    scene.world.restoreState(state);
    ASSERT_TRUE(sameTrajectory(trajectory(scene, kAfter), expected));
}

// A World built by other calls (another shape) refuses the state and is unchanged.
TEST_P(WorldState, ForeignStateIsRefusedAndChangesNothing) {
    RollbackScene scene(GetParam());
    scene.run(kSaveStep);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    World other(RollbackScene::settingsWith(GetParam()));
    addMixedPile(other, 3, 2);
    other.step(kDt);
    const std::vector<std::uint8_t> before = other.saveState();
    EXPECT_THROW(other.restoreState(state), InvalidArgument);
    EXPECT_EQ(other.saveState(), before);
    try {
        other.restoreState(state);
    } catch (const InvalidArgument &e) {
        EXPECT_EQ(e.function(), "World::restoreState");
        EXPECT_EQ(e.field(), "state");
    }
}

// A flipped byte anywhere (header or payload) or a cut-short state is refused, and the
// World is unchanged.
TEST_P(WorldState, DamagedStateIsRefusedAndChangesNothing) {
    RollbackScene scene(GetParam());
    scene.run(kSaveStep);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    scene.run(10);
    const std::vector<std::uint8_t> before = scene.world.saveState();
    for (std::size_t at : {std::size_t(2), std::size_t(20), state.size() / 2, state.size() - 1}) {
        std::vector<std::uint8_t> damaged = state;
        damaged[at] ^= 0x10;
        EXPECT_THROW(scene.world.restoreState(damaged), InvalidArgument) << "byte " << at;
    }
    std::vector<std::uint8_t> cut(state.begin(), state.end() - 8);
    EXPECT_THROW(scene.world.restoreState(cut), InvalidArgument);
    EXPECT_THROW(scene.world.restoreState({}), InvalidArgument);
    EXPECT_EQ(scene.world.saveState(), before);
}

// A character walking at 1.5 m/s into a crate 2 m ahead, which it pushes: the state holds
// the character's feet, velocities, pushes and ground. Restored, it walks on bit for bit
// as the World that never saved; one added after the save is gone and the one removed is
// back with its handle. (Without the characters in the state, the restored character
// stood where the run after the save had left it: the first step after the restore
// differed.)
struct WalkScene {
    World world;
    CharacterId walker;
    BodyId crate;

    explicit WalkScene(int threads) : world(RollbackScene::settingsWith(threads)) {
        BodySettings floor;
        floor.motion = Motion::Static;
        floor.shape = Shape::box(Vector3(20, 0.5, 20));
        floor.position = Vector3(0, -0.5, 0);
        world.addBody(floor);
        BodySettings box;
        box.shape = Shape::box(Vector3(0.3, 0.3, 0.3));
        box.mass = 5;
        box.position = Vector3(2, 0.3, 0);
        crate = world.addBody(box);
        walker = world.addCharacter(CharacterSettings{});
        world.setCharacterVelocity(walker, Vector3(1.5, 0, 0));
    }

    std::vector<std::vector<std::uint8_t>> walk(int steps) {
        std::vector<std::vector<std::uint8_t>> states;
        for (int i = 0; i < steps; ++i) {
            world.step(kDt);
            const CharacterState c = world.character(walker);
            std::vector<std::uint8_t> bits = stateBits(world, {crate, c.body});
            const auto *p = reinterpret_cast<const std::uint8_t *>(c.position.data());
            const auto *v = reinterpret_cast<const std::uint8_t *>(c.velocity.data());
            bits.insert(bits.end(), p, p + 3 * sizeof(real));
            bits.insert(bits.end(), v, v + 3 * sizeof(real));
            bits.push_back(c.onGround);
            states.push_back(bits);
        }
        return states;
    }
};

TEST_P(WorldState, CharactersWalkOnFromWhereTheyWere) {
    WalkScene reference(GetParam());
    reference.walk(40);
    const auto expected = reference.walk(80);
    EXPECT_GT(reference.world.body(reference.crate).getPosition().x(), 2.01);  // it was pushed

    WalkScene scene(GetParam());
    scene.walk(40);
    const std::vector<std::uint8_t> state = scene.world.saveState();
    const CharacterId added = scene.world.addCharacter(CharacterSettings{Vector3(-3, 0, 0)});
    scene.world.removeCharacter(scene.walker);
    for (int i = 0; i < 30; ++i) scene.world.step(kDt);
    scene.world.restoreState(state);
    EXPECT_THROW(scene.world.character(added), InvalidArgument);
    EXPECT_NO_THROW(scene.world.character(scene.walker));
    ASSERT_TRUE(sameTrajectory(scene.walk(80), expected));
}

INSTANTIATE_TEST_SUITE_P(Threads, WorldState, ::testing::Values(1, 2));

// --- What a state costs in bytes (docs/rollback.md, "What a state holds") ---------------

// A 6 x 6 x 4 mixed pile one second after it was dropped (its top layer from 3.6 m falls
// for 0.86 s, sqrt(2 * 3.6 / 9.81)): landing, tumbling and stacking, its bodies awake,
// every kind of shape pair touching. Per body the state must hold its pose, velocities
// and broadphase box (7 + 6 + 6 reals, 152 bytes); per manifold its normals, friction
// impulses and up to four points with two anchors, a depth and an impulse each (10 + 4 x
// 8 reals, 336 bytes), and per solver slot what its Jacobians were made from (two
// stamped poses and a normal, 17 reals, 136 bytes). A pile has about one manifold and one
// slot per body (each joins two bodies, each body touches about two others): some 620
// bytes a body at the most, when no field is left out, within the 1 KB a body that
// rollback asks for.
TEST(StateSize, AwakeMixedPileTakesAtMostOneKilobyteABody) {
    World world;
    const std::vector<BodyId> ids = addMixedPile(world, 6, 4);
    for (int i = 0; i < 60; ++i) world.step(kDt);
    ASSERT_GT(world.stats().awakeBodies, static_cast<int>(ids.size()) * 9 / 10);
    ASSERT_GT(world.stats().manifolds, static_cast<int>(ids.size()) / 2);
    const std::vector<std::uint8_t> state = world.saveState();
    EXPECT_LE(state.size(), 1024 * world.bodyCount());
}

// 100 boxes put to sleep 1 m apart on a plane: each holds its pose and box (13 reals, 104
// bytes), its sleep average (8 bytes) and some 40 bytes of flags, indices and its
// broadphase node. Nothing derived from its pose (transform, world inertia, the boxes of
// the tree's inner nodes) and no contact: at most a quarter of the awake budget.
TEST(StateSize, BodiesAsleepApartTakeAQuarterOfThat) {
    World world;
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    world.addBody(ground);
    for (int k = 0; k < 100; ++k) {
        BodySettings box;
        box.shape = Shape::box(Vector3(0.2, 0.2, 0.2));
        box.position = Vector3(k % 10, 0.2, k / 10);
        box.awake = false;
        world.addBody(box);
    }
    world.step(kDt);
    ASSERT_EQ(world.stats().awakeBodies, 0);
    const std::vector<std::uint8_t> state = world.saveState();
    EXPECT_LE(state.size(), 256 * world.bodyCount());
}


}  // namespace
}  // namespace cyclone::test
