// Validation and compilation of shapes, their unit inertia and supporting features.
//
// Supporting features follow Jolt's GetSupportingFace: flat-faced shapes always give the
// face most aligned with the direction, and the narrowphase keeps only the clipped points
// that are within the speculative distance. Curved shapes give a polygon or a segment
// only when the direction is close to where the shape is flat (a cylinder's cap or side,
// a capsule's side) and one point otherwise.
#include "collision/collision_shape.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include "collision/broadphase.h"
#include "collision/convex_hull.h"
#include "collision/heightfield.h"
#include "collision/mesh_features.h"
#include "cyclone/world/error.h"
#include "cyclone/world/settings.h"

namespace cyclone::detail {
namespace {

constexpr real kPi = 3.14159265358979323846;
// A capsule's or cylinder's side is a segment when the axis is within 5 degrees of
// perpendicular to the direction: sin(5 deg).
constexpr real kSideSine = 0.08715574274765817;
// A cylinder's cap is a polygon when the axis is within 15 degrees of the direction:
// cos(15 deg). Rim points beyond the speculative distance are dropped by clipping.
constexpr real kCapCosine = 0.9659258262890683;
// Beyond 1 degree of tilt the exact deepest rim point is added to the cap polygon; below
// it, the direction of tilt is noise and the fixed vertices alone keep contacts steady.
constexpr real kRimPointSine = 0.01745240643728351;
constexpr int kCapVertices = 16;

// The cap polygon's vertex directions, computed once.
struct CapCircle {
    real cosine[kCapVertices];
    real sine[kCapVertices];
    CapCircle() {
        for (int i = 0; i < kCapVertices; ++i) {
            cosine[i] = std::cos(2 * kPi * i / kCapVertices);
            sine[i] = std::sin(2 * kPi * i / kCapVertices);
        }
    }
};

// Half size of the square a plane gives as its feature, m. The narrowphase treats a
// plane as unbounded and never clips against these corners.
constexpr real kPlaneFeatureHalfSize = 1000;

std::string str(real value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string index(const char *field, size_t i) { return std::string(field) + "[" + std::to_string(i) + "]"; }

[[noreturn]] void refuse(const std::string &field, const std::string &problem) {
    throw InvalidArgument("", field, problem);
}

void requirePositive(const std::string &field, real value) {
    if (!(std::isfinite(value) && value > 0)) refuse(field, "must be finite and > 0, got " + str(value));
}

void requireFinite(const std::string &field, real value) {
    if (!std::isfinite(value)) refuse(field, "must be finite, got " + str(value));
}

void requireFinite(const std::string &field, const Vector3 &value) {
    for (int k = 0; k < 3; ++k) requireFinite(index(field.c_str(), static_cast<size_t>(k)), value[k]);
}

Matrix3 boxInertia(const Vector3 &h) {
    // (1/12)(b^2 + c^2) with full sizes b = 2 h_y, c = 2 h_z: (h_y^2 + h_z^2) / 3.
    return Vector3(h.y() * h.y() + h.z() * h.z(), h.x() * h.x() + h.z() * h.z(), h.x() * h.x() + h.y() * h.y())
               .asDiagonal() *
           (real(1) / 3);
}

Matrix3 cylinderInertia(real r, real length) {
    const real side = (3 * r * r + length * length) / 12;
    return Vector3(side, side, r * r / 2).asDiagonal();
}

Matrix3 capsuleInertia(real r, real length) {
    // Mass splits by volume between the cylinder (length L) and the two hemispheres
    // (together one sphere). A hemisphere of mass m has 2/5 m r^2 about any diameter of
    // its flat face; its centre of mass is 3r/8 from that face, which is L/2 from the
    // capsule's centre, so across the axis it contributes
    // m (2/5 r^2 - (3r/8)^2 + (L/2 + 3r/8)^2) = m (2/5 r^2 + L^2/4 + 3 L r / 8).
    const real cylinderVolume = kPi * r * r * length;
    const real sphereVolume = 4 * kPi * r * r * r / 3;
    const real total = cylinderVolume + sphereVolume;
    const real mc = cylinderVolume / total;
    const real ms = sphereVolume / total;
    const real side = mc * (3 * r * r + length * length) / 12 +
                      ms * (real(2) / 5 * r * r + length * length / 4 + 3 * length * r / 8);
    const real axial = mc * r * r / 2 + ms * real(2) / 5 * r * r;
    return Vector3(side, side, axial).asDiagonal();
}

// The broadphase's geometry of a compound: a box the size of its children's bounds whose
// local AABB (and the bounding sphere FCL places rotated boxes by) is theirs, which need
// not be centred on the centre of mass. FCL recomputes a geometry's local AABB whenever a
// collision object is made of it, hence the override. Only the broadphase and queries'
// tree walks see it; the children are what collide.
class CompoundBounds : public fcl::Boxd {
public:
    explicit CompoundBounds(const fcl::AABBd &bounds) : fcl::Boxd(bounds.max_ - bounds.min_), bounds_(bounds) {}
    void computeLocalAABB() override {
        aabb_local = bounds_;
        aabb_center = boxCentre(bounds_);
        aabb_radius = 0.5 * (bounds_.max_ - bounds_.min_).norm();
    }

private:
    fcl::AABBd bounds_;
};

// Radius of the ball about a compiled solid's origin that it holds: the nearest of a
// hull's face planes, a box's or cylinder's smallest half size; -1 for the others and
// for a hull whose origin lies outside it or on its surface.
real solidInnerRadius(const CollisionShape &c) {
    const Shape &shape = c.shape();
    switch (shape.type) {
        case ShapeType::Box: return shape.halfExtents.minCoeff();
        case ShapeType::Sphere:
        case ShapeType::Capsule: return shape.radius;
        case ShapeType::Cylinder: return std::min(shape.radius, shape.length / 2);
        case ShapeType::Convex: {
            // The nearest face plane, each at its first vertex's offset.
            real r = std::numeric_limits<real>::infinity();
            for (std::size_t f = 0; f < c.faces().size(); ++f)
                r = std::min(r, c.faceNormals()[f].dot(c.vertices()[c.faces()[f][0]]));
            return r > 0 ? r : -1;
        }
        default: return -1;
    }
}

// Farthest point of a compiled solid (or mesh) from its origin; 0 for a plane.
real solidBoundingRadius(const CollisionShape &c) {
    const Shape &shape = c.shape();
    switch (shape.type) {
        case ShapeType::Box: return shape.halfExtents.norm();
        case ShapeType::Sphere: return shape.radius;
        case ShapeType::Capsule: return shape.radius + shape.length / 2;
        case ShapeType::Cylinder: return std::hypot(shape.radius, shape.length / 2);
        case ShapeType::Convex:
        case ShapeType::Mesh: {
            real r = 0;
            for (const Vector3 &v : c.vertices()) r = std::max(r, v.norm());
            return r;
        }
        case ShapeType::Heightfield: {
            const fcl::AABBd &box = c.geometry()->aabb_local;
            return Vector3(box.max_.x(), std::max(std::abs(box.min_.y()), std::abs(box.max_.y())), box.max_.z()).norm();
        }
        case ShapeType::Plane:
        case ShapeType::Compound: break;
    }
    return 0;
}

void compileConvex(const Shape &shape, std::vector<Vector3> &vertices, std::vector<std::vector<int>> &faces,
                   std::vector<Vector3> &normals, Matrix3 &inertia, real &volume, Vector3 &centroid,
                   std::shared_ptr<fcl::CollisionGeometryd> &geometry) {
    for (size_t i = 0; i < shape.vertices.size(); ++i) requireFinite(index("shape.vertices", i), shape.vertices[i]);
    if (shape.vertices.size() < 4)
        refuse("shape.vertices", "needs at least 4 points, got " + std::to_string(shape.vertices.size()));
    ConvexHull hull;
    if (!computeConvexHull(shape.vertices, hull))
        refuse("shape.vertices", "are all coplanar (or coincident): their hull has no volume");
    if (hull.vertices.size() > static_cast<size_t>(kMaxHullVertices)) {
        // Each step's support and clipping work grows with the vertex count: keep the hull
        // of a well-spread subset of the corners (Shape::convex states the bound).
        real cover = 0;
        const std::vector<Vector3> corners = spreadSubset(hull.vertices, kMaxHullVertices, cover);
        if (!computeConvexHull(corners, hull))
            refuse("shape.vertices", "have more than " + std::to_string(kMaxHullVertices) +
                                         " hull corners and no well-spread subset of them spans a volume");
    }
    polyhedronMassProperties(hull.vertices, hull.faces, volume, inertia, centroid);
    if (!(volume > 0)) refuse("shape.vertices", "span no volume");

    auto fclVertices = std::make_shared<std::vector<fcl::Vector3d>>(hull.vertices.begin(), hull.vertices.end());
    auto fclFaces = std::make_shared<std::vector<int>>();
    for (const std::vector<int> &face : hull.faces) {
        fclFaces->push_back(static_cast<int>(face.size()));
        fclFaces->insert(fclFaces->end(), face.begin(), face.end());
    }
    geometry = std::make_shared<fcl::Convexd>(fclVertices, static_cast<int>(hull.faces.size()), fclFaces);
    vertices = std::move(hull.vertices);
    faces = std::move(hull.faces);
    normals = std::move(hull.normals);
}

void compileMesh(const Shape &shape, std::vector<Vector3> &vertices, std::vector<std::vector<int>> &faces,
                 std::vector<Vector3> &normals, std::shared_ptr<fcl::CollisionGeometryd> &geometry) {
    for (size_t i = 0; i < shape.vertices.size(); ++i) requireFinite(index("shape.vertices", i), shape.vertices[i]);
    if (shape.triangles.empty()) refuse("shape.triangles", "must not be empty");
    if (shape.sides != MeshSides::Both && shape.sides != MeshSides::Front && shape.sides != MeshSides::Back)
        refuse("shape.sides", "must be MeshSides::Both, Front or Back, got " + std::to_string(static_cast<int>(shape.sides)));
    const int count = static_cast<int>(shape.vertices.size());
    for (size_t t = 0; t < shape.triangles.size(); ++t) {
        const std::array<int, 3> &triangle = shape.triangles[t];
        const std::string field = index("shape.triangles", t);
        for (size_t k = 0; k < 3; ++k) {
            if (triangle[k] < 0 || triangle[k] >= count)
                refuse(index(field.c_str(), k), "must be a vertex index in [0, " + std::to_string(count) + "), got " +
                                                    std::to_string(triangle[k]));
            for (size_t j = 0; j < k; ++j)
                if (triangle[j] == triangle[k])
                    refuse(index(field.c_str(), k), "repeats vertex " + std::to_string(triangle[k]) + " of its triangle");
        }
        const Vector3 &p0 = shape.vertices[triangle[0]];
        const Vector3 e1 = shape.vertices[triangle[1]] - p0;
        const Vector3 e2 = shape.vertices[triangle[2]] - p0;
        const Vector3 cross = e1.cross(e2);
        const real scale = std::max(e1.squaredNorm(), e2.squaredNorm());
        if (!(cross.norm() > 1e-12 * scale)) refuse(field, "has zero area (its vertices are collinear)");
        faces.push_back({triangle[0], triangle[1], triangle[2]});
        normals.push_back(cross.normalized());
    }
    vertices = shape.vertices;

    auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    std::vector<fcl::Vector3d> points(vertices.begin(), vertices.end());
    std::vector<fcl::Triangle> triangles;
    triangles.reserve(shape.triangles.size());
    for (const std::array<int, 3> &t : shape.triangles) triangles.emplace_back(t[0], t[1], t[2]);
    model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
    model->addSubModel(points, triangles);
    model->endModel();
    geometry = model;
}

// A box's face most aligned with `direction`, counter-clockwise seen from outside.
void boxFeature(const Vector3 &h, const Matrix3 &rotation, const Vector3 &origin, const Vector3 &direction,
                SupportFeature &out) {
    const Vector3 local = rotation.transpose() * direction;
    int axis = 0;
    local.cwiseAbs().maxCoeff(&axis);
    const int j = (axis + 1) % 3;
    const int k = (axis + 2) % 3;
    const real sign = local[axis] >= 0 ? 1 : -1;
    // Counter-clockwise about +e_axis is (-,-) (+,-) (+,+) (-,+) in (e_j, e_k);
    // about -e_axis the same loop runs backwards.
    static constexpr real corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int n = 0; n < 4; ++n) {
        const real *corner = corners[sign > 0 ? n : 3 - n];
        Vector3 p;
        p[axis] = sign * h[axis];
        p[j] = corner[0] * h[j];
        p[k] = corner[1] * h[k];
        out.points[n] = rotation * p + origin;
    }
    out.count = 4;
}

// A capsule's side (a segment) when `direction` is near perpendicular to its axis, else
// the support point of the nearer end.
void capsuleFeature(real radius, real length, const Matrix3 &rotation, const Vector3 &origin,
                    const Vector3 &direction, SupportFeature &out) {
    const Vector3 axis = rotation.col(2);
    const real along = axis.dot(direction);
    const Vector3 half = axis * (length / 2);
    const Vector3 offset = radius * direction;
    if (length > 0 && std::abs(along) < kSideSine) {
        // Each end sphere's own support point: exact for either end.
        out.points[0] = origin - half + offset;
        out.points[1] = origin + half + offset;
        out.count = 2;
    } else {
        out.points[0] = origin + (along >= 0 ? half : Vector3(-half)) + offset;
        out.count = 1;
    }
}

// A cylinder's cap (a polygon with the deepest rim point when tilted) when `direction` is
// near its axis, its side (a segment) when near perpendicular, else the deepest rim point.
void cylinderFeature(real radius, real length, const Matrix3 &rotation, const Vector3 &origin,
                     const Vector3 &direction, SupportFeature &out) {
    const Vector3 axis = rotation.col(2);
    const real along = axis.dot(direction);
    const real sign = along >= 0 ? 1 : -1;
    const Vector3 perpendicular = direction - along * axis;
    const real tilt = perpendicular.norm();
    const Vector3 capCentre = origin + axis * (sign * length / 2);
    const real r = radius;
    if (std::abs(along) >= kCapCosine) {
        const Vector3 u = rotation.col(0);
        const Vector3 v = rotation.col(1);
        const real step = 2 * kPi / kCapVertices;
        real rimAngle = -1;
        if (tilt > kRimPointSine) {
            rimAngle = std::atan2(perpendicular.dot(v), perpendicular.dot(u));
            if (rimAngle < 0) rimAngle += 2 * kPi;
        }
        static const CapCircle circle;
        int n = 0;
        for (int i = 0; i < kCapVertices; ++i) {
            const real angle = i * step;
            out.points[n++] = capCentre + r * (circle.cosine[i] * u + circle.sine[i] * v);
            if (rimAngle > angle + 1e-6 && rimAngle < angle + step - 1e-6)
                out.points[n++] = capCentre + r * (perpendicular / tilt);
        }
        out.count = n;
        // The loop runs counter-clockwise about +axis; the bottom cap faces -axis.
        if (sign < 0) std::reverse(out.points, out.points + n);
    } else if (std::abs(along) < kSideSine) {
        const Vector3 offset = r * (perpendicular / tilt);
        const Vector3 half = axis * (length / 2);
        out.points[0] = origin - half + offset;
        out.points[1] = origin + half + offset;
        out.count = 2;
    } else {
        out.points[0] = capCentre + r * (perpendicular / tilt);
        out.count = 1;
    }
}

// A convex hull's face (of `faces`, outward `normals`, corners in `vertices`) most
// aligned with `direction`.
void hullFeature(const std::vector<Vector3> &normals, const std::vector<std::vector<int>> &faces,
                 const std::vector<Vector3> &vertices, const Matrix3 &rotation, const Vector3 &origin,
                 const Vector3 &direction, SupportFeature &out) {
    const Vector3 local = rotation.transpose() * direction;
    size_t best = 0;
    real bestDot = -2;
    for (size_t f = 0; f < normals.size(); ++f) {
        const real d = normals[f].dot(local);
        if (d > bestDot) bestDot = d, best = f;
    }
    const std::vector<int> &face = faces[best];
    const int size = static_cast<int>(face.size());
    // A face with more corners than a feature holds keeps an evenly spaced subset,
    // which is still a convex loop in the same order.
    const int n = std::min(size, SupportFeature::kMaxPoints);
    for (int i = 0; i < n; ++i) out.points[i] = rotation * vertices[face[i * size / n]] + origin;
    out.count = n;
}

// A plane's feature: a large square about the point nearest the body's origin.
void planeFeature(const Vector3 &localNormal, real offset, const Matrix3 &rotation, const Vector3 &origin,
                  SupportFeature &out) {
    const Vector3 normal = rotation * localNormal;
    const Vector3 centre = origin + offset * normal;
    const Vector3 u = normal.unitOrthogonal() * kPlaneFeatureHalfSize;
    const Vector3 v = normal.cross(u);
    out.points[0] = centre - u - v;
    out.points[1] = centre + u - v;
    out.points[2] = centre + u + v;
    out.points[3] = centre - u + v;
    out.count = 4;
}

// A mesh's triangle `t` with its `normal` (in the body's frame): in its order when the
// normal is along `direction`, else reversed.
void triangleFeature(const std::vector<int> &t, const Vector3 &normal, const std::vector<Vector3> &vertices,
                     const Matrix3 &rotation, const Vector3 &origin, const Vector3 &direction, SupportFeature &out) {
    const bool facing = (rotation * normal).dot(direction) >= 0;
    for (int i = 0; i < 3; ++i) out.points[i] = rotation * vertices[t[facing ? i : 2 - i]] + origin;
    out.count = 3;
}

}  // namespace

// Mass properties at one density: child k holds the fraction V_k / V of the mass at its
// centroid c_k, so the centre of mass is sum (V_k / V) c_k, and the inertia about it is
// each child's own (turned into the frame's axes, R I R^T) plus the parallel-axis term
// m_k (|d|^2 E - d d^T) for its offset d from the centre of mass.
void compileCompound(const Shape &shape, CollisionShape &c) {
    if (shape.children.empty()) refuse("shape.children", "must hold at least one child");
    std::vector<CompoundPart> parts;
    std::vector<Vector3> centroids;
    real volume = 0;
    Vector3 moment = Vector3::Zero();
    for (std::size_t k = 0; k < shape.children.size(); ++k) {
        const CompoundChild &child = shape.children[k];
        const std::string field = index("shape.children", k);
        const ShapeType type = child.shape.type;
        if (type == ShapeType::Plane || type == ShapeType::Mesh || type == ShapeType::Compound ||
            type == ShapeType::Heightfield)
            refuse(field + ".shape.type", std::string("\"") + shapeTypeName(type) +
                                              "\" is not a convex shape; a compound's children are box, sphere, "
                                              "capsule, cylinder or convex");
        requireFinite(field + ".position", child.position);
        if (!child.orientation.coeffs().allFinite())
            refuse(field + ".orientation", "must be finite, got [" + str(child.orientation.w()) + ", " +
                                               str(child.orientation.x()) + ", " + str(child.orientation.y()) +
                                               ", " + str(child.orientation.z()) + "]");
        std::shared_ptr<const CollisionShape> compiled;
        try {
            compiled = compileShape(child.shape);
        } catch (const InvalidArgument &e) {
            refuse(field + "." + e.field(), e.problem());
        }
        const real reach = child.position.stableNorm() + compiled->boundingRadius();
        if (!(reach <= kMaxCoordinate))
            refuse(field + ".position", "puts the child " + str(reach) +
                                            " m from the compound's frame; every child must be within 1e12 m of it");
        const real length = child.orientation.norm();
        const Quaternion q = length > 0 ? Quaternion(child.orientation.coeffs() / length) : Quaternion::Identity();
        CompoundPart part;
        part.shape = compiled;
        part.pose.linear() = q.toRotationMatrix();
        part.pose.translation() = child.position;
        centroids.push_back(part.pose * compiled->centroid());
        volume += compiled->volume();
        moment += compiled->volume() * centroids.back();
        parts.push_back(std::move(part));
    }
    const Vector3 centre = moment / volume;
    Matrix3 inertia = Matrix3::Zero();
    fcl::AABBd box;
    real radius = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        CompoundPart &part = parts[k];
        const CollisionShape &child = *part.shape;
        const real fraction = child.volume() / volume;
        // The child's unit inertia is about its own origin; about its centroid it is
        // smaller by the parallel-axis term of the centroid's offset.
        const Vector3 &g = child.centroid();
        const Matrix3 own = child.unitInertia() - (g.squaredNorm() * Matrix3::Identity() - g * g.transpose());
        const Matrix3 rotation = part.pose.linear();
        const Vector3 d = centroids[k] - centre;
        inertia += fraction * (rotation * own * rotation.transpose() +
                               (d.squaredNorm() * Matrix3::Identity() - d * d.transpose()));
        part.pose.translation() -= centre;
        const fcl::AABBd &local = child.geometry()->aabb_local;
        const Vector3 middle = part.pose * boxCentre(local);
        const Vector3 half = rotation.cwiseAbs() * (0.5 * (local.max_ - local.min_));
        const fcl::AABBd placed(middle - half, middle + half);
        if (k == 0) box = placed;
        else box += placed;
        radius = std::max(radius, part.pose.translation().norm() + child.boundingRadius());
    }
    auto geometry = std::make_shared<CompoundBounds>(box);
    geometry->computeLocalAABB();
    c.geometry_ = geometry;
    c.parts_ = std::move(parts);
    c.unitInertia_ = inertia;
    c.volume_ = volume;
    c.frameToCentre_ = centre;
    c.centroid_ = Vector3::Zero();
    c.boundingRadius_ = radius;
}

