// Ray tests, exact for each shape type, in the shape's own frame: the ray is moved into
// it (a rotation keeps the direction unit, so distances are the same in both frames) and
// the normal moved back out.
//
// Solids are entered from outside only: a ray that starts inside a shape leaves it and
// does not hit it (as in Box2D and Bullet), so that a ray cast from inside a trigger or
// from a character's centre ignores that body. A point exactly on the surface counts as
// outside, so a ray starting on a face and going in hits it at distance 0. Mesh triangles
// have no inside and are hit from either side. Meshes are walked through FCL's own
// bounding-volume tree (OBBs in the mesh's frame), nearest child first.
#include "collision/ray_cast.h"

#include "collision/heightfield.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cyclone::detail {
namespace {

constexpr real kInfinity = std::numeric_limits<real>::infinity();
// Directions closer than this to a plane's or an axis' orthogonal count as parallel.
constexpr real kParallel = 1e-14;
// Barycentric slack so that a ray through the shared edge of two triangles hits one.
constexpr real kEdgeSlack = 1e-12;

// Sphere of centre c, radius r: the entry distance of a ray from outside.
bool raySphere(const Vector3 &o, const Vector3 &d, const Vector3 &c, real r, real &t) {
    const Vector3 m = o - c;
    const real b = m.dot(d);
    const real outside = m.squaredNorm() - r * r;
    if (outside < 0 || b > 0) return false;  // inside, or outside and going away
    const real disc = b * b - outside;
    if (disc < 0) return false;
    t = std::max<real>(0, -b - std::sqrt(disc));
    return true;
}

// The infinite cylinder x^2 + y^2 = r^2 (axis z): the entry distance of a ray that starts
// outside it.
bool rayInfiniteCylinder(const Vector3 &o, const Vector3 &d, real r, real &t) {
    const real a = d.x() * d.x() + d.y() * d.y();
    if (a < kParallel) return false;
    const real b = o.x() * d.x() + o.y() * d.y();
    const real c = o.x() * o.x() + o.y() * o.y() - r * r;
    if (c < 0 || b > 0) return false;
    const real disc = b * b - a * c;
    if (disc < 0) return false;
    t = std::max<real>(0, (-b - std::sqrt(disc)) / a);
    return true;
}

bool rayLocalBox(const Vector3 &o, const Vector3 &d, const Vector3 &h, real limit, real &t, Vector3 &n) {
    real enter = -kInfinity;
    real exit = kInfinity;
    int axis = -1;
    for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < kParallel) {
            if (std::abs(o[k]) > h[k]) return false;
            continue;
        }
        const real t1 = (-h[k] - o[k]) / d[k];
        const real t2 = (h[k] - o[k]) / d[k];
        const real near = std::min(t1, t2);
        if (near > enter) enter = near, axis = k;
        exit = std::min(exit, std::max(t1, t2));
    }
    if (axis < 0 || enter < 0 || enter > exit || enter > limit) return false;
    t = enter;
    n = Vector3::Zero();
    n[axis] = d[axis] > 0 ? -1 : 1;
    return true;
}

// Where the ray enters the side of the cylinder of radius r about z between z = -half and
// half (infinity when it does not), with the normal there in `n`.
real rayCylinderSide(const Vector3 &o, const Vector3 &d, real r, real half, Vector3 &n) {
    real s;
    if (!rayInfiniteCylinder(o, d, r, s) || !(std::abs(o.z() + s * d.z()) <= half)) return kInfinity;
    const Vector3 p = o + s * d;
    n = Vector3(p.x(), p.y(), 0) / r;
    return s;
}

bool rayLocalCapsule(const Vector3 &o, const Vector3 &d, real r, real half, real limit, real &t, Vector3 &n) {
    const Vector3 nearest(0, 0, std::clamp(o.z(), -half, half));
    if ((o - nearest).squaredNorm() < r * r) return false;
    real best = rayCylinderSide(o, d, r, half, n);
    real s;
    for (real end : {-half, half}) {
        const Vector3 c(0, 0, end);
        if (!raySphere(o, d, c, r, s) || !(s < best)) continue;
        const Vector3 p = o + s * d;
        // Only the hemisphere beyond the end belongs to the surface.
        if ((end > 0 && p.z() < end) || (end < 0 && p.z() > end)) continue;
        best = s;
        n = (p - c) / r;
    }
    if (!(best <= limit)) return false;
    t = best;
    return true;
}

