// Collision layers and masks: two bodies touch only when each one's mask holds the other's
// layer; filtered pairs never reach the narrowphase; queries take a layer mask.
#include "world_fixture.h"

namespace cyclone::test {
namespace {

BodySettings layeredBox(const Vector3 &position, int layer, std::uint32_t mask) {
    BodySettings s;
    s.shape = Shape::box(Vector3(0.5, 0.5, 0.5));
    s.position = position;
    s.layer = layer;
    s.collidesWith = mask;
    return s;
}

// A box on layer 1 that does not collide with layer 0 falls through a layer-0 box resting
// on the ground: after 1 s of free fall from 3 m it is below where the other stands.
TEST(CollisionFilter, ABodyFallsThroughALayerItIgnores) {
    WorldFixture f;
    f.ground();
    const BodyId lower = f.box(Vector3(0, 0.5, 0));
    BodySettings ghost = layeredBox(Vector3(0, 3, 0), 1, 1u << 1);
    ghost.shape = Shape::sphere(0.25);
    const BodyId falling = f.world.addBody(ghost);  // the ground is on layer 0 too: it falls through it
    f.simulate(1.0);
    EXPECT_NEAR(f.position(falling).y(), 3 - 0.5 * 9.81 * 1.0, 0.1) << "free fall through both";
    EXPECT_NEAR(f.position(lower).y(), 0.5, 0.01);
    EXPECT_GE(f.world.stats().filteredPairs, 1);
}

// One-sided masks do not collide: a's mask holds b's layer but b's does not hold a's.
TEST(CollisionFilter, BothMasksMustHoldTheOthersLayer) {
    WorldFixture f(noSleep());
    const BodyId a = f.world.addBody(layeredBox(Vector3(0, 0, 0), 2, kAllLayers));
    const BodyId b = f.world.addBody(layeredBox(Vector3(0.8, 0, 0), 3, ~(1u << 2)));
    f.world.setSettings([] { WorldSettings w = noSleep(); w.gravity = Vector3::Zero(); return w; }());
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().filteredPairs, 1);
    EXPECT_EQ(f.world.stats().pairsTested, 0);
    f.world.setCollisionFilter(b, 3, kAllLayers);
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().filteredPairs, 0);
    EXPECT_EQ(f.world.stats().pairsTested, 1);
    EXPECT_EQ(f.world.events().contactBegins.size(), 1u);
    f.world.setCollisionFilter(a, 2, 0);
    f.world.step(kDt);
    EXPECT_EQ(f.world.events().contactEnds.size(), 1u) << "the forbidden contact ends at once";
    EXPECT_EQ(f.world.stats().contacts, 0);
}

TEST(CollisionFilter, QueriesTakeALayerMask) {
    WorldFixture f;
    f.world.addBody(layeredBox(Vector3(0, 0, 5), 4, kAllLayers));
    const BodyId far = f.world.addBody(layeredBox(Vector3(0, 0, 10), 0, kAllLayers));
    QueryFilter filter;
    filter.layers = ~(1u << 4);
    const auto hit = f.world.rayCast(Vector3::Zero(), Vector3::UnitZ(), 100, filter);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, far);
    EXPECT_NEAR(hit->distance, 9.5, 1e-9);
    std::vector<BodyId> out;
    EXPECT_EQ(f.world.overlap(Shape::sphere(1), Vector3(0, 0, 5), Quaternion::Identity(), out, filter), 0u);
}