std::shared_ptr<const CollisionShape> compileShape(const Shape &shape) {
    auto compiled = std::make_shared<CollisionShape>();
    CollisionShape &c = *compiled;
    switch (shape.type) {
        case ShapeType::Box:
            for (size_t k = 0; k < 3; ++k) requirePositive(index("shape.half_extents", k), shape.halfExtents[k]);
            c.geometry_ = std::make_shared<fcl::Boxd>(2 * shape.halfExtents);
            c.unitInertia_ = boxInertia(shape.halfExtents);
            c.volume_ = 8 * shape.halfExtents.prod();
            break;
        case ShapeType::Sphere:
            requirePositive("shape.radius", shape.radius);
            c.geometry_ = std::make_shared<fcl::Sphered>(shape.radius);
            c.unitInertia_ = Matrix3::Identity() * (real(2) / 5 * shape.radius * shape.radius);
            c.volume_ = 4 * kPi * std::pow(shape.radius, 3) / 3;
            break;
        case ShapeType::Capsule:
            requirePositive("shape.radius", shape.radius);
            if (!(std::isfinite(shape.length) && shape.length >= 0))
                refuse("shape.length", "must be finite and >= 0, got " + str(shape.length));
            c.geometry_ = std::make_shared<fcl::Capsuled>(shape.radius, shape.length);
            c.unitInertia_ = capsuleInertia(shape.radius, shape.length);
            c.volume_ = kPi * shape.radius * shape.radius * (shape.length + 4 * shape.radius / 3);
            break;
        case ShapeType::Cylinder:
            requirePositive("shape.radius", shape.radius);
            requirePositive("shape.length", shape.length);
            c.geometry_ = std::make_shared<fcl::Cylinderd>(shape.radius, shape.length);
            c.unitInertia_ = cylinderInertia(shape.radius, shape.length);
            c.volume_ = kPi * shape.radius * shape.radius * shape.length;
            break;
        case ShapeType::Convex:
            compileConvex(shape, c.vertices_, c.faces_, c.faceNormals_, c.unitInertia_, c.volume_, c.centroid_,
                          c.geometry_);
            c.hullEdges_ = std::make_shared<const HullEdges>(makeHullEdges(c.vertices_, c.faces_, c.faceNormals_));
            break;
        case ShapeType::Plane: {
            requireFinite("shape.normal", shape.normal);
            requireFinite("shape.offset", shape.offset);
            const real length = shape.normal.stableNorm();
            if (!(length > 0)) refuse("shape.normal", "must have non-zero length");
            // The solid is normal.x <= offset; dividing both sides by |normal| keeps it.
            c.planeNormal_ = shape.normal / length;
            c.planeOffset_ = shape.offset / length;
            c.geometry_ = std::make_shared<fcl::Halfspaced>(c.planeNormal_, c.planeOffset_);
            break;
        }
        case ShapeType::Mesh:
            compileMesh(shape, c.vertices_, c.faces_, c.faceNormals_, c.geometry_);
            c.activeFeatures_ = meshActiveFeatures(c.vertices_, c.faces_, c.faceNormals_);
            break;
        case ShapeType::Heightfield: {
            validateHeightfield(shape);
            c.shape_ = Shape::heightfield(shape.rows, shape.columns, shape.spacing, copyHeights(shape.heights));
            c.geometry_ = heightfieldBounds(HeightfieldGrid(c.shape_));
            c.boundingRadius_ = solidBoundingRadius(c);
            return compiled;
        }
        case ShapeType::Compound:
            compileCompound(shape, c);
            c.shape_ = shape;
            return compiled;
        default:
            refuse("shape.type", "is not a known shape type");
    }
    c.geometry_->computeLocalAABB();
    c.shape_ = shape;
    c.boundingRadius_ = solidBoundingRadius(c);
    c.innerRadius_ = solidInnerRadius(c);
    return compiled;
}

