// collide() allocates nothing for a pair of shapes once its reused vectors have grown:
// its working storage is on the stack, the pairs with a test of their own (box-box,
// sphere-sphere, sphere-box, a plane against a solid) use nothing else, and FCL's contact
// test runs on a reused contact vector with libccd objects on the stack
// (shape_contact.cpp). What remains is inside FCL: box against box when forced through
// FCL (fcl::detail::boxBoxIntersect) and meshes (fcl::collide).
#include <gtest/gtest.h>

#include "collision/time_of_impact.h"
#include "collision_test_support.h"
#include "counting_allocator.h"

namespace cyclone::test {
namespace {

using Geometry = std::shared_ptr<const CollisionShape>;

// Allocations of one collide() call after three warm-up calls.
long collideAllocations(const Geometry &a, const Matrix4 &poseA, const Geometry &b, const Matrix4 &poseB,
                        const detail::NarrowphaseSettings &settings = {}) {
    std::vector<Manifold> out;
    out.reserve(8);
    for (int i = 0; i < 3; ++i) {
        out.clear();
        detail::collide(*a, poseA, *b, poseB, settings, out);
    }
    EXPECT_FALSE(out.empty()) << "the shapes must touch for the test to mean something";
    const long before = allocationCount();
    out.clear();
    detail::collide(*a, poseA, *b, poseB, settings, out);
    return allocationCount() - before;
}

void expectNoAllocation(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB) {
    const long count = collideAllocations(detail::compileShape(a), poseA, detail::compileShape(b), poseB);
    EXPECT_EQ(count, 0) << shapeTypeName(a.type) << " against " << shapeTypeName(b.type);
}

TEST(Allocation, CollideOfShapePairsAllocatesNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    const Shape box = Shape::box(Vector3(0.5, 0.5, 0.5));
    const Shape sphere = Shape::sphere(0.4);
    const Shape capsule = Shape::capsule(0.25, 1);
    const Shape cylinder = Shape::cylinder(0.4, 1);
    const Shape plane = Shape::plane(Vector3::UnitY(), 0);
    // Tests of their own.
    expectNoAllocation(box, pose(Vector3(0.1, 0.95, 0)), box, Matrix4::Identity());
    expectNoAllocation(box, pose(Vector3(0.1, 0.45, 0)), plane, Matrix4::Identity());
    expectNoAllocation(sphere, pose(Vector3(0.1, 0.7, 0)), sphere, Matrix4::Identity());
    // Through the libccd solver's own routines.
    expectNoAllocation(sphere, pose(Vector3(0.1, 0.85, 0)), box, Matrix4::Identity());
    expectNoAllocation(sphere, pose(Vector3(0, 0.35, 0)), plane, Matrix4::Identity());
    expectNoAllocation(capsule, pose(Vector3(0, 0.2, 0), zAlongX()), plane, Matrix4::Identity());
    expectNoAllocation(cylinder, pose(Vector3(0, 0.45, 0), zUp()), plane, Matrix4::Identity());
    expectNoAllocation(pyramid(), pose(Vector3(0, 0.2, 0)), plane, Matrix4::Identity());
    // Through libccd's MPR.
    expectNoAllocation(cylinder, pose(Vector3(0.1, 0.95, 0), zUp()), box, Matrix4::Identity());
    expectNoAllocation(capsule, pose(Vector3(0, 0.45, 0), zAlongX()), capsule, Matrix4::Identity());
    expectNoAllocation(pyramid(), pose(Vector3(0.1, 0.7, 0)), box, Matrix4::Identity());
    expectNoAllocation(sphere, pose(Vector3(0.1, 0.6, 0)), pyramid(), Matrix4::Identity());
}

// Box against box forced through FCL: only fcl::detail::boxBoxIntersect allocates
// (vectors of its own).
TEST(Allocation, CollideOfTwoBoxesThroughFclAllocatesOnlyInBoxBoxIntersect) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    const Geometry box = detail::compileShape(Shape::box(Vector3(0.5, 0.5, 0.5)));
    const Matrix4 poseA = pose(Vector3(0.1, 0.95, 0));
    const Matrix4 poseB = Matrix4::Identity();
    const auto &fclBox = static_cast<const fcl::Boxd &>(*box->geometry());
    std::vector<fcl::ContactPointd> contacts;
    contacts.reserve(16);
    long before = allocationCount();
    ASSERT_TRUE(fcl::detail::boxBoxIntersect(fclBox, poseA, fclBox, poseB, &contacts));
    const long byFcl = allocationCount() - before;
    EXPECT_GT(byFcl, 0) << "boxBoxIntersect no longer allocates: expect 0 below and drop this test";
    detail::NarrowphaseSettings viaFcl;
    viaFcl.forceFcl = true;
    EXPECT_EQ(collideAllocations(box, poseA, box, poseB, viaFcl), byFcl);
}

// A mesh goes through fcl::collide: collide() adds nothing to what that allocates.
TEST(Allocation, CollideWithMeshAllocatesOnlyWhatFclDoes) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    const Geometry box = detail::compileShape(Shape::box(Vector3(0.5, 0.5, 0.5)));
    const Geometry floor = detail::compileShape(meshFloor());
    const Matrix4 poseA = pose(Vector3(0.3, 0.45, 0.2));
    const Matrix4 poseB = Matrix4::Identity();
    fcl::CollisionRequestd request(16, true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::CollisionResultd result;
    for (int i = 0; i < 3; ++i) {
        result.clear();
        fcl::collide(box->geometry().get(), poseA, floor->geometry().get(), poseB, request, result);
    }
    const long before = allocationCount();
    result.clear();
    fcl::collide(box->geometry().get(), poseA, floor->geometry().get(), poseB, request, result);
    const long byFcl = allocationCount() - before;
    EXPECT_EQ(collideAllocations(box, poseA, floor, poseB), byFcl);
}

// The time of impact samples poses and bisects with a contact test at each: two boxes are
// tested by their separating axes (FCL's box test fills vectors of its own each call), so
// a sweep of a box into a box allocates nothing.
TEST(Allocation, TimeOfImpactOfTwoBoxesAllocatesNothing) {
    if (!kCountingAllocator) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    const Geometry box = detail::compileShape(Shape::box(Vector3(0.5, 0.5, 0.5)));
    const detail::SweptShape swept = detail::sweptShape(*box);
    // A unit box falls from 0.3 m above a resting one to 0.2 m into it: they touch after
    // 0.3 of the 0.5 m fall, t = 0.6.
    const Matrix4 start = pose(Vector3(0, 1.3, 0));
    const Matrix4 end = pose(Vector3(0, 0.8, 0));
    const Matrix4 still = Matrix4::Identity();
    real t = 0;
    ASSERT_EQ(detail::timeOfImpact(swept, start, end, swept, still, still, t), detail::Impact::Hit);
    EXPECT_NEAR(t, 0.6, 1e-3);
    const long before = allocationCount();
    detail::timeOfImpact(swept, start, end, swept, still, still, t);
    EXPECT_EQ(allocationCount() - before, 0);
}

}  // namespace
}  // namespace cyclone::test
