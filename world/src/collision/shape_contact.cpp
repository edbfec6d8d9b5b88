// fcl::collide between two shapes runs ShapeCollisionTraversalNode::leafTesting, which
// collects the solver's contacts in a vector of its own each call, and the libccd solver
// then creates both shapes' libccd objects with new (GJKInitializer::createGJKObject);
// a convex hull's support function allocates a visited list on every call
// (Convex::findExtremeVertex). Here the same solver routines run on a reused contact
// vector, the libccd objects live on the stack, and a hull's support is a plain scan of
// its vertices (what findExtremeVertex does for hulls of up to 32 vertices), so a step
// of shape pairs allocates nothing once the vectors have grown.
#include "collision/shape_contact.h"

#include <algorithm>
#include <type_traits>
#include <vector>

namespace cyclone::detail {
namespace {

using fcl::detail::ccd_box_t;
using fcl::detail::ccd_cap_t;
using fcl::detail::ccd_convex_t;
using fcl::detail::ccd_cyl_t;
using fcl::detail::ccd_sphere_t;
using Solver = fcl::detail::GJKSolver_libccd<double>;
using ContactPoints = std::vector<fcl::ContactPointd>;

// A hull's support point along `direction`: the first vertex of greatest projection.
void supportConvex(const void *object, const ccd_vec3_t *direction, ccd_vec3_t *out) {
    const auto *hull = static_cast<const ccd_convex_t<double> *>(object);
    ccd_vec3_t local;
    ccdVec3Copy(&local, direction);
    ccdQuatRotVec(&local, &hull->rot_inv);
    const fcl::Vector3d d(local.v[0], local.v[1], local.v[2]);
    const std::vector<fcl::Vector3d> &vertices = hull->convex->getVertices();
    std::size_t best = 0;
    double bestValue = d.dot(vertices[0]);
    for (std::size_t i = 1; i < vertices.size(); ++i) {
        const double value = d.dot(vertices[i]);
        if (value > bestValue) best = i, bestValue = value;
    }
    ccdVec3Set(out, vertices[best].x(), vertices[best].y(), vertices[best].z());
    ccdQuatRotVec(out, &hull->rot);
    ccdVec3Add(out, &hull->pos);
}

// The libccd object of each shape type, filled as GJKInitializer::createGJKObject fills it.
template <class Shape>
struct CcdShape;

template <>
struct CcdShape<fcl::Boxd> {
    ccd_box_t object;
    CcdShape(const fcl::Boxd &s, const fcl::Transform3d &pose) { fcl::detail::boxToGJK(s, pose, &object); }
    static fcl::detail::GJKSupportFunction support() { return fcl::detail::GJKInitializer<double, fcl::Boxd>::getSupportFunction(); }
    static fcl::detail::GJKCenterFunction center() { return fcl::detail::GJKInitializer<double, fcl::Boxd>::getCenterFunction(); }
};

template <>
struct CcdShape<fcl::Sphered> {
    ccd_sphere_t object;
    CcdShape(const fcl::Sphered &s, const fcl::Transform3d &pose) { fcl::detail::sphereToGJK(s, pose, &object); }
    static fcl::detail::GJKSupportFunction support() { return fcl::detail::GJKInitializer<double, fcl::Sphered>::getSupportFunction(); }
    static fcl::detail::GJKCenterFunction center() { return fcl::detail::GJKInitializer<double, fcl::Sphered>::getCenterFunction(); }
};

template <>
struct CcdShape<fcl::Capsuled> {
    ccd_cap_t object;
    CcdShape(const fcl::Capsuled &s, const fcl::Transform3d &pose) { fcl::detail::capToGJK(s, pose, &object); }
    static fcl::detail::GJKSupportFunction support() { return fcl::detail::GJKInitializer<double, fcl::Capsuled>::getSupportFunction(); }
    static fcl::detail::GJKCenterFunction center() { return fcl::detail::GJKInitializer<double, fcl::Capsuled>::getCenterFunction(); }
};

template <>
struct CcdShape<fcl::Cylinderd> {
    ccd_cyl_t object;
    CcdShape(const fcl::Cylinderd &s, const fcl::Transform3d &pose) { fcl::detail::cylToGJK(s, pose, &object); }
    static fcl::detail::GJKSupportFunction support() { return fcl::detail::GJKInitializer<double, fcl::Cylinderd>::getSupportFunction(); }
    static fcl::detail::GJKCenterFunction center() { return fcl::detail::GJKInitializer<double, fcl::Cylinderd>::getCenterFunction(); }
};

template <>
struct CcdShape<fcl::Convexd> {
    ccd_convex_t<double> object;
    CcdShape(const fcl::Convexd &s, const fcl::Transform3d &pose) { fcl::detail::convexToGJK(s, pose, &object); }
    static fcl::detail::GJKSupportFunction support() { return &supportConvex; }
    static fcl::detail::GJKCenterFunction center() { return fcl::detail::GJKInitializer<double, fcl::Convexd>::getCenterFunction(); }
};

// Whether the libccd solver has a routine of its own for the pair (ShapeIntersectLibccdImpl's
// specialisations); the other pairs go through GJKCollide (libccd's MPR).
template <class A, class B>
constexpr bool hasOwnRoutine() {
    constexpr bool aSphere = std::is_same_v<A, fcl::Sphered>;
    constexpr bool bSphere = std::is_same_v<B, fcl::Sphered>;
    constexpr bool aConvex = std::is_same_v<A, fcl::Convexd>;
    constexpr bool bConvex = std::is_same_v<B, fcl::Convexd>;
    if (std::is_same_v<A, fcl::Halfspaced> || std::is_same_v<B, fcl::Halfspaced>) return true;
    if (std::is_same_v<A, fcl::Boxd> && std::is_same_v<B, fcl::Boxd>) return true;
    return (aSphere && !bConvex) || (bSphere && !aConvex);
}

// Whether the libccd solver measures the pair's distance with a routine of its own
// (ShapeDistanceLibccdImpl's specialisations); the other pairs go through GJKDistance.
template <class A, class B>
constexpr bool hasOwnDistance() {
    constexpr bool aSphere = std::is_same_v<A, fcl::Sphered>;
    constexpr bool bSphere = std::is_same_v<B, fcl::Sphered>;
    constexpr bool aCapsule = std::is_same_v<A, fcl::Capsuled>;
    constexpr bool bCapsule = std::is_same_v<B, fcl::Capsuled>;
    constexpr bool aConvex = std::is_same_v<A, fcl::Convexd>;
    constexpr bool bConvex = std::is_same_v<B, fcl::Convexd>;
    return (aCapsule && bCapsule) || (aSphere && !bConvex) || (bSphere && !aConvex);
}

// `contacts` null: only whether they touch (libccd's MPR intersection test, as FCL runs
// it for a request without contacts).
template <class A, class B>
bool intersect(const A &a, const fcl::Transform3d &poseA, const B &b, const fcl::Transform3d &poseB,
               const Solver &solver, ContactPoints *contacts) {
    if constexpr (hasOwnRoutine<A, B>()) {
        return solver.shapeIntersect(a, poseA, b, poseB, contacts);
    } else {
        CcdShape<A> ccdA(a, poseA);
        CcdShape<B> ccdB(b, poseB);
        if (!contacts)
            return fcl::detail::GJKCollide<double>(&ccdA.object, CcdShape<A>::support(), CcdShape<A>::center(),
                                                   &ccdB.object, CcdShape<B>::support(), CcdShape<B>::center(),
                                                   solver.max_collision_iterations, solver.collision_tolerance, nullptr,
                                                   nullptr, nullptr);
        fcl::Vector3d point;
        fcl::Vector3d normal;
        double depth = 0;
        const bool touching = fcl::detail::GJKCollide<double>(
            &ccdA.object, CcdShape<A>::support(), CcdShape<A>::center(), &ccdB.object, CcdShape<B>::support(),
            CcdShape<B>::center(), solver.max_collision_iterations, solver.collision_tolerance, &point, &depth, &normal);
        if (touching) contacts->emplace_back(normal, point, depth);
        return touching;
    }
}

// The distance and nearest points of two shapes, as GJKSolver_libccd::shapeDistance
// finds them.
template <class A, class B>
void measure(const A &a, const fcl::Transform3d &poseA, const B &b, const fcl::Transform3d &poseB,
             const Solver &solver, double &distance, fcl::Vector3d &pointA, fcl::Vector3d &pointB) {
    if constexpr (std::is_same_v<A, fcl::Halfspaced> || std::is_same_v<B, fcl::Halfspaced>) {
        return;  // not measured here (isSolid)
    } else if constexpr (hasOwnDistance<A, B>()) {
        solver.shapeDistance(a, poseA, b, poseB, &distance, &pointA, &pointB);
    } else {
        CcdShape<A> ccdA(a, poseA);
        CcdShape<B> ccdB(b, poseB);
        fcl::detail::GJKDistance<double>(&ccdA.object, CcdShape<A>::support(), &ccdB.object, CcdShape<B>::support(),
                                         solver.max_distance_iterations, solver.distance_tolerance, &distance, &pointA,
                                         &pointB);
    }
}

// Calls f with the geometry cast to its shape type; false for anything else (a mesh).
template <class F>
bool withShape(const fcl::CollisionGeometryd *g, F &&f) {
    switch (g->getNodeType()) {
        case fcl::GEOM_BOX: f(static_cast<const fcl::Boxd &>(*g)); return true;
        case fcl::GEOM_SPHERE: f(static_cast<const fcl::Sphered &>(*g)); return true;
        case fcl::GEOM_CAPSULE: f(static_cast<const fcl::Capsuled &>(*g)); return true;
        case fcl::GEOM_CYLINDER: f(static_cast<const fcl::Cylinderd &>(*g)); return true;
        case fcl::GEOM_CONVEX: f(static_cast<const fcl::Convexd &>(*g)); return true;
        case fcl::GEOM_HALFSPACE: f(static_cast<const fcl::Halfspaced &>(*g)); return true;
        default: return false;
    }
}

bool isShape(const fcl::CollisionGeometryd *g) {
    return withShape(g, [](const auto &) {});
}

// A shape that libccd measures distances to (a half-space is not one).
bool isSolid(const fcl::CollisionGeometryd *g) {
    return g->getNodeType() != fcl::GEOM_HALFSPACE && isShape(g);
}

}  // namespace

bool shapeTriangleContact(const fcl::CollisionGeometryd *shape, const fcl::Transform3d &pose,
                          const fcl::Vector3d (&p)[3], const fcl::Transform3d &trianglePose, fcl::Vector3d &normal,
                          double &depth) {
    if (!isSolid(shape)) return false;
    // As fcl::collide sets up its solver for GST_LIBCCD, with a default request.
    static const double tolerance = fcl::CollisionRequestd().gjk_tolerance;
    Solver solver;
    solver.collision_tolerance = tolerance;
    bool touching = false;
    withShape(shape, [&](const auto &s) {
        fcl::Vector3d point;
        touching = solver.shapeTriangleIntersect(s, pose, p[0], p[1], p[2], trianglePose, &point, &depth, &normal);
    });
    return touching;
}

std::size_t collideShapes(const fcl::CollisionGeometryd *a, const fcl::Transform3d &poseA,
                          const fcl::CollisionGeometryd *b, const fcl::Transform3d &poseB,
                          const fcl::CollisionRequestd &request, fcl::CollisionResultd &result) {
    if (!isShape(a) || !isShape(b)) return fcl::collide(a, poseA, b, poseB, request, result);

    // As fcl::collide sets up its solver for GST_LIBCCD.
    Solver solver;
    solver.collision_tolerance = request.gjk_tolerance;
    static thread_local ContactPoints contacts;
    contacts.clear();
    bool touching = false;
    withShape(a, [&](const auto &shapeA) {
        withShape(b, [&](const auto &shapeB) {
            touching = intersect(shapeA, poseA, shapeB, poseB, solver, request.enable_contact ? &contacts : nullptr);
        });
    });
    if (!touching || result.numContacts() >= request.num_max_contacts) return result.numContacts();
    if (!request.enable_contact) {
        result.addContact(fcl::Contactd(a, b, fcl::Contactd::NONE, fcl::Contactd::NONE));
        return result.numContacts();
    }

    // As leafTesting: when the contacts do not all fit, the deepest ones.
    const std::size_t room = request.num_max_contacts - result.numContacts();
    std::size_t adding = contacts.size();
    if (room < adding) {
        std::partial_sort(contacts.begin(), contacts.begin() + static_cast<std::ptrdiff_t>(room), contacts.end(),
                          [](const fcl::ContactPointd &x, const fcl::ContactPointd &y) {
                              return x.penetration_depth > y.penetration_depth;
                          });
        adding = room;
    }
    for (std::size_t i = 0; i < adding; ++i)
        result.addContact(fcl::Contactd(a, b, fcl::Contactd::NONE, fcl::Contactd::NONE, contacts[i].pos,
                                        contacts[i].normal, contacts[i].penetration_depth));
    return result.numContacts();
}

}  // namespace cyclone::detail