TEST(CollisionFilter, LayerOutsideTheRangeIsRefused) {
    WorldFixture f;
    try {
        f.world.addBody(layeredBox(Vector3::Zero(), 32, kAllLayers));
        FAIL();
    } catch (const InvalidArgument &e) {
        EXPECT_NE(std::string(e.what()).find("World::addBody"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("layer"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("32"), std::string::npos);
    }
    const BodyId box = f.box(Vector3::Zero());
    EXPECT_THROW(f.world.setCollisionFilter(box, -1, kAllLayers), InvalidArgument);
    EXPECT_EQ(f.world.bodyCount(), 1u);
}

// Two boxes kept apart pass through each other: in zero gravity box b slides at 1 m/s
// into box a for 2.4 s, from x = 3 to x = 3 - 2.4 = 0.6 (constant velocity, exact to
// rounding), while a stays at rest. Allowed to collide again, they are pushed apart until
// their centres are a box width (1 m) apart, less the slop the solver leaves.
TEST(PairCollision, BoxesKeptApartPassThroughAndSeparateWhenAllowedAgain) {
    WorldSettings settings = noSleep();
    settings.gravity = Vector3::Zero();
    WorldFixture f(settings);
    const BodyId a = f.box(Vector3(0, 0, 0));
    const BodyId b = f.box(Vector3(3, 0, 0));
    f.world.setPairCollision(a, b, false);
    EXPECT_FALSE(f.world.pairCollision(b, a));
    f.world.setVelocity(b, Vector3(-1, 0, 0));
    for (int step = 0; step < 144; ++step) {
        f.world.step(kDt);
        EXPECT_EQ(f.world.stats().pairsTested, 0);
        EXPECT_EQ(f.world.stats().broadphasePairs, 0) << "filtered in the broadphase, never a candidate";
    }
    EXPECT_EQ(f.world.stats().filteredPairs, 1);
    EXPECT_NEAR(f.position(b).x(), 0.6, 1e-9);
    EXPECT_EQ(f.position(a), Vector3::Zero());
    EXPECT_EQ(f.world.body(a).getVelocity(), Vector3::Zero());

    f.world.setVelocity(b, Vector3::Zero());
    f.world.setPairCollision(a, b, true);
    EXPECT_TRUE(f.world.pairCollision(a, b));
    f.world.step(kDt);
    EXPECT_EQ(f.world.stats().filteredPairs, 0);
    EXPECT_EQ(f.world.events().contactBegins.size(), 1u);
    f.simulate(2);
    EXPECT_GT(f.position(b).x() - f.position(a).x(), 1 - 0.01);
}

// A box asleep on another: keeping the pair apart ends their contact at once and wakes the
// upper box, which falls through the lower one onto the ground (centre at its half
// height, 0.5 m, where the lower one is).
TEST(PairCollision, KeepingApartEndsTheContactAndWakesWhatRestedOnIt) {
    WorldFixture f;
    f.ground();
    const BodyId lower = f.box(Vector3(0, 0.5, 0));
    const BodyId upper = f.box(Vector3(0, 1.5, 0));
    f.simulate(3);
    ASSERT_FALSE(f.awake(upper));
    f.world.setPairCollision(lower, upper, false);
    EXPECT_TRUE(f.awake(upper));
    f.world.step(kDt);
    ASSERT_EQ(f.world.events().contactEnds.size(), 1u);
    EXPECT_EQ(f.world.events().contactEnds[0].a, lower);
    EXPECT_EQ(f.world.events().contactEnds[0].b, upper);
    f.simulate(3);
    EXPECT_NEAR(f.position(upper).y(), 0.5, 0.01);
    EXPECT_NEAR(f.position(lower).y(), 0.5, 0.01);
}

// Removing a body drops its rules: a body that takes the slot later collides as usual.
TEST(PairCollision, RulesGoWithTheirBodies) {
    WorldFixture f;
    const BodyId a = f.box(Vector3(0, 0, 0));
    const BodyId b = f.box(Vector3(5, 0, 0));
    f.world.setPairCollision(a, b, false);
    f.world.removeBody(b);
    const BodyId c = f.box(Vector3(5, 0, 0));
    ASSERT_EQ(c.index, b.index);
    EXPECT_TRUE(f.world.pairCollision(a, c));
}

TEST(PairCollision, BadIdsAreRefused) {
    WorldFixture f;
    const BodyId a = f.box(Vector3(0, 0, 0));
    const BodyId b = f.box(Vector3(5, 0, 0));
    const auto refused = [&](BodyId x, BodyId y, const char *field) {
        try {
            f.world.setPairCollision(x, y, false);
            ADD_FAILURE() << field;
        } catch (const InvalidArgument &e) {
            EXPECT_NE(std::string(e.what()).find("World::setPairCollision"), std::string::npos);
            EXPECT_EQ(e.field(), field);
        }
    };
    refused(a, a, "b");
    refused(BodyId(), b, "a");
    refused(a, BodyId{b.index, b.generation + 1}, "b");
    EXPECT_TRUE(f.world.pairCollision(a, b)) << "nothing changed";
    EXPECT_THROW(f.world.pairCollision(a, BodyId()), InvalidArgument);
}

}  // namespace
}  // namespace cyclone::test