bool rayLocalCylinder(const Vector3 &o, const Vector3 &d, real r, real half, real limit, real &t, Vector3 &n) {
    const real radial2 = o.x() * o.x() + o.y() * o.y();
    if (std::abs(o.z()) < half && radial2 < r * r) return false;
    real best = rayCylinderSide(o, d, r, half, n);
    real s;
    for (real side : {real(-1), real(1)}) {
        // The cap at z = side * half, entered from beyond it.
        if (side * o.z() < half || !(side * d.z() < -kParallel)) continue;
        s = (side * half - o.z()) / d.z();
        const Vector3 p = o + s * d;
        if (s < best && p.x() * p.x() + p.y() * p.y() <= r * r) {
            best = s;
            n = Vector3(0, 0, side);
        }
    }
    if (!(best <= limit)) return false;
    t = best;
    return true;
}

bool rayLocalConvex(const Vector3 &o, const Vector3 &d, const CollisionShape &shape, real limit, real &t,
                    Vector3 &n) {
    real enter = -kInfinity;
    real exit = kInfinity;
    const std::vector<Vector3> &normals = shape.faceNormals();
    for (std::size_t f = 0; f < normals.size(); ++f) {
        const Vector3 &normal = normals[f];
        const real outside = normal.dot(o - shape.vertices()[shape.faces()[f][0]]);
        const real along = normal.dot(d);
        if (std::abs(along) < kParallel) {
            if (outside > 0) return false;
            continue;
        }
        const real s = -outside / along;
        if (along < 0) {
            if (s > enter) enter = s, n = normal;
        } else {
            exit = std::min(exit, s);
        }
    }
    if (enter < 0 || enter > exit || enter > limit) return false;
    t = enter;
    return true;
}

bool rayLocalPlane(const Vector3 &o, const Vector3 &d, const CollisionShape &shape, real limit, real &t,
                   Vector3 &n) {
    const Vector3 &normal = shape.planeNormal();
    const real outside = normal.dot(o) - shape.planeOffset();
    const real along = normal.dot(d);
    if (outside < 0 || !(along < -kParallel)) return false;
    const real s = -outside / along;
    if (s > limit) return false;
    t = s;
    n = normal;
    return true;
}

// Möller-Trumbore, two-sided: the distance to triangle `f` of a mesh, and its normal
// turned towards the ray's origin.
bool rayTriangle(const Vector3 &o, const Vector3 &d, const CollisionShape &shape, int f, real limit, real &t,
                 Vector3 &n) {
    const std::vector<int> &tri = shape.faces()[f];
    const Vector3 &v0 = shape.vertices()[tri[0]];
    const Vector3 e1 = shape.vertices()[tri[1]] - v0;
    const Vector3 e2 = shape.vertices()[tri[2]] - v0;
    const Vector3 p = d.cross(e2);
    const real det = e1.dot(p);
    if (std::abs(det) <= kParallel * e1.norm() * e2.norm()) return false;
    const real inverse = 1 / det;
    const Vector3 s = o - v0;
    const real u = s.dot(p) * inverse;
    if (u < -kEdgeSlack || u > 1 + kEdgeSlack) return false;
    const Vector3 q = s.cross(e1);
    const real v = d.dot(q) * inverse;
    if (v < -kEdgeSlack || u + v > 1 + kEdgeSlack) return false;
    const real distance = e2.dot(q) * inverse;
    if (distance < 0 || distance > limit) return false;
    t = distance;
    const Vector3 &normal = shape.faceNormals()[f];
    n = normal.dot(d) > 0 ? Vector3(-normal) : normal;
    return true;
}

// Entry distance of the ray into a node's oriented box, if within `limit`.
bool rayObb(const Vector3 &o, const Vector3 &d, const fcl::OBBd &box, real limit, real &enter) {
    const Vector3 localO = box.axis.transpose() * (o - box.To);
    const Vector3 localD = box.axis.transpose() * d;
    return rayBox(localO, localD, -box.extent, box.extent, limit, enter);
}

struct MeshWalk {
    const fcl::BVHModel<fcl::OBBRSSd> &model;
    const CollisionShape &shape;
    const Vector3 &o;
    const Vector3 &d;
    real best;
    Vector3 normal = Vector3::UnitY();
    bool found = false;

