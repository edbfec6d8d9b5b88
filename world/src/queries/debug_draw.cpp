// Debug drawing: the World's bodies, boxes and contacts as lines through the game's
// DebugDraw. Curved shapes are outlined by circles in their frames and the lines that
// join them; hulls and meshes by their edges.
#include <cmath>
#include <string>

#include "collision/heightfield.h"
#include "queries/debug_draw.h"
#include "world/validation.h"

namespace cyclone {

using detail::BodyRecord;
namespace {

constexpr real kPi = 3.14159265358979323846;

// The game's DebugDraw, checked after each call: a DebugDraw must only read the World,
// and one that changed it (removed a body, stepped) has pulled the records and contacts
// being drawn from under the walk, so the walk stops before touching them again.
class CheckedDraw final : public DebugDraw {
public:
    CheckedDraw(DebugDraw &draw, const std::uint64_t &changingCalls)
        : draw_(draw), changingCalls_(changingCalls), calls_(changingCalls) {}
    void line(const Vector3 &from, const Vector3 &to, const DebugColor &color) override {
        draw_.line(from, to, color);
        check();
    }
    void box(const Matrix4 &pose, const Vector3 &halfExtents, const DebugColor &color) override {
        draw_.box(pose, halfExtents, color);
        check();
    }
    void circle(const Vector3 &centre, const Vector3 &normal, real radius, int segments,
                const DebugColor &color) override {
        draw_.circle(centre, normal, radius, segments, color);
        check();
    }
    void contact(const Vector3 &point, const Vector3 &normal, real depth, real normalLength,
                 const DebugColor &pointColor, const DebugColor &normalColor) override {
        draw_.contact(point, normal, depth, normalLength, pointColor, normalColor);
        check();
    }

private:
    void check() const {
        if (changingCalls_ != calls_)
            detail::refuse("World::debugDraw", "draw",
                           "changed the world while drawing (called a World member that changes it, such as "
                           "removeBody or step); a DebugDraw must only read");
    }
    DebugDraw &draw_;
    const std::uint64_t &changingCalls_;  ///< WorldState::changingCalls, read after each call.
    const std::uint64_t calls_;
};

// The points of an arc of `radius` around `centre`, from angle `from` to `to` (rad) in
// the plane spanned by the unit vectors u and v, as `segments` lines.
template <class Draw>
void arc(Draw &draw, const Vector3 &centre, const Vector3 &u, const Vector3 &v, real radius, real from, real to,
         int segments, const DebugColor &color) {
    Vector3 previous = centre + radius * (std::cos(from) * u + std::sin(from) * v);
    for (int i = 1; i <= segments; ++i) {
        const real angle = from + (to - from) * i / segments;
        const Vector3 next = centre + radius * (std::cos(angle) * u + std::sin(angle) * v);
        draw.line(previous, next, color);
        previous = next;
    }
}

// A capsule (two circles, four side lines and its end caps' half circles) or a
// cylinder (two circles and four side lines), along local z.
void drawRound(CheckedDraw &draw, const Shape &s, const Matrix4 &pose, int segments, const DebugColor &color) {
    const Matrix3 rotation = pose.linear();
    const Vector3 x = rotation.col(0);
    const Vector3 y = rotation.col(1);
    const Vector3 z = rotation.col(2);
    const Vector3 top = pose.translation() + z * (s.length / 2);
    const Vector3 bottom = pose.translation() - z * (s.length / 2);
    draw.circle(top, z, s.radius, segments, color);
    draw.circle(bottom, z, s.radius, segments, color);
    if (s.type == ShapeType::Cylinder) {
        for (const Vector3 &side : {x, y, Vector3(-x), Vector3(-y)})
            draw.line(top + s.radius * side, bottom + s.radius * side, color);
        return;
    }
    for (const Vector3 &side : {x, y}) {
        draw.line(top + s.radius * side, bottom + s.radius * side, color);
        draw.line(top - s.radius * side, bottom - s.radius * side, color);
        // The end caps: half circles over the ends, in the planes of x and y.
        arc(draw, top, side, z, s.radius, 0, kPi, segments / 2, color);
        arc(draw, bottom, side, z, s.radius, kPi, 2 * kPi, segments / 2, color);
    }
}

// Each sample's lines to its next neighbours along x and z and along the diagonal of the
// cell it opens: every edge of every triangle once.
void drawHeightfield(CheckedDraw &draw, const Shape &s, const Matrix4 &pose, const DebugColor &color) {
    const detail::HeightfieldGrid grid(s);
    for (int i = 0; i < grid.rows; ++i)
        for (int j = 0; j < grid.columns; ++j) {
            const Vector3 p = pose * grid.sample(i, j);
            if (j + 1 < grid.columns) draw.line(p, pose * grid.sample(i, j + 1), color);
            if (i + 1 < grid.rows) draw.line(p, pose * grid.sample(i + 1, j), color);
            if (i + 1 < grid.rows && j + 1 < grid.columns) draw.line(p, pose * grid.sample(i + 1, j + 1), color);
        }
}

// A square around the plane's point nearest the world origin, its diagonals, and its normal.
void drawPlane(CheckedDraw &draw, const detail::CollisionShape &shape, const Matrix4 &pose,
               const DebugDrawOptions &options, const DebugColor &color) {
    const Vector3 normal = pose.linear() * shape.planeNormal();
    const Vector3 onPlane = pose.translation() + shape.planeOffset() * normal;
    const Vector3 centre = onPlane - normal.dot(onPlane) * normal;
    const Vector3 u = normal.unitOrthogonal() * options.planeHalfSize;
    const Vector3 w = normal.cross(u);
    const Vector3 corners[4] = {centre - u - w, centre + u - w, centre + u + w, centre - u + w};
    for (int i = 0; i < 4; ++i) draw.line(corners[i], corners[(i + 1) % 4], color);
    draw.line(corners[0], corners[2], color);
    draw.line(corners[1], corners[3], color);
    draw.line(centre, centre + options.normalLength * normal, color);
}

void drawShape(CheckedDraw &draw, const detail::CollisionShape &shape, const Matrix4 &pose,
               const DebugDrawOptions &options, const DebugColor &color) {
    const Shape &s = shape.shape();
    const Matrix3 rotation = pose.linear();
    const Vector3 origin = pose.translation();
    const Vector3 x = rotation.col(0);
    const Vector3 y = rotation.col(1);
    const Vector3 z = rotation.col(2);
    const int segments = options.circleSegments;
    switch (s.type) {
        case ShapeType::Compound:
            for (std::size_t k = 0; k < shape.children().size(); ++k)
                drawShape(draw, *shape.children()[k].shape, detail::partPose(shape, k, pose), options, color);
            break;
        case ShapeType::Box: draw.box(pose, s.halfExtents, color); break;
        case ShapeType::Sphere:
            draw.circle(origin, x, s.radius, segments, color);
            draw.circle(origin, y, s.radius, segments, color);
            draw.circle(origin, z, s.radius, segments, color);
            break;
        case ShapeType::Capsule:
        case ShapeType::Cylinder: drawRound(draw, s, pose, segments, color); break;
        case ShapeType::Convex: {
            // Hull faces run counter-clockwise, so each edge appears once in each
            // direction: drawing it from its smaller vertex draws it once.
            const std::vector<Vector3> &v = shape.vertices();
            for (const std::vector<int> &face : shape.faces())
                for (std::size_t i = 0; i < face.size(); ++i) {
                    const int from = face[i];
                    const int to = face[(i + 1) % face.size()];
                    if (from < to) draw.line(pose * v[from], pose * v[to], color);
                }
            break;
        }
        case ShapeType::Mesh: {
            const std::vector<Vector3> &v = shape.vertices();
            for (const std::vector<int> &t : shape.faces())
                for (int i = 0; i < 3; ++i) draw.line(pose * v[t[i]], pose * v[t[(i + 1) % 3]], color);
            break;
        }
        case ShapeType::Heightfield: drawHeightfield(draw, s, pose, color); break;
        case ShapeType::Plane: drawPlane(draw, shape, pose, options, color); break;
    }
}

}  // namespace

void detail::validateDrawOptions(const DebugDrawOptions &o) {
    static const char *function = "World::debugDraw";
    detail::requirePositive(function, "options.normalLength", o.normalLength);
    detail::requirePositive(function, "options.planeHalfSize", o.planeHalfSize);
    detail::requirePositive(function, "options.jointSize", o.jointSize);
    if (o.circleSegments < 4 || o.circleSegments > 256)
        detail::refuse(function, "options.circleSegments",
                       "must be in [4, 256], got " + std::to_string(o.circleSegments));
    const std::pair<const char *, const DebugColor *> colors[] = {
        {"options.awake", &o.awake},           {"options.asleep", &o.asleep},
        {"options.staticBody", &o.staticBody}, {"options.isolated", &o.isolated},
        {"options.sensor", &o.sensor},
        {"options.boundingBox", &o.boundingBox}, {"options.contactPoint", &o.contactPoint},
        {"options.contactNormal", &o.contactNormal}, {"options.jointAnchor", &o.jointAnchor},
        {"options.jointAxis", &o.jointAxis},         {"options.jointLimit", &o.jointLimit}};
    for (const auto &[field, c] : colors)
        for (float channel : {c->r, c->g, c->b, c->a})
            if (!(channel >= 0 && channel <= 1))
                detail::refuse(function, field, "components must be in [0, 1], got " + detail::show(channel));
}

void DebugDraw::box(const Matrix4 &pose, const Vector3 &h, const DebugColor &color) {
    Vector3 corner[8];
    for (int i = 0; i < 8; ++i)
        corner[i] = pose * Vector3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    // Corners i and j share an edge when their indices differ in exactly one bit.
    for (int i = 0; i < 8; ++i)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(i & bit)) line(corner[i], corner[i | bit], color);
}

