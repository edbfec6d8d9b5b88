// The broadphase and narrowphase stages share their per-body and per-pair work between the
// step's threads (box placing, slot checks, the merge of fresh manifolds, wake flags, the
// search for separated pairs) and keep every list in the bodies' or pairs' order: a scene
// that goes through each of them gives bit-identical states, counters and events with 1,
// 2 and 3 threads.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

// 64 boxes and 64 compounds (a box with a sphere at each end) dropped onto a plane in two
// grids, so that more than one chunk (Workers::kChunk = 64) of bodies and of pairs is
// shared out; a kinematic box sliding through a row of static posts (pairs of two
// immovable bodies, skipped); a chain of six boxes joined without collideConnected
// (contacts excluded); sleep on. At step 240 a heavy ball is thrown into the settled
// compounds: it wakes them and knocks pairs apart.
struct ContactStageScene {
    std::unique_ptr<World> world;
    std::vector<BodyId> ids;

    explicit ContactStageScene(int threads) {
        WorldSettings settings;
        settings.threads = threads;
        world = std::make_unique<World>(settings);
        BodySettings ground;
        ground.motion = Motion::Static;
        ground.shape = Shape::plane(Vector3::UnitY(), 0);
        world->addBody(ground);
        const Shape dumbbell = Shape::compound({{Shape::box(Vector3(0.3, 0.15, 0.15)), Vector3::Zero()},
                                                {Shape::sphere(0.2), Vector3(-0.35, 0, 0)},
                                                {Shape::sphere(0.2), Vector3(0.35, 0, 0)}});
        for (int i = 0; i < 64; ++i) {
            BodySettings box;
            box.shape = Shape::box(Vector3(0.25, 0.25, 0.25));
            box.position = Vector3(-8 + 0.55 * (i % 8), 0.3 + 0.6 * (i / 8), 0.01 * (i % 3));
            box.orientation = Quaternion(1, 0.02 * (i % 5), 0.01 * i, 0);
            ids.push_back(world->addBody(box));
            BodySettings compound;
            compound.shape = dumbbell;
            compound.position = Vector3(2 + 1.1 * (i % 8), 0.25 + 0.5 * (i / 8), 0.6 * (i % 2));
            compound.orientation = Quaternion(1, 0, 0.05 * (i % 7), 0.02 * (i % 3));
            ids.push_back(world->addBody(compound));
        }
        for (int i = 0; i < 6; ++i) {
            BodySettings post;
            post.motion = Motion::Static;
            post.shape = Shape::box(Vector3(0.2, 0.5, 0.2));
            post.position = Vector3(-4 + 1.5 * i, 0.5, -6);
            world->addBody(post);
        }
        BodySettings slider;
        slider.motion = Motion::Kinematic;
        slider.shape = Shape::box(Vector3(0.5, 0.3, 0.5));
        slider.position = Vector3(-6, 0.6, -6);
        slider.velocity = Vector3(2, 0, 0);
        ids.push_back(world->addBody(slider));
        BodyId previous;
        for (int i = 0; i < 6; ++i) {
            BodySettings link;
            link.shape = Shape::box(Vector3(0.3, 0.1, 0.1));
            link.position = Vector3(-3 + 0.55 * i, 3, 5);
            const BodyId id = world->addBody(link);
            ids.push_back(id);
            if (i > 0) {
                JointSettings joint;
                joint.a = previous;
                joint.b = id;
                joint.anchor = Vector3(-3 + 0.55 * i - 0.275, 3, 5);
                world->addJoint(joint);
            }
            previous = id;
        }
    }

    void throwBall() {
        BodySettings ball;
        ball.shape = Shape::sphere(0.4);
        ball.mass = 50;
        ball.position = Vector3(0, 1, 0.3);
        ball.velocity = Vector3(12, 1, 0);
        ids.push_back(world->addBody(ball));
    }
};

