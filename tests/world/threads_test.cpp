// Threads share a step's work and change nothing in its results: the same scene with 1,
// 2 or 3 threads gives bit-identical states (docs/solver.md, "Threads"). The scene is
// large enough for the solver to split its passes in two halves (threads/partition.h).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "solver/schedule.h"
#include "solver/carriers.h"
#include "solver/threads/carrier_threads.h"
#include "solver/threads/ordered_shares.h"
#include "world/chunk_lists.h"
#include "world/task_pool.h"
#include "world/workers.h"
#include "world_fixture.h"

namespace cyclone::test {
namespace {

// A world of `threads` threads (the defaults otherwise) on a static floor at y = 0, whose
// id goes first in `ids`.
std::unique_ptr<World> worldOnFloor(int threads, std::vector<BodyId> &ids) {
    WorldSettings settings;
    settings.threads = threads;
    auto world = std::make_unique<World>(settings);
    ids.push_back(addStatic(*world, Shape::plane(Vector3::UnitY(), 0), Vector3::Zero()));
    return world;
}

// A 16-box-wide pyramid (136 boxes, some 270 manifolds), with spheres, capsules and boxes
// thrown onto it with spin and a spring on one of them; sleep on.
struct ThreadedScene {
    std::unique_ptr<World> world;
    std::vector<BodyId> ids;

