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

}  // namespace
}  // namespace cyclone::test
