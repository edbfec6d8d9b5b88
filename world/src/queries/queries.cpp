// Queries: a ray's closest hit and a shape's overlaps, through the broadphase trees.
//
// Both walk the three FCL trees themselves rather than through the managers' callbacks:
// the ray prunes every box it enters beyond the closest hit so far, visiting the nearer
// child first, and the overlap prunes by the query's box. Planes are not in the trees
// and are tested one by one. The exact tests are ray_cast.cpp's and fcl::collide.
// Nothing here changes the World, so queries may run concurrently with each other.
#include <algorithm>
#include <cmath>

#include "collision/narrowphase.h"
#include "collision/ray_cast.h"
#include "collision/shape_cast.h"
#include "queries/queries.h"
#include "world/validation.h"

namespace cyclone {

using detail::BodyRecord;
namespace {

using Node = fcl::detail::NodeBase<fcl::AABBd>;

std::uint32_t leafBody(const Node *node) {
    return detail::bodyIndexOf(static_cast<const fcl::CollisionObjectd *>(node->data));
}

// The descent both ray walks share: every box the ray reaches within ray.maxDistance,
// the nearer child first, each leaf's body to Walk::test (which may shorten the ray, and
// so prune the boxes beyond its hit).
template <class Walk>
struct RayDescent {
    void visit(const Node *node) {
        Walk &self = static_cast<Walk &>(*this);
        if (node->isLeaf()) {
            self.test(leafBody(node));
            return;
        }
        const Node *children[2] = {node->children[0], node->children[1]};
        real enter[2] = {0, 0};
        bool reached[2];
        for (int k = 0; k < 2; ++k)
            reached[k] = detail::rayBox(self.ray.origin, self.ray.direction, children[k]->bv.min_,
                                        children[k]->bv.max_, self.ray.maxDistance, enter[k]);
        detail::visitNearestFirst(children, reached, enter, self.ray.maxDistance,
                                  [this](const Node *child) { visit(child); });
    }

    void walk(const Node *root) {
        const detail::Ray &ray = static_cast<Walk &>(*this).ray;
        real enter;
        if (root && detail::rayBox(ray.origin, ray.direction, root->bv.min_, root->bv.max_, ray.maxDistance, enter))
            visit(root);
    }
};

// The closest hit: each hit shortens the ray.
template <class Accepts>
struct RayWalk : RayDescent<RayWalk<Accepts>> {
    const detail::BodyStore &bodies;
    const Accepts &accepts;
    detail::Ray ray;
    bool found = false;
    std::uint32_t body = 0;
    detail::RaySurfaceHit hit;

    RayWalk(const detail::BodyStore &b, const Accepts &a, const detail::Ray &r) : bodies(b), accepts(a), ray(r) {}

    void test(std::uint32_t index) {
        if (!accepts(index)) return;
        const BodyRecord &r = bodies[index];
        detail::RaySurfaceHit candidate;
        if (!detail::rayShape(ray, *r.shape, r.body.getTransform(), candidate)) return;
        // Equally close hits go to the smaller index, whatever order the trees give.
        if (found && (candidate.distance > hit.distance || (candidate.distance == hit.distance && index > body)))
            return;
        found = true;
        body = index;
        hit = candidate;
        ray.maxDistance = candidate.distance;
    }
};

// Every body the ray meets: the ray keeps its full length, so every box it reaches is
// visited.
template <class Accepts>
struct RayAllWalk : RayDescent<RayAllWalk<Accepts>> {
    const detail::BodyStore &bodies;
    const Accepts &accepts;
    detail::Ray ray;
    std::vector<std::pair<detail::RaySurfaceHit, std::uint32_t>> &hits;

    RayAllWalk(const detail::BodyStore &b, const Accepts &a, const detail::Ray &r,
               std::vector<std::pair<detail::RaySurfaceHit, std::uint32_t>> &h)
        : bodies(b), accepts(a), ray(r), hits(h) {}

    void test(std::uint32_t index) {
        if (!accepts(index)) return;
        const BodyRecord &r = bodies[index];
        detail::RaySurfaceHit hit;
        if (detail::rayShape(ray, *r.shape, r.body.getTransform(), hit)) hits.emplace_back(hit, index);
    }
};

// A query's ray, its direction normalised; refused with `function`'s name when the origin
// is out of range, the direction zero or not finite, or the length not positive.
detail::Ray checkedRay(const char *function, const Vector3 &origin, const Vector3 &direction, real maxDistance) {
    detail::requirePlace(function, "origin", origin);
    detail::requireFinite(function, "direction", direction);
    const real length = direction.stableNorm();
    if (!(length > 0)) detail::refuse(function, "direction", "must not be zero, got " + detail::show(direction));
    if (!(maxDistance > 0))
        detail::refuse(function, "maxDistance", "must be > 0 (infinity allowed), got " + detail::show(maxDistance));
    return {origin, direction / length, maxDistance};
}

template <class Test>
struct OverlapWalk {
    const fcl::AABBd &box;
    const Test &test;