    void visit(int node) {
        const fcl::BVNode<fcl::OBBRSSd> &bv = model.getBV(node);
        if (bv.isLeaf()) {
            real t;
            Vector3 n;
            if (rayTriangle(o, d, shape, bv.primitiveId(), best, t, n) && (!found || t < best)) {
                best = t;
                normal = n;
                found = true;
            }
            return;
        }
        int children[2] = {bv.leftChild(), bv.rightChild()};
        real enter[2] = {0, 0};
        bool reached[2];
        for (int k = 0; k < 2; ++k) reached[k] = rayObb(o, d, model.getBV(children[k]).bv.obb, best, enter[k]);
        visitNearestFirst(children, reached, enter, best, [this](int child) { visit(child); });
    }
};

bool rayLocalMesh(const Vector3 &o, const Vector3 &d, const CollisionShape &shape, real limit, real &t,
                  Vector3 &n) {
    const auto &model = static_cast<const fcl::BVHModel<fcl::OBBRSSd> &>(*shape.geometry());
    if (model.getNumBVs() == 0) return false;
    real enter;
    if (!rayObb(o, d, model.getBV(0).bv.obb, limit, enter)) return false;
    MeshWalk walk{model, shape, o, d, limit};
    walk.visit(0);
    if (!walk.found) return false;
    t = walk.best;
    n = walk.normal;
    return true;
}

}  // namespace

bool rayBox(const Vector3 &origin, const Vector3 &direction, const Vector3 &min, const Vector3 &max, real limit,
            real &enter) {
    real near = 0;
    real far = limit;
    for (int k = 0; k < 3; ++k) {
        if (std::abs(direction[k]) < kParallel) {
            if (origin[k] < min[k] || origin[k] > max[k]) return false;
            continue;
        }
        const real inverse = 1 / direction[k];
        real t1 = (min[k] - origin[k]) * inverse;
        real t2 = (max[k] - origin[k]) * inverse;
        if (t1 > t2) std::swap(t1, t2);
        near = std::max(near, t1);
        far = std::min(far, t2);
        if (near > far) return false;
    }
    enter = near;
    return true;
}

bool rayShape(const Ray &ray, const CollisionShape &shape, const Matrix4 &pose, RaySurfaceHit &hit) {
    if (shape.isCompound()) {
        // The nearest entry into any child; each child's own ray stops at the best so far.
        Ray nearer = ray;
        bool found = false;
        for (std::size_t k = 0; k < shape.children().size(); ++k) {
            RaySurfaceHit candidate;
            if (!rayShape(nearer, *shape.children()[k].shape, partPose(shape, k, pose), candidate)) continue;
            if (found && !(candidate.distance < hit.distance)) continue;
            hit = candidate;
            nearer.maxDistance = candidate.distance;
            found = true;
        }
        return found;
    }
    const Matrix3 rotation = pose.linear();
    const Vector3 o = rotation.transpose() * (ray.origin - pose.translation());
    const Vector3 d = rotation.transpose() * ray.direction;
    const Shape &s = shape.shape();
    const real limit = ray.maxDistance;
    real t = 0;
    Vector3 n = Vector3::UnitY();
    bool found = false;
    switch (s.type) {
        case ShapeType::Box: found = rayLocalBox(o, d, s.halfExtents, limit, t, n); break;
        case ShapeType::Sphere:
            found = raySphere(o, d, Vector3::Zero(), s.radius, t) && t <= limit;
            if (found) n = (o + t * d) / s.radius;
            break;
        case ShapeType::Capsule: found = rayLocalCapsule(o, d, s.radius, s.length / 2, limit, t, n); break;
        case ShapeType::Cylinder: found = rayLocalCylinder(o, d, s.radius, s.length / 2, limit, t, n); break;
        case ShapeType::Convex: found = rayLocalConvex(o, d, shape, limit, t, n); break;
        case ShapeType::Plane: found = rayLocalPlane(o, d, shape, limit, t, n); break;
        case ShapeType::Mesh: found = rayLocalMesh(o, d, shape, limit, t, n); break;
        case ShapeType::Heightfield:
            found = rayHeightfield(o, d, HeightfieldGrid(s), shape.geometry()->aabb_local, limit, t, n);
            break;
        case ShapeType::Compound: break;  // taken child by child above
    }
    if (!found) return false;
    hit.distance = t;
    hit.normal = (rotation * n).normalized();
    return true;
}

}  // namespace cyclone::detail