std::size_t CollisionShape::furthestPart(const Matrix4 &pose, const Vector3 &direction) const {
    std::size_t best = 0;
    real bestAlong = -std::numeric_limits<real>::infinity();
    for (std::size_t k = 0; k < parts_.size(); ++k) {
        const real along = parts_[k].shape->supportPoint(pose * parts_[k].pose, direction, -1).dot(direction);
        if (along > bestAlong) bestAlong = along, best = k;
    }
    return best;
}

void CollisionShape::supportingFeature(const Matrix4 &pose, const Vector3 &direction, int triangle,
                                       SupportFeature &out) const {
    const Matrix3 rotation = pose.linear();
    const Vector3 origin = pose.translation();
    out.count = 0;
    switch (shape_.type) {
        case ShapeType::Box: boxFeature(shape_.halfExtents, rotation, origin, direction, out); break;
        case ShapeType::Sphere:
            out.points[0] = origin + shape_.radius * direction;
            out.count = 1;
            break;
        case ShapeType::Capsule:
            capsuleFeature(shape_.radius, shape_.length, rotation, origin, direction, out);
            break;
        case ShapeType::Cylinder:
            cylinderFeature(shape_.radius, shape_.length, rotation, origin, direction, out);
            break;
        case ShapeType::Convex:
            hullFeature(faceNormals_, faces_, vertices_, rotation, origin, direction, out);
            break;
        case ShapeType::Plane: planeFeature(planeNormal_, planeOffset_, rotation, origin, out); break;
        case ShapeType::Compound: {
            const std::size_t k = furthestPart(pose, direction);
            parts_[k].shape->supportingFeature(pose * parts_[k].pose, direction, -1, out);
            break;
        }
        case ShapeType::Mesh:
            if (triangle < 0 || triangle >= static_cast<int>(faces_.size())) break;
            triangleFeature(faces_[triangle], faceNormals_[triangle], vertices_, rotation, origin, direction, out);
            break;
        case ShapeType::Heightfield: {
            if (triangle < 0 || triangle >= triangleCount()) break;
            Vector3 corners[3];
            int ids[3];
            this->triangle(triangle, corners, ids);
            const bool facing = (rotation * triangleNormal(triangle)).dot(direction) >= 0;
            for (int i = 0; i < 3; ++i) out.points[i] = rotation * corners[facing ? i : 2 - i] + origin;
            out.count = 3;
            break;
        }
    }
}

