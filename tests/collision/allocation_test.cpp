// collide() allocates nothing beyond what fcl::collide itself allocates: its working
// storage is on the stack and the caller's vector is reused. The pairs with a test of
// their own (box-box, sphere-sphere, sphere-box, plane against a solid) allocate nothing.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "collision_test_support.h"

namespace {
std::atomic<long> allocations{0};
}  // namespace

// Counting replacements of the global allocation functions, for this test binary only.
// They pair malloc with free; GCC 12 at -O1 inlines a delete expression and then flags
// free() on memory from operator new (-Wmismatched-new-delete), which is exactly the
// pairing intended here.
// Under AddressSanitizer they are left out: ASan has its own allocator, and memory FCL
// allocates through it would come back here to free() (an alloc-dealloc mismatch).
#if defined(__SANITIZE_ADDRESS__)
#define CYCLONE_COUNTING_ALLOCATOR 0
#else
#define CYCLONE_COUNTING_ALLOCATOR 1
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void *operator new(std::size_t size) {
    ++allocations;
    if (void *p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void *operator new[](std::size_t size) { return operator new(size); }
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t) noexcept { std::free(p); }
#endif

namespace cyclone::test {
namespace {

template <class Call>
long allocationsOf(const Call &call) {
    const long before = allocations;
    call();
    return allocations - before;
}

void expectNoExtraAllocation(const Shape &a, const Matrix4 &poseA, const Shape &b, const Matrix4 &poseB,
                             bool ownTest = false) {
    const auto compiledA = detail::compileShape(a);
    const auto compiledB = detail::compileShape(b);
    const bool mesh = a.type == ShapeType::Mesh || b.type == ShapeType::Mesh;
    fcl::CollisionRequestd request(mesh ? 16 : 4, true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::CollisionResultd result;
    std::vector<Manifold> out;
    out.reserve(8);
    const detail::NarrowphaseSettings settings;
    detail::NarrowphaseSettings viaFcl;
    viaFcl.forceFcl = true;
    auto fclAlone = [&] {
        result.clear();
        fcl::collide(compiledA->geometry().get(), poseA, compiledB->geometry().get(), poseB, request, result);
    };
    auto collideWith = [&](const detail::NarrowphaseSettings &s) {
        return [&] {
            out.clear();
            detail::collide(*compiledA, poseA, *compiledB, poseB, s, out);
        };
    };
    // Warm up: first calls size FCL's and our reused storage.
    for (int i = 0; i < 3; ++i) {
        collideWith(settings)();
        collideWith(viaFcl)();
        fclAlone();
    }
    ASSERT_FALSE(out.empty());

    const long byFcl = allocationsOf(fclAlone);
    EXPECT_EQ(allocationsOf(collideWith(viaFcl)), byFcl) << shapeTypeName(a.type) << " against " << shapeTypeName(b.type);
    EXPECT_EQ(allocationsOf(collideWith(settings)), ownTest ? 0 : byFcl)
        << shapeTypeName(a.type) << " against " << shapeTypeName(b.type);
}

TEST(Allocation, CollideAllocatesOnlyWhatFclDoes) {
    if (!CYCLONE_COUNTING_ALLOCATOR) GTEST_SKIP() << "AddressSanitizer replaces the allocator; counted in normal builds";
    const Shape box = Shape::box(Vector3(0.5, 0.5, 0.5));
    expectNoExtraAllocation(box, pose(Vector3(0.1, 0.95, 0)), box, Matrix4::Identity(), true);
    expectNoExtraAllocation(box, pose(Vector3(0.1, 0.45, 0)), Shape::plane(Vector3::UnitY(), 0), Matrix4::Identity(),
                            true);
    expectNoExtraAllocation(Shape::sphere(0.5), pose(Vector3(0.1, 0.95, 0)), box, Matrix4::Identity(), true);
    expectNoExtraAllocation(Shape::sphere(0.5), pose(Vector3(0.1, 0.95, 0)), Shape::sphere(0.5), Matrix4::Identity(),
                            true);
    expectNoExtraAllocation(Shape::cylinder(0.4, 1), pose(Vector3(0.1, 0.95, 0), zUp()), box, Matrix4::Identity());
    expectNoExtraAllocation(Shape::capsule(0.25, 1), pose(Vector3(0, 0.45, 0), zAlongX()), Shape::capsule(0.25, 1),
                            Matrix4::Identity());
    expectNoExtraAllocation(pyramid(), pose(Vector3(0.1, 0.7, 0)), box, Matrix4::Identity());
    expectNoExtraAllocation(box, pose(Vector3(0.3, 0.45, 0.2)), meshFloor(), Matrix4::Identity());
}

}  // namespace
}  // namespace cyclone::test