namespace cyclone::detail {

double distanceShapes(const fcl::CollisionGeometryd *a, const fcl::Transform3d &poseA,
                      const fcl::CollisionGeometryd *b, const fcl::Transform3d &poseB,
                      const fcl::DistanceRequestd &request, fcl::DistanceResultd &result) {
    if (request.gjk_solver_type != fcl::GST_LIBCCD || request.enable_signed_distance || !isSolid(a) || !isSolid(b) ||
        request.isSatisfied(result))
        return fcl::distance(a, poseA, b, poseB, request, result);
    // As fcl::distance sets up its solver for GST_LIBCCD, and as its traversal node
    // records the answer.
    Solver solver;
    solver.distance_tolerance = request.distance_tolerance;
    double distance = 0;
    fcl::Vector3d pointA = fcl::Vector3d::Zero();
    fcl::Vector3d pointB = fcl::Vector3d::Zero();
    withShape(a, [&](const auto &shapeA) {
        withShape(b, [&](const auto &shapeB) { measure(shapeA, poseA, shapeB, poseB, solver, distance, pointA, pointB); });
    });
    result.update(distance, a, b, fcl::DistanceResultd::NONE, fcl::DistanceResultd::NONE, pointA, pointB);
    return result.min_distance;
}

}  // namespace cyclone::detail
