// Bodies added with one description share its compiled shape: the 200th rock of a pile
// costs what the 200th ball costs, not another hull (its FCL geometry, corners, faces and
// edges).
#include <gtest/gtest.h>

#include "collision/collision_shape.h"
#include "counting_allocator.h"
#include "cyclone/world/world.h"

namespace cyclone::test {
namespace {

Shape rock() {
    return Shape::convex({Vector3(0.3, 0, 0), Vector3(-0.28, 0.05, 0.02), Vector3(0, 0.27, 0.03),
                          Vector3(0.02, -0.3, -0.01), Vector3(0.01, 0.02, 0.29), Vector3(-0.03, 0, -0.31),
                          Vector3(0.18, 0.18, 0.16), Vector3(-0.17, -0.17, 0.17), Vector3(0.17, -0.18, -0.16),
                          Vector3(-0.18, 0.17, -0.17)});
}

// Bytes each of `count` more bodies of `shape` adds to a World that already has one,
// the bodies 2 m apart in a row (no pairs).
long bytesPerBody(const Shape &shape, int count) {
    World world;
    BodySettings body;
    body.shape = shape;
    body.awake = false;
    world.addBody(body);
    const long before = liveBytes();
    for (int i = 1; i <= count; ++i) {
        body.position = Vector3(2.0 * i, 0, 0);
        world.addBody(body);
    }
    return (liveBytes() - before) / count;
}

TEST(SharedShapes, TheTwoHundredthRockCostsWhatABallCosts) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    const long start = liveBytes();
    const auto compiled = detail::compileShape(rock());
    const long hull = liveBytes() - start;
    const long rocks = bytesPerBody(rock(), 200);
    const long balls = bytesPerBody(Shape::sphere(0.3), 200);
    // Compiled apart, each rock would add a hull: at least `hull` more than a ball.
    EXPECT_LT(rocks, balls + hull / 4) << "hull " << hull << " B, ball " << balls << " B";
}

}  // namespace
}  // namespace cyclone::test
