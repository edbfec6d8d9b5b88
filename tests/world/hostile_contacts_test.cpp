// Hostile input, round three (issue 61), in contact: coincident round shapes are pushed
// apart, and bodies spawned at one point stay on the static floor under them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "world_fixture.h"

namespace cyclone::test {
namespace {

WorldSettings weightless() {
    WorldSettings s = noSleep();
    s.gravity = Vector3::Zero();
    return s;
}

// Two unit-diameter spheres with one centre, no gravity: their normal is +x (their offset
// has no direction), so every impulse between them is along x and their y and z never
// change; after 2 s the overlap of 1 m is gone: their centres are 2 r = 1 m apart, less
// the penetration slop (0.2 mm) and what is left of the recovery (bounded here by 1 cm).
// They never separated before: 0 m apart after 2 s.
TEST(HostileContacts, CoincidentSpheresArePushedApart) {
    WorldFixture f(weightless());
    const BodyId a = f.sphere(Vector3(0, 2, 0));
    const BodyId b = f.sphere(Vector3(0, 2, 0));
    f.simulate(2.0);
    const Vector3 offset = f.position(b) - f.position(a);
    EXPECT_GT(std::abs(offset.x()), 0.99);
    EXPECT_EQ(offset.y(), 0);
    EXPECT_EQ(offset.z(), 0);
    EXPECT_EQ(f.position(a).y(), 2);
}

// 1e-9 m apart along z: pushed apart along z, the direction of their offset.
TEST(HostileContacts, SpheresANanometreApartArePushedApartAlongTheirOffset) {
    WorldFixture f(weightless());
    const BodyId a = f.sphere(Vector3(0, 2, 0));
    const BodyId b = f.sphere(Vector3(0, 2, 1e-9));
    f.simulate(2.0);
    const Vector3 offset = f.position(b) - f.position(a);
    EXPECT_GT(offset.z(), 0.99);
    EXPECT_EQ(offset.x(), 0);
    EXPECT_EQ(offset.y(), 0);
}

// 30 spheres of radius 0.2 spawned at one point resting on a static box floor 0.2 m
// thick, 60 m wide: pushed apart along x they form a row, each on the floor. None goes
// into it deeper than 1 cm (its centre at r = 0.2 m above the top face, less 1 cm) and
// none rises above 2 r (they are pushed sideways, never onto each other). The floor is
// thin enough that a sphere pushed more than half its thickness into it used to come
// out below it and fall for ever.
TEST(HostileContacts, SpheresSpawnedAtOnePointStayOnAThinFloor) {
    WorldFixture f(noSleep());
    f.staticBox(Vector3(0, -0.1, 0), Vector3(30, 0.1, 30));
    std::vector<BodyId> spheres;
    for (int i = 0; i < 30; ++i) spheres.push_back(f.sphere(Vector3(0, 0.2, 0), 0.2));
    f.simulate(5.0);
    std::vector<real> xs;
    for (BodyId id : spheres) {
        EXPECT_GT(f.position(id).y(), 0.19);
        EXPECT_LT(f.position(id).y(), 0.4);
        xs.push_back(f.position(id).x());
    }
    // Apart: neighbours along the row touch, their centres 2 r = 0.4 m apart (less 1 cm).
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 1; k < xs.size(); ++k) EXPECT_GT(xs[k] - xs[k - 1], 0.39) << "spheres " << k - 1 << ", " << k;
}

}  // namespace
}  // namespace cyclone::test