    void visit(const Node *node) {
        if (!node || !node->bv.overlap(box)) return;
        if (node->isLeaf()) {
            test(leafBody(node));
            return;
        }
        visit(node->children[0]);
        visit(node->children[1]);
    }
};

// Calls visit(root) for each broadphase tree that may hold a body the filter considers,
// and test(plane) for each plane when static bodies are considered. A moving kinematic
// body is in the awake tree, a still one in the static tree; a sleeping tree holds only
// dynamic bodies.
template <class Visit, class Test>
void visitTrees(const detail::QueryScene &scene, const QueryFilter &filter, const Visit &visit, const Test &test) {
    if (filter.dynamicBodies || filter.kinematicBodies) visit(scene.broadphase.root(detail::Tree::Awake));
    if (filter.dynamicBodies) visit(scene.broadphase.root(detail::Tree::Asleep));
    if (filter.staticBodies || filter.kinematicBodies) visit(scene.broadphase.root(detail::Tree::Static));
    if (filter.staticBodies)
        for (std::uint32_t plane : scene.bodies.planes) test(plane);
}

Quaternion unitOrIdentity(const Quaternion &q) {
    const real length = q.norm();
    return length > 0 ? Quaternion(q.coeffs() / length) : Quaternion::Identity();
}

// A query shape compiled and placed as World::addBody places a body (a compound by its
// frame), refused as addBody refuses one: a size or a place beyond the coordinate range.
struct PlacedShape {
    std::shared_ptr<const detail::CollisionShape> shape;
    Matrix4 pose = Matrix4::Identity();
};

PlacedShape placeQueryShape(const char *function, const Shape &shape, const Vector3 &position,
                            const Quaternion &orientation) {
    PlacedShape placed;
    try {
        placed.shape = detail::compileShape(shape);
    } catch (const InvalidArgument &e) {
        throw InvalidArgument(function, e.field(), e.problem());
    }
    const real radius = placed.shape->boundingRadius();
    if (!(radius <= detail::kMaxCoordinate))
        detail::refuse(function, "shape",
                       "must fit within 1e12 m of its origin, got a shape reaching " + detail::show(radius) + " m from it");
    placed.pose.linear() = unitOrIdentity(orientation).toRotationMatrix();
    placed.pose.translation() = position + placed.pose.linear() * placed.shape->frameToCentre();
    detail::requireReach(function, "position", placed.pose.translation(), radius);
    return placed;
}

}  // namespace

bool detail::accepts(const QueryScene &scene, std::uint32_t index, const QueryFilter &filter) {
    const BodyStore &bodies = scene.bodies;
    const BodyRecord &r = bodies[index];
    if (!r.alive || r.isolated || (r.sensor && !filter.sensors)) return false;
    const bool considered = r.kinematic ? filter.kinematicBodies : r.immovable ? filter.staticBodies : filter.dynamicBodies;
    if (!considered || !(filter.layers >> r.layer & 1u)) return false;
    const BodyId id = bodies.idOf(index);
    if (filter.ignore && *filter.ignore == id) return false;
    if (!filter.accept) return true;
    // The query walks the broadphase trees and the body records: an accept() that adds,
    // removes or moves a body pulls them from under the walk (QueryFilter forbids it).
    const std::uint64_t changes = scene.broadphase.changes(), calls = scene.changingCalls;
    const std::size_t records = bodies.size(), live = bodies.order.size();
    const bool accepted = filter.accept(id);
    if (scene.broadphase.changes() != changes || scene.changingCalls != calls || bodies.size() != records ||
        bodies.order.size() != live)
        refuse("World query", "filter.accept", "changed the world during the query (called a World member that "
                                               "changes it, such as removeBody or step); a QueryFilter::accept must "
                                               "only read");
    return accepted;
}

std::optional<RayHit> detail::rayCast(const QueryScene &scene, const Vector3 &origin, const Vector3 &direction,
                                      real maxDistance, const QueryFilter &filter) {
    const auto accepted = [&](std::uint32_t index) { return accepts(scene, index, filter); };
    RayWalk<decltype(accepted)> walk(scene.bodies, accepted,
                                     checkedRay("World::rayCast", origin, direction, maxDistance));
    visitTrees(
        scene, filter, [&](const Node *root) { walk.walk(root); }, [&](std::uint32_t plane) { walk.test(plane); });
    if (!walk.found) return std::nullopt;
    RayHit hit;
    hit.body = scene.bodies.idOf(walk.body);
    hit.userData = scene.bodies[walk.body].userData;
    hit.distance = walk.hit.distance;
    hit.point = walk.ray.origin + walk.hit.distance * walk.ray.direction;
    hit.normal = walk.hit.normal;
    return hit;
}

std::size_t detail::rayCastAll(const QueryScene &scene, const Vector3 &origin, const Vector3 &direction,
                               std::vector<RayHit> &out, real maxDistance, const QueryFilter &filter) {
    std::vector<std::pair<detail::RaySurfaceHit, std::uint32_t>> hits;
    const auto accepted = [&](std::uint32_t index) { return accepts(scene, index, filter); };
    RayAllWalk<decltype(accepted)> walk(scene.bodies, accepted,
                                        checkedRay("World::rayCastAll", origin, direction, maxDistance), hits);
    visitTrees(
        scene, filter, [&](const Node *root) { walk.walk(root); }, [&](std::uint32_t plane) { walk.test(plane); });
    std::sort(hits.begin(), hits.end(), [](const auto &x, const auto &y) {
        return x.first.distance != y.first.distance ? x.first.distance < y.first.distance : x.second < y.second;
    });
    out.clear();
    for (const auto &[surface, index] : hits) {
        RayHit hit;
        hit.body = scene.bodies.idOf(index);
        hit.userData = scene.bodies[index].userData;
        hit.distance = surface.distance;
        hit.point = walk.ray.origin + surface.distance * walk.ray.direction;
        hit.normal = surface.normal;
        out.push_back(hit);
    }
    return out.size();
}

std::size_t detail::overlap(const QueryScene &scene, const Shape &shape, const Vector3 &position,
                            const Quaternion &orientation, std::vector<BodyId> &out, const QueryFilter &filter) {
    static const char *function = "World::overlap";
    detail::requirePlace(function, "position", position);
    detail::requireFinite(function, "orientation", orientation);
    if (shape.type == ShapeType::Plane || shape.type == ShapeType::Heightfield)
        detail::refuse(function, "shape.type",
                       std::string("\"") + shapeTypeName(shape.type) + "\" cannot be a query shape; use a solid shape");
    const PlacedShape placed = placeQueryShape(function, shape, position, orientation);
    const std::shared_ptr<const detail::CollisionShape> &compiled = placed.shape;
    const Matrix4 &pose = placed.pose;
    out.clear();

    const fcl::CollisionObjectd query(compiled->geometry(), pose);
    const auto test = [&](std::uint32_t index) {
        if (!detail::accepts(scene, index, filter)) return;
        const BodyRecord &r = scene.bodies[index];
        if (detail::intersects(*compiled, pose, *r.shape, r.body.getTransform()))
            out.push_back(scene.bodies.idOf(index));
    };
    OverlapWalk<decltype(test)> walk{query.getAABB(), test};
    visitTrees(scene, filter, [&](const Node *root) { walk.visit(root); }, test);
    std::sort(out.begin(), out.end(), [](const BodyId &x, const BodyId &y) { return x.index < y.index; });
    return out.size();
}

namespace {

// The earliest hit of `shape` cast from `start` by `motion` among the bodies `filter`
// accepts whose boxes meet `swept`; ties to the smaller index.
std::optional<ShapeCastHit> castAmong(const detail::QueryScene &scene, const detail::CollisionShape &shape,
                                      const Matrix4 &start, const detail::CastMotion &motion, const fcl::AABBd &swept,
                                      const QueryFilter &filter) {
    bool found = false;
    std::uint32_t best = 0;
    detail::CastHit hit;
    const auto test = [&](std::uint32_t index) {
        if (!detail::accepts(scene, index, filter)) return;
        const BodyRecord &r = scene.bodies[index];
        detail::CastHit candidate;
        const real limit = found ? hit.fraction : 1;
        if (!detail::castShape(shape, start, motion, *r.shape, r.body.getTransform(), limit, candidate)) return;
        if (found && (candidate.fraction > hit.fraction || (candidate.fraction == hit.fraction && index > best))) return;
        found = true;
        best = index;
        hit = candidate;
    };
    OverlapWalk<decltype(test)> walk{swept, test};
    visitTrees(scene, filter, [&](const Node *root) { walk.visit(root); }, test);
    if (!found) return std::nullopt;
    ShapeCastHit result;
    result.body = scene.bodies.idOf(best);
    result.userData = scene.bodies[best].userData;
    result.fraction = hit.fraction;
    result.distance = hit.fraction * motion.translation.stableNorm();
    result.point = hit.point;
    result.normal = hit.normal;
    return result;
}

// A shape cast's shape: refused when it is a plane, a mesh or a height field.
void requireCastable(const char *function, const Shape &shape) {
    if (shape.type == ShapeType::Plane || shape.type == ShapeType::Mesh || shape.type == ShapeType::Heightfield)
        detail::refuse(function, "shape.type",
                       std::string("\"") + shapeTypeName(shape.type) + "\" cannot be cast; cast a solid shape");
}

// How far a unit quaternion's norm may be from 1.
constexpr real kUnitNormTolerance = 1e-6;

void requireUnitQuaternion(const char *function, const char *field, const Quaternion &q) {
    detail::requireFinite(function, field, q);
    if (!(std::abs(q.norm() - 1) <= kUnitNormTolerance))
        detail::refuse(function, field,
                       "must be a unit quaternion (norm within 1e-6 of 1), got " + detail::show(q) + " of norm " +
                           detail::show(q.norm()));
}

// The turn from `from` to `to` (unit quaternions) the shorter way, about an axis through
// `pivot`, with the translation: angle in [0, pi]; a half turn goes about the vector part
// of to from^-1 as given.
detail::CastMotion turningMotion(const Vector3 &translation, const Vector3 &pivot, const Quaternion &from,
                                 const Quaternion &to) {
    detail::CastMotion motion;
    motion.translation = translation;
    motion.pivot = pivot;
    Quaternion relative = to.normalized() * from.normalized().conjugate();
    if (relative.w() < 0) relative.coeffs() = -relative.coeffs();
    const real sine = relative.vec().norm();
    if (!(sine > 0)) return motion;
    motion.axis = relative.vec() / sine;
    motion.angle = 2 * std::atan2(sine, relative.w());
    return motion;
}

}  // namespace

std::optional<ShapeCastHit> detail::shapeCast(const QueryScene &scene, const Shape &shape, const Vector3 &position,
                                              const Quaternion &orientation, const Vector3 &translation,
                                              const QueryFilter &filter) {
    static const char *function = "World::shapeCast";
    detail::requirePlace(function, "position", position);
    detail::requireFinite(function, "orientation", orientation);
    detail::requireFinite(function, "translation", translation);
    if (!(translation.stableNorm() > 0))
        detail::refuse(function, "translation", "must not be zero, got " + detail::show(translation));
    requireCastable(function, shape);
    const PlacedShape placed = placeQueryShape(function, shape, position, orientation);
    const std::shared_ptr<const detail::CollisionShape> &compiled = placed.shape;
    const Matrix4 &start = placed.pose;
    detail::requireReach(function, "translation", start.translation() + translation, compiled->boundingRadius());

    // Every body whose box meets the box swept by the shape's.
    const fcl::CollisionObjectd query(compiled->geometry(), start);
    fcl::AABBd swept = query.getAABB();
    swept += fcl::AABBd(swept.min_ + translation, swept.max_ + translation);
    detail::CastMotion motion;
    motion.translation = translation;
    motion.pivot = position;
    return castAmong(scene, *compiled, start, motion, swept, filter);
}

detail::CastMotion detail::checkedTurn(const Vector3 &position, const Quaternion &orientation,
                                       const Vector3 &translation, const Quaternion &endOrientation) {
    static const char *function = "World::shapeCast";
    detail::requirePlace(function, "position", position);
    requireUnitQuaternion(function, "orientation", orientation);
    detail::requireFinite(function, "translation", translation);
    requireUnitQuaternion(function, "endOrientation", endOrientation);
    return turningMotion(translation, position, orientation, endOrientation);
}

std::optional<ShapeCastHit> detail::turningCast(const QueryScene &scene, const Shape &shape, const Vector3 &position,
                                                const Quaternion &orientation, const CastMotion &motion,
                                                const QueryFilter &filter) {
    static const char *function = "World::shapeCast";
    const Vector3 &translation = motion.translation;
    requireCastable(function, shape);
    const PlacedShape placed = placeQueryShape(function, shape, position, orientation);
    const real radius = placed.shape->boundingRadius();
    detail::requireReach(function, "translation", motion.at(placed.pose, 1).translation(), radius);

    // Every point stays within `reach` of the pivot, which moves along the translation.
    const real reach = motion.reach(placed.pose, radius);
    const Vector3 widen = Vector3::Constant(reach);
    fcl::AABBd swept(position - widen, position + widen);
    swept += fcl::AABBd(position + translation - widen, position + translation + widen);
    return castAmong(scene, *placed.shape, placed.pose, motion, swept, filter);
}

}  // namespace cyclone