const HullEdges &CollisionShape::hullEdges() const {
    static const HullEdges none;
    return hullEdges_ ? *hullEdges_ : none;
}

Vector3 CollisionShape::supportPoint(const Matrix4 &pose, const Vector3 &direction, int triangle) const {
    const Matrix3 rotation = pose.linear();
    const Vector3 origin = pose.translation();
    switch (shape_.type) {
        case ShapeType::Box: {
            const Vector3 local = rotation.transpose() * direction;
            Vector3 corner;
            for (int k = 0; k < 3; ++k) corner[k] = local[k] >= 0 ? shape_.halfExtents[k] : -shape_.halfExtents[k];
            return rotation * corner + origin;
        }
        case ShapeType::Sphere:
            return origin + shape_.radius * direction;
        case ShapeType::Capsule: {
            const Vector3 axis = rotation.col(2);
            const real end = axis.dot(direction) >= 0 ? shape_.length / 2 : -shape_.length / 2;
            return origin + end * axis + shape_.radius * direction;
        }
        case ShapeType::Cylinder: {
            const Vector3 axis = rotation.col(2);
            const real along = axis.dot(direction);
            const Vector3 perpendicular = direction - along * axis;
            const real tilt = perpendicular.norm();
            Vector3 p = origin + axis * (along >= 0 ? shape_.length / 2 : -shape_.length / 2);
            if (tilt > 1e-12) p += shape_.radius / tilt * perpendicular;
            return p;
        }
        case ShapeType::Convex: {
            const Vector3 local = rotation.transpose() * direction;
            size_t best = 0;
            real bestDot = vertices_[0].dot(local);
            for (size_t i = 1; i < vertices_.size(); ++i) {
                const real d = vertices_[i].dot(local);
                if (d > bestDot) bestDot = d, best = i;
            }
            return rotation * vertices_[best] + origin;
        }
        case ShapeType::Plane:
            return origin + planeOffset_ * (rotation * planeNormal_);
        case ShapeType::Compound: {
            const std::size_t k = furthestPart(pose, direction);
            return parts_[k].shape->supportPoint(pose * parts_[k].pose, direction, -1);
        }
        case ShapeType::Mesh:
        case ShapeType::Heightfield: {
            if (triangle < 0 || triangle >= triangleCount()) return origin;
            const Vector3 local = rotation.transpose() * direction;
            Vector3 corners[3];
            int ids[3];
            this->triangle(triangle, corners, ids);
            int best = 0;
            for (int i = 1; i < 3; ++i)
                if (corners[i].dot(local) > corners[best].dot(local)) best = i;
            return rotation * corners[best] + origin;
        }
    }
    return origin;
}

int CollisionShape::triangleCount() const {
    if (shape_.type == ShapeType::Heightfield) return HeightfieldGrid(shape_).triangleCount();
    return static_cast<int>(faces_.size());
}

void CollisionShape::triangle(int t, Vector3 (&corners)[3], int (&ids)[3]) const {
    if (shape_.type == ShapeType::Heightfield) {
        HeightfieldGrid(shape_).triangle(t, corners, ids);
        return;
    }
    for (int k = 0; k < 3; ++k) {
        ids[k] = faces_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
        corners[k] = vertices_[static_cast<std::size_t>(ids[k])];
    }
}

std::uint8_t CollisionShape::activeFeatures(int t) const {
    if (shape_.type == ShapeType::Heightfield) return HeightfieldGrid(shape_).activeFeatures(t);
    return activeFeatures_[static_cast<std::size_t>(t)];
}

Vector3 CollisionShape::triangleNormal(int t) const {
    if (shape_.type == ShapeType::Heightfield) return HeightfieldGrid(shape_).normal(t);
    return faceNormals_[static_cast<std::size_t>(t)];
}

}  // namespace cyclone::detail