    explicit ThreadedScene(int threads) {
        world = worldOnFloor(threads, ids);
        constexpr int kBase = 16;
        for (int row = 0; row < kBase; ++row) {
            for (int i = 0; i < kBase - row; ++i) {
                BodySettings box;
                box.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
                box.position = Vector3(-0.5 * (kBase - 1) + 0.5 * row + i + 0.01 * (row % 3), 0.5 + row, 0);
                ids.push_back(world->addBody(box));
            }
        }
        const Shape shapes[] = {Shape::sphere(0.4), Shape::capsule(0.25, 0.6), Shape::box(Vector3(0.4, 0.3, 0.5))};
        for (int i = 0; i < 12; ++i) {
            BodySettings s;
            s.shape = shapes[i % 3];
            s.position = Vector3(-6 + 1.1 * i, 18 + 0.5 * (i % 2), 0.3 * (i % 3) - 0.3);
            s.orientation = Quaternion(1, 0.1 * i, 0.2, -0.05 * i);
            s.velocity = Vector3(0.5, -2, 0.2 * (i % 2));
            s.rotation = Vector3(0.5 * i, -1, 2);
            s.material.restitution = 0.2 * (i % 2);
            ids.push_back(world->addBody(s));
        }
        SpringSettings spring;
        spring.a = ids.back();
        spring.bPoint = Vector3(6, 22, 0);
        spring.restLength = 3;
        spring.stiffness = 40;
        spring.damping = 1;
        world->addSpring(spring);
    }
};

::testing::AssertionResult sameState(const ThreadedScene &x, const ThreadedScene &y) {
    for (std::size_t i = 0; i < x.ids.size(); ++i)
        if (!sameBits(x.world->body(x.ids[i]), y.world->body(y.ids[i])))
            return ::testing::AssertionFailure() << "body " << i << " differs";
    return ::testing::AssertionSuccess();
}

TEST(Threads, OneTwoAndThreeThreadsGiveBitIdenticalStates) {
    ThreadedScene one(1), two(2), three(3);
    int mostManifolds = 0;
    for (int i = 0; i < 240; ++i) {
        one.world->step(kDt);
        two.world->step(kDt);
        three.world->step(kDt);
        ASSERT_TRUE(sameState(one, two)) << "2 threads, after step " << i + 1;
        ASSERT_TRUE(sameState(one, three)) << "3 threads, after step " << i + 1;
        mostManifolds = std::max(mostManifolds, one.world->stats().manifolds);
    }
    // The split is what is compared: it takes 128 manifolds (kMinSplitManifolds).
    EXPECT_GE(mostManifolds, 200);
}

TEST(Threads, ChangingTheCountBetweenStepsChangesNothing) {
    ThreadedScene fixed(1), changed(1);
    const int counts[] = {2, 1, 4, 2};
    for (int i = 0; i < 160; ++i) {
        if (i % 40 == 0) {
            // setSettings wakes every body: the fixed scene gets the same call, with its
            // thread count unchanged, so that only the count differs.
            fixed.world->setSettings(fixed.world->settings());
            WorldSettings settings = changed.world->settings();
            settings.threads = counts[i / 40];
            changed.world->setSettings(settings);
        }
        fixed.world->step(kDt);
        changed.world->step(kDt);
        ASSERT_TRUE(sameState(fixed, changed)) << "after step " << i + 1;
    }
}

TEST(Threads, CountsOutsideOneTo64AreRefused) {
    for (int threads : {0, -1, 65}) {
        WorldSettings settings;
        settings.threads = threads;
        try {
            World world(settings);
            ADD_FAILURE() << "threads = " << threads << " accepted";
        } catch (const InvalidArgument &e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("World::World"), std::string::npos) << message;
            EXPECT_NE(message.find("threads"), std::string::npos) << message;
            EXPECT_NE(message.find(std::to_string(threads)), std::string::npos) << message;
        }
    }
    World world;
    WorldSettings settings;
    settings.threads = 65;
    EXPECT_THROW(world.setSettings(settings), InvalidArgument);
    EXPECT_EQ(world.settings().threads, 1);
}

// The carrier pass's threads: two columns on the floor, one per half, a bridge on both
// columns and a box on the bridge. Each run goes to its carried body's half, level by
// level, and the bridge's run (half 1) must wait for a carrier of half 0.
TEST(CarrierThreads, RunsGoToTheirBodysHalfLevelByLevel) {
    // Solver bodies: 0 the world; 1, 3 the left column; 2, 4 the right; 5 the bridge
    // on 3 and 4; 6 on 5.
    const int pairs[][2] = {{0, 1}, {0, 2}, {1, 3}, {2, 4}, {3, 5}, {4, 5}, {5, 6}};
    detail::SolverManifolds manifolds;
    for (const auto &pair : pairs) {
        detail::SolverManifold m;
        m.a = pair[0];
        m.b = pair[1];
        m.normal = Vector3::UnitY();  // from A up to B: A carries B
        m.tangent[0] = Vector3::UnitX();
        m.tangent[1] = Vector3::UnitZ();
        for (detail::SolverPoint &p : m.points) p.localA = p.localB = Vector3::Zero();
        manifolds.push_back(m);
    }
    detail::CarrierScratch scratch;
    detail::CarrierRuns runs;
    const std::vector<int> order = {0, 1, 2, 3, 4, 5, 6};
    detail::assignCarriers(7, 7, Vector3::UnitY(), manifolds, order, scratch, runs);
    const std::vector<signed char> side = {-1, 0, 1, 0, 1, 1, 0};
    detail::CarrierThreads threads;
    detail::buildCarrierThreads(runs, manifolds, &side, 7, threads);
    // Runs by level: {1, 2}, {3, 4}, {5}, {6}, each body its own run in that order.
    const std::vector<int> expectedRunOf = {-1, 0, 1, 2, 3, 4, 5};
    EXPECT_EQ(threads.runOf, expectedRunOf);
    EXPECT_EQ(threads.runLevel, (std::vector<int>{0, 0, 1, 1, 2, 3}));
    EXPECT_EQ(threads.share[0], (std::vector<int>{0, 2, 5}));  // bodies 1, 3, 6
    EXPECT_EQ(threads.share[1], (std::vector<int>{1, 3, 4}));  // bodies 2, 4, 5

    // Solved on two threads, both threads finish (the waits resolve) in every pass.
    std::vector<detail::SolverBody> bodies(7);
    detail::TaskPool pool(2);
    for (int pass = 0; pass < 100; ++pass) {
        threads.finished.begin();
        pool.run(2, [&](int lane, int) { detail::solveCarrierShare(bodies, manifolds, runs, threads, lane, false); });
        for (int r = 0; r < 6; ++r) ASSERT_TRUE(threads.finished.finished(static_cast<std::size_t>(r))) << "run " << r << ", pass " << pass;
    }

    // Without halves every run is on lane 0, in order.
    detail::buildCarrierThreads(runs, manifolds, nullptr, 7, threads);
    EXPECT_EQ(threads.share[0], (std::vector<int>{0, 1, 2, 3, 4, 5}));
    EXPECT_TRUE(threads.share[1].empty());
}

// A manifold between solver bodies a and b, for the schedule tests.
detail::SolverManifold between(int a, int b) {
    detail::SolverManifold m;
    m.a = a;
    m.b = b;
    return m;
}

// The manifolds of each group, in order.
std::vector<std::vector<int>> members(const std::vector<detail::SolverGroup> &groups) {
    std::vector<std::vector<int>> out;
    for (const detail::SolverGroup &g : groups) out.emplace_back(g.manifold, g.manifold + g.size);
    return out;
}

// Groups by hand: a manifold joins a group only past manifolds it shares no moving body
// with, and the static world (body 0) blocks no one. Scheduled again with other bodies,
// the same scratch gives the new groups. The order comes back as the groups list it.
TEST(SolverSchedule, ManifoldsJoinPastThoseSharingNoMovingBody) {
    detail::SolverManifolds manifolds = {between(1, 2), between(2, 3), between(4, 5), between(1, 6)};
    std::vector<int> order = {0, 1, 2, 3};
    std::vector<detail::SolverGroup> groups;
    detail::ScheduleScratch scratch;
    // 1 shares body 2 with 0; 2 shares none; 3 shares body 1 with 0: {0, 2}. Then 1, and 3
    // past nothing of 1's: {1, 3}.
    detail::buildSchedule(manifolds, order, groups, scratch);
    const std::vector<std::vector<int>> first = {{0, 2}, {1, 3}};
    EXPECT_EQ(members(groups), first);
    EXPECT_EQ(order, (std::vector<int>{0, 2, 1, 3}));
    order = {0, 1, 2, 3};
    detail::buildSchedule(manifolds, order, groups, scratch);
    EXPECT_EQ(members(groups), first);
    // Manifold 2 now touches body 2: it cannot pass 0 or 1, and 3 still passes 1.
    manifolds[2] = between(2, 5);
    order = {0, 1, 2, 3};
    detail::buildSchedule(manifolds, order, groups, scratch);
    EXPECT_EQ(members(groups), (std::vector<std::vector<int>>{{0}, {1, 3}, {2}}));
    EXPECT_EQ(order, (std::vector<int>{0, 1, 3, 2}));
    // The static world (body 0) blocks no one.
    manifolds = {between(0, 1), between(0, 2)};
    order = {0, 1};
    detail::buildSchedule(manifolds, order, groups, scratch);
    EXPECT_EQ(members(groups), (std::vector<std::vector<int>>{{0, 1}}));
}

// The level rule by hand. 0 moves bodies 1, 2 and 1 moves 2, 3 (1 m up); 2 moves 3, 4;
// 3 moves 5, 6 (2 m up). 1 shares body 2 with member 0: it waits. 2 shares body 3 with
// waiting 1: it passes it only when level with it (within kLevelBand), as the plain
// schedule never lets it. 3 shares nothing and joins. The order comes back as the groups
// list it.
TEST(SolverSchedule, AManifoldPassesAWaitingOneItSharesABodyWithOnlyWhenLevel) {
    const detail::SolverManifolds manifolds = {between(1, 2), between(2, 3), between(3, 4), between(5, 6)};
    std::vector<int> order;
    std::vector<detail::SolverGroup> groups;
    detail::ScheduleScratch scratch;
    const auto schedule = [&](real rise) {
        const std::vector<real> heights = {1, 1, 1 + rise, 2};
        order = {0, 1, 2, 3};
        detail::buildLevelSchedule(manifolds, heights, order, groups, scratch);
    };
    schedule(0.5 * detail::kLevelBand);
    EXPECT_EQ(members(groups), (std::vector<std::vector<int>>{{0, 2, 3}, {1}}));
    EXPECT_EQ(order, (std::vector<int>{0, 2, 3, 1}));
    // 2 mm above 1: it waits, and then shares body 3 with member 1.
    schedule(2 * detail::kLevelBand);
    const std::vector<std::vector<int>> plain = {{0, 3}, {1}, {2}};
    EXPECT_EQ(members(groups), plain);
    EXPECT_EQ(order, (std::vector<int>{0, 3, 1, 2}));
    order = {0, 1, 2, 3};
    detail::buildSchedule(manifolds, order, groups, scratch);
    EXPECT_EQ(members(groups), plain);
}

// A pass shared by OrderedShares gives the one-thread numbers. Entries touch two of 300
// bodies (body 0, the immovable world, now and then) and change them in a way whose result
// depends on the order: each body must meet its entries in the list's order.
struct OrderedEntries {
    std::vector<int> a, b;
    std::vector<signed char> side;
    explicit OrderedEntries(std::size_t count) {
        constexpr int kBodies = 300;
        std::uint32_t state = 12345;
        const auto next = [&](int range) {
            state = state * 1664525u + 1013904223u;
            return static_cast<int>((state >> 8) % static_cast<std::uint32_t>(range));
        };
        side.resize(kBodies);
        side[0] = -1;
        for (int k = 1; k < kBodies; ++k)
            side[static_cast<std::size_t>(k)] = static_cast<signed char>(k < kBodies / 2 ? 0 : 1);
        for (std::size_t k = 0; k < count; ++k) {
            // Mostly within a half, as a partition's bodies are; now and then across it.
            const int first = 1 + next(kBodies - 1);
            const bool across = next(8) == 0;
            const int half = side[static_cast<std::size_t>(first)];
            const int low = across ? 1 : (half == 0 ? 1 : kBodies / 2);
            const int high = across ? kBodies : (half == 0 ? kBodies / 2 : kBodies);
            int second = low + next(high - low);
            if (second == first || next(20) == 0) second = 0;
            a.push_back(first);
            b.push_back(second);
        }
    }
    // The entries split between two threads by the bodies' halves.
    detail::OrderedShares shared() const {
        detail::OrderedShares shares;
        detail::buildOrderedShares(
            a.size(), [&](std::size_t k) { return a[k]; }, [&](std::size_t k) { return b[k]; }, side,
            static_cast<int>(side.size()), shares);
        return shares;
    }
    void solve(std::vector<double> &values, int k) const {
        const std::size_t i = static_cast<std::size_t>(a[static_cast<std::size_t>(k)]);
        const std::size_t j = static_cast<std::size_t>(b[static_cast<std::size_t>(k)]);
        const double x = values[i], y = values[j];
        values[i] = 0.75 * x + 0.5 * y + k;
        if (j != 0) values[j] = 0.5 * y - 0.25 * x + 1;
    }
};

TEST(OrderedShares, TwoThreadsGiveTheOneThreadOrdersNumbers) {
    const OrderedEntries entries(4000);
    const std::size_t count = entries.a.size();
    detail::OrderedShares shares = entries.shared();
    std::vector<double> one(300, 1.0), two(300, 1.0);
    detail::TaskPool pool(2);
    for (int pass = 0; pass < 5; ++pass) {
        for (std::size_t k = 0; k < count; ++k) entries.solve(one, static_cast<int>(k));
        shares.finished.begin();
        pool.run(2, [&](int share, int) {
            detail::solveOrderedShare(shares, share, [&](int k) { entries.solve(two, k); });
        });
        for (std::size_t body = 0; body < one.size(); ++body)
            ASSERT_EQ(one[body], two[body]) << "pass " << pass << ", body " << body;
    }
    EXPECT_EQ(shares.share[0].size() + shares.share[1].size(), count);
    EXPECT_FALSE(shares.share[0].empty());
    EXPECT_FALSE(shares.share[1].empty());
}

// What each entry waits for, worked out apart: the last earlier entry touching each of its
// moving bodies when that entry went to the other thread; an entry goes to the thread of
// its first body's half.
TEST(OrderedShares, AnEntryWaitsForTheOtherThreadsLastEntryOnEachOfItsBodies) {
    const OrderedEntries entries(2000);
    const std::size_t count = entries.a.size();
    const detail::OrderedShares shares = entries.shared();
    std::vector<int> shareOf(count, -1);
    for (int s = 0; s < 2; ++s)
        for (int k : shares.share[s]) shareOf[static_cast<std::size_t>(k)] = s;
    int waits = 0;
    for (std::size_t k = 0; k < count; ++k) {
        ASSERT_EQ(shareOf[k], entries.side[static_cast<std::size_t>(entries.a[k])]) << "entry " << k;
        const int bodies[2] = {entries.a[k], entries.b[k]};
        for (int j = 0; j < 2; ++j) {
            int expected = -1;
            if (bodies[j] != 0) {
                for (std::size_t e = k; e-- > 0;) {
                    if (entries.a[e] != bodies[j] && entries.b[e] != bodies[j]) continue;
                    if (shareOf[e] != shareOf[k]) expected = static_cast<int>(e);
                    break;
                }
            }
            EXPECT_EQ(shares.waits[2 * k + static_cast<std::size_t>(j)], expected) << "entry " << k << ", body " << j;
            waits += expected >= 0;
        }
    }
    // Within a share the entries keep the list's order.
    for (const std::vector<int> &share : shares.share) EXPECT_TRUE(std::is_sorted(share.begin(), share.end()));
    EXPECT_GT(waits, 0);
}

// A heap of balls and capsules on a floor: rolling and spinning rows and manifolds without
// a carrier (side by side on the floor) by the hundreds, which two threads share
// (threads/ordered_shares.h): the states stay bit-identical to one thread's.
TEST(Threads, SharedResistanceRowsAndUncarriedManifoldsGiveOneThreadsNumbers) {
    struct Heap {
        std::unique_ptr<World> world;
        std::vector<BodyId> ids;
        explicit Heap(int threads) {
            world = worldOnFloor(threads, ids);
            const Shape shapes[] = {Shape::sphere(0.25), Shape::capsule(0.2, 0.4)};
            for (int i = 0; i < 300; ++i) {
                BodySettings s;
                s.shape = shapes[i % 2];
                s.position = Vector3(-3.8 + 0.55 * (i % 15), 0.3 + 0.6 * (i / 45),
                                     -2.2 + 0.55 * ((i / 15) % 3) + 0.02 * (i % 4));
                s.orientation = Quaternion(1, 0.05 * (i % 5), 0.3, 0.02 * i).normalized();
                s.velocity = Vector3(0.1 * ((i % 3) - 1), -0.5, 0);
                ids.push_back(world->addBody(s));
            }
        }
    };
    Heap one(1), two(2);
    int mostRows = 0, mostManifolds = 0;
    for (int i = 0; i < 150; ++i) {
        one.world->step(kDt);
        two.world->step(kDt);
        for (std::size_t k = 0; k < one.ids.size(); ++k)
            ASSERT_TRUE(sameBits(one.world->body(one.ids[k]), two.world->body(two.ids[k])))
                << "body " << k << ", step " << i + 1;
        mostRows = std::max(mostRows, one.world->stats().resistanceRows);
        mostManifolds = std::max(mostManifolds, one.world->stats().manifolds);
    }
    // Shared only from detail::kMinSharedEntries entries on (rows count up to three each).
    EXPECT_GE(mostRows, 3 * static_cast<int>(detail::kMinSharedEntries));
    EXPECT_GE(mostManifolds, 2 * static_cast<int>(detail::kMinSharedEntries));
}

// The pool itself: every task of a job runs exactly once, whatever the count, and jobs
// run after the workers have gone to sleep.
TEST(TaskPool, RunsEveryTaskOnce) {
    detail::TaskPool pool(3);
    EXPECT_EQ(pool.threads(), 3);
    for (int count : {0, 1, 2, 3, 7, 100, 1000}) {
        std::vector<std::atomic<int>> runs(static_cast<std::size_t>(count));
        for (int job = 0; job < 20; ++job) pool.run(count, [&](int i, int) { runs[static_cast<std::size_t>(i)]++; });
        for (int i = 0; i < count; ++i) EXPECT_EQ(runs[static_cast<std::size_t>(i)].load(), 20) << "task " << i;
    }
}

// A task is told which thread runs it: the caller is thread 0, each worker keeps its own
// number from job to job, and no two threads share one.
TEST(TaskPool, NamesTheThreadThatRunsATask) {
    detail::TaskPool pool(3);
    std::mutex mutex;
    std::map<int, std::set<std::thread::id>> seen;  // thread number -> OS threads seen with it
    const std::thread::id caller = std::this_thread::get_id();
    for (int job = 0; job < 50; ++job) {
        pool.run(64, [&](int, int thread) {
            std::this_thread::sleep_for(std::chrono::microseconds(20));
            std::lock_guard<std::mutex> lock(mutex);
            seen[thread].insert(std::this_thread::get_id());
        });
    }
    std::set<std::thread::id> all;
    for (const auto &[thread, ids] : seen) {
        EXPECT_GE(thread, 0);
        EXPECT_LT(thread, 3);
        EXPECT_EQ(ids.size(), 1u) << "thread " << thread;
        all.insert(ids.begin(), ids.end());
    }
    EXPECT_EQ(all.size(), seen.size());  // one number per OS thread
    ASSERT_TRUE(seen.count(0));
    EXPECT_EQ(*seen[0].begin(), caller);
}

// Chunks on three threads append to their threads' lists; read back chunk by chunk, the
// items come in the one-thread order: chunk c of 64 items [64c, 64c + 64) appends item i
// (i mod 3) times, so the job holds 0 + 1 + 2 of every three items, 1,000 in all.
TEST(ChunkLists, ReadBackInTheChunksOrderWhateverThreadRanThem) {
    detail::Workers workers;
    workers.match(3);
    ASSERT_EQ(workers.threads(), 3);
    constexpr std::size_t kItems = 1000;
    std::vector<int> expected;
    for (int i = 0; i < int(kItems); ++i)
        for (int copy = 0; copy < i % 3; ++copy) expected.push_back(i);
    detail::ChunkLists<int> lists;
    for (int job = 0; job < 20; ++job) {
        const std::size_t chunks = detail::Workers::chunksOf(kItems);
        lists.start(workers.threads(), chunks);
        std::atomic<int> threadsSeen{0};
        workers.forEachChunkOnThreads(kItems, [&](int thread, std::size_t chunk, std::size_t begin, std::size_t end) {
            std::vector<int> &out = lists.open(chunk, thread);
            for (std::size_t i = begin; i < end; ++i)
                for (std::size_t copy = 0; copy < i % 3; ++copy) out.push_back(int(i));
            lists.close(chunk);
            threadsSeen |= 1 << thread;
        });
        lists.finish();
        std::vector<int> read;
        for (std::size_t chunk = 0; chunk < chunks; ++chunk)
            for (int item : lists.items(chunk)) read.push_back(item);
        ASSERT_EQ(read, expected) << "job " << job;
        EXPECT_EQ(threadsSeen.load() & ~7, 0);
    }
}

TEST(TaskPool, RunsJobsAfterTheWorkersBlocked) {
    detail::TaskPool pool(2);
    std::atomic<int> sum{0};
    for (int job = 0; job < 3; ++job) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));  // past the workers' polling time
        pool.run(4, [&](int i, int) { sum += i + 1; });
    }
    EXPECT_EQ(sum.load(), 3 * (1 + 2 + 3 + 4));
}

TEST(TaskPool, OneThreadRunsTasksInOrderOnTheCaller) {
    detail::TaskPool pool(1);
    std::vector<int> order;
    const std::thread::id caller = std::this_thread::get_id();
    bool onCaller = true;
    pool.run(5, [&](int i, int thread) {
        EXPECT_EQ(thread, 0);
        order.push_back(i);
        onCaller = onCaller && std::this_thread::get_id() == caller;
    });
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
    EXPECT_TRUE(onCaller);
}

}  // namespace
}  // namespace cyclone::test