::testing::AssertionResult sameEvents(const WorldEvents &x, const WorldEvents &y) {
    if (x.contactBegins.size() != y.contactBegins.size() || x.contactEnds.size() != y.contactEnds.size() ||
        x.wokeUp.size() != y.wokeUp.size() || x.fellAsleep.size() != y.fellAsleep.size())
        return ::testing::AssertionFailure() << "event counts differ";
    for (std::size_t i = 0; i < x.contactBegins.size(); ++i)
        if (x.contactBegins[i].a != y.contactBegins[i].a || x.contactBegins[i].b != y.contactBegins[i].b ||
            x.contactBegins[i].depth != y.contactBegins[i].depth)
            return ::testing::AssertionFailure() << "contact begin " << i << " differs";
    for (std::size_t i = 0; i < x.contactEnds.size(); ++i)
        if (x.contactEnds[i].a != y.contactEnds[i].a || x.contactEnds[i].b != y.contactEnds[i].b)
            return ::testing::AssertionFailure() << "contact end " << i << " differs";
    for (std::size_t i = 0; i < x.wokeUp.size(); ++i)
        if (x.wokeUp[i] != y.wokeUp[i]) return ::testing::AssertionFailure() << "woken body " << i << " differs";
    return ::testing::AssertionSuccess();
}

TEST(ContactStageThreads, BroadphaseAndNarrowphaseGiveTheSameStepOnOneTwoAndThreeThreads) {
    ContactStageScene one(1), two(2), three(3);
    int mostTested = 0, mostSkipped = 0, ends = 0, woken = 0;
    for (int step = 0; step < 330; ++step) {
        if (step == 240) {
            one.throwBall();
            two.throwBall();
            three.throwBall();
        }
        one.world->step(kDt);
        two.world->step(kDt);
        three.world->step(kDt);
        const StepStats &s1 = one.world->stats();
        for (const ContactStageScene *other : {&two, &three}) {
            const StepStats &s = other->world->stats();
            ASSERT_EQ(s1.broadphasePairs, s.broadphasePairs) << "step " << step;
            ASSERT_EQ(s1.pairsTested, s.pairsTested) << "step " << step;
            ASSERT_EQ(s1.pairsReused, s.pairsReused) << "step " << step;
            ASSERT_EQ(s1.immovablePairsSkipped, s.immovablePairsSkipped) << "step " << step;
            ASSERT_EQ(s1.contacts, s.contacts) << "step " << step;
            ASSERT_TRUE(sameEvents(one.world->events(), other->world->events())) << "step " << step;
            for (std::size_t i = 0; i < one.ids.size(); ++i)
                ASSERT_TRUE(sameBits(one.world->body(one.ids[i]), other->world->body(other->ids[i])))
                    << "body " << i << ", step " << step;
        }
        mostTested = std::max(mostTested, s1.pairsTested);
        mostSkipped = std::max(mostSkipped, s1.immovablePairsSkipped);
        ends += static_cast<int>(one.world->events().contactEnds.size());
        if (step >= 240) woken += static_cast<int>(one.world->events().wokeUp.size());
    }
    // Each shared path was taken: more than one chunk of pairs merged in a step, the
    // slider met the posts, pairs separated, and the ball woke sleeping bodies.
    EXPECT_GT(mostTested, 64);
    EXPECT_GT(mostSkipped, 0);
    EXPECT_GT(ends, 0);
    EXPECT_GT(woken, 0);
}

// StageTimes::shared counts the jobs of more than one share. A lone body falling in empty
// space makes none: its per-body work fits one chunk of 64, which the stepping thread runs
// alone, and without contacts the solver hands out nothing, so shared is exactly zero;
// 128 boxes make two chunks of bodies to place, so it is positive, and it is part of the
// step (<= total).
TEST(ContactStageThreads, SharedTimeCountsOnlyWorkHandedOutInShares) {
    World lone;
    BodySettings box;
    box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    box.position = Vector3(0, 10, 0);
    lone.addBody(box);
    BodySettings ground;
    ground.motion = Motion::Static;
    ground.shape = Shape::plane(Vector3::UnitY(), 0);
    for (int i = 0; i < 10; ++i) {
        lone.step(kDt);
        EXPECT_EQ(lone.stats().ms.shared, 0.0) << "step " << i;
    }
    World many;
    many.addBody(ground);
    for (int i = 0; i < 128; ++i) {
        box.position = Vector3(1.5 * (i % 16), 0.5, 1.5 * (i / 16));
        many.addBody(box);
    }
    many.step(kDt);
    EXPECT_GT(many.stats().ms.shared, 0.0);
    EXPECT_LE(many.stats().ms.shared, many.stats().ms.total);
}

}  // namespace
}  // namespace cyclone::test