void DebugDraw::circle(const Vector3 &centre, const Vector3 &normal, real radius, int segments,
                       const DebugColor &color) {
    const Vector3 u = normal.unitOrthogonal();
    arc(*this, centre, u, normal.cross(u), radius, 0, 2 * kPi, segments, color);
}

void DebugDraw::contact(const Vector3 &point, const Vector3 &normal, real, real normalLength,
                        const DebugColor &pointColor, const DebugColor &normalColor) {
    const real arm = normalLength / 20;
    for (int k = 0; k < 3; ++k) {
        const Vector3 offset = Vector3::Unit(k) * arm;
        line(point - offset, point + offset, pointColor);
    }
    line(point, point + normalLength * normal, normalColor);
}

void detail::debugDraw(const DrawScene &scene, DebugDraw &game, const DebugDrawOptions &options) {
    CheckedDraw draw(game, scene.changingCalls);
    for (std::uint32_t index : scene.bodies.order) {
        const BodyRecord &r = scene.bodies[index];
        const bool isStatic = r.immovable && !r.kinematic;  // a kinematic body is drawn awake while it moves
        const DebugColor &color = r.sensor && !r.isolated ? options.sensor
                                  : isStatic   ? options.staticBody
                                  : r.isolated ? options.isolated
                                  : r.body.getAwake() ? options.awake
                                                      : options.asleep;
        const Matrix4 pose = r.body.getTransform();
        if (!pose.matrix().allFinite()) continue;  // an isolated body that flew off: nothing to draw
        if (options.shapes && (!isStatic || options.staticBodies)) drawShape(draw, *r.shape, pose, options, color);
        if (options.boundingBoxes && r.object && r.tree != detail::Tree::None) {
            const fcl::AABBd &box = r.object->getAABB();
            Matrix4 pose = Matrix4::Identity();
            pose.translation() = box.center();
            draw.box(pose, 0.5 * (box.max_ - box.min_), options.boundingBox);
        }
    }
    if (options.joints) scene.joints.draw(scene.bodies, draw, options);
    if (!options.contacts) return;
    for (std::uint32_t p = 0; p < scene.pairs.slots(); ++p) {
        const detail::PairState &pair = scene.pairs[p];
        if (!pair.alive || !pair.touching()) continue;
        const Matrix4 poseA = scene.bodies[pair.a].body.getTransform();
        const Matrix4 poseB = scene.bodies[pair.b].body.getTransform();
        for (const detail::ManifoldState &m : pair.manifolds)
            for (int i = 0; i < m.count; ++i) {
                const detail::PersistentPoint &point = m.points[i];
                const Vector3 at = 0.5 * (poseA * point.localA + poseB * point.localB);
                draw.contact(at, m.normal, point.depth, options.normalLength, options.contactPoint,
                             options.contactNormal);
            }
    }
}

}  // namespace cyclone
