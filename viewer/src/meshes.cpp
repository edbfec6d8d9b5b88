#include "meshes.h"

#include <libqhull_r/qhull_ra.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cyclone::viewer {

namespace {

constexpr float kPi = 3.14159265f;

Eigen::Vector3f toFloat(const Vector3 &v) { return v.cast<float>(); }

std::uint32_t addVertex(TriangleMesh &mesh, const Eigen::Vector3f &p, const Eigen::Vector3f &n) {
    mesh.vertices.push_back({{p.x(), p.y(), p.z()}, {n.x(), n.y(), n.z()}});
    return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
}

void addTriangle(TriangleMesh &mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// A quad a-b-c-d (counter-clockwise from outside) with one flat normal.
void addQuad(TriangleMesh &mesh, const Eigen::Vector3f &a, const Eigen::Vector3f &b, const Eigen::Vector3f &c,
             const Eigen::Vector3f &d) {
    const Eigen::Vector3f n = (b - a).cross(c - a).normalized();
    const std::uint32_t i = addVertex(mesh, a, n), j = addVertex(mesh, b, n), k = addVertex(mesh, c, n),
                        l = addVertex(mesh, d, n);
    addTriangle(mesh, i, j, k);
    addTriangle(mesh, i, k, l);
}

TriangleMesh boxMesh(const Eigen::Vector3f &h) {
    TriangleMesh mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (float side : {-1.0f, 1.0f}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            Eigen::Vector3f corner[4];
            const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k) {
                corner[k][axis] = side * h[axis];
                corner[k][u] = su[k] * h[u];
                corner[k][v] = side * sv[k] * h[v];
            }
            addQuad(mesh, corner[0], corner[1], corner[2], corner[3]);
        }
    }
    return mesh;
}

// Rings of a round shape about z: a half sphere of radius r at z = centre (cap = +1 for
// the top, -1 for the bottom) with smooth normals, `rings` rings from equator to pole.
void addHemisphere(TriangleMesh &mesh, float r, float centre, float cap, int rings) {
    const int n = kRoundSegments;
    const std::uint32_t base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int i = 0; i <= rings; ++i) {
        const float polar = kPi / 2 * static_cast<float>(i) / static_cast<float>(rings);
        for (int j = 0; j <= n; ++j) {
            const float a = 2 * kPi * static_cast<float>(j) / static_cast<float>(n);
            const Eigen::Vector3f normal(std::cos(polar) * std::cos(a), std::cos(polar) * std::sin(a),
                                         cap * std::sin(polar));
            addVertex(mesh, r * normal + Eigen::Vector3f(0, 0, centre), normal);
        }
    }
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < n; ++j) {
            const std::uint32_t a = base + static_cast<std::uint32_t>(i * (n + 1) + j);
            const std::uint32_t b = a + 1, c = a + static_cast<std::uint32_t>(n + 1), d = c + 1;
            if (cap > 0) {
                addTriangle(mesh, a, b, d);
                addTriangle(mesh, a, d, c);
            } else {
                addTriangle(mesh, a, d, b);
                addTriangle(mesh, a, c, d);
            }
        }
    }
}

// The side of a cylinder of radius r about z from z0 to z1, smooth normals.
void addTube(TriangleMesh &mesh, float r, float z0, float z1) {
    const int n = kRoundSegments;
    const std::uint32_t base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int j = 0; j <= n; ++j) {
        const float a = 2 * kPi * static_cast<float>(j) / static_cast<float>(n);
        const Eigen::Vector3f normal(std::cos(a), std::sin(a), 0);
        addVertex(mesh, r * normal + Eigen::Vector3f(0, 0, z0), normal);
        addVertex(mesh, r * normal + Eigen::Vector3f(0, 0, z1), normal);
    }
    for (int j = 0; j < n; ++j) {
        const std::uint32_t a = base + static_cast<std::uint32_t>(2 * j);
        addTriangle(mesh, a, a + 2, a + 3);
        addTriangle(mesh, a, a + 3, a + 1);
    }
}

// A flat disc of radius r at height z facing +z (up = true) or -z.
void addDisc(TriangleMesh &mesh, float r, float z, bool up) {
    const int n = kRoundSegments;
    const Eigen::Vector3f normal(0, 0, up ? 1.0f : -1.0f);
    const std::uint32_t centre = addVertex(mesh, Eigen::Vector3f(0, 0, z), normal);
    for (int j = 0; j <= n; ++j) {
        const float a = 2 * kPi * static_cast<float>(j) / static_cast<float>(n);
        addVertex(mesh, Eigen::Vector3f(r * std::cos(a), r * std::sin(a), z), normal);
    }
    for (int j = 0; j < n; ++j) {
        const std::uint32_t a = centre + 1 + static_cast<std::uint32_t>(j);
        if (up) {
            addTriangle(mesh, centre, a, a + 1);
        } else {
            addTriangle(mesh, centre, a + 1, a);
        }
    }
}

// Qhull's messages go nowhere: a failed hull is an empty mesh, and the World has already
// refused such a shape when the scene was built.
FILE *quietStream() {
    static FILE *sink = std::fopen("/dev/null", "w");
    return sink != nullptr ? sink : stderr;
}

TriangleMesh hullMesh(const std::vector<Vector3> &points) {
    TriangleMesh mesh;
    if (points.size() < 4) return mesh;
    std::vector<coordT> coordinates;
    coordinates.reserve(points.size() * 3);
    for (const Vector3 &p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
    qhT state;
    qhT *qh = &state;
    qh_zero(qh, quietStream());
    // Qt: triangulated output, so that every facet is one triangle to draw.
    char options[] = "qhull Qt";
    if (qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False, options, nullptr,
                     quietStream()) == 0) {
        facetT *facet;
        vertexT *vertex, **vertexp;
        FORALLfacets {
            const Eigen::Vector3f normal(static_cast<float>(facet->normal[0]), static_cast<float>(facet->normal[1]),
                                         static_cast<float>(facet->normal[2]));
            Eigen::Vector3f corner[3];
            int k = 0;
            FOREACHvertex_(facet->vertices) {
                if (k < 3) corner[k] = toFloat(points[static_cast<std::size_t>(qh_pointid(qh, vertex->point))]);
                ++k;
            }
            if (k != 3) continue;
            if ((corner[1] - corner[0]).cross(corner[2] - corner[0]).dot(normal) < 0) std::swap(corner[1], corner[2]);
            const std::uint32_t a = addVertex(mesh, corner[0], normal), b = addVertex(mesh, corner[1], normal),
                                c = addVertex(mesh, corner[2], normal);
            addTriangle(mesh, a, b, c);
        }
    }
    qh_freeqhull(qh, !qh_ALL);
    int currentLong = 0, totalLong = 0;
    qh_memfreeshort(qh, &currentLong, &totalLong);
    return mesh;
}

TriangleMesh triangleMesh(const Shape &shape) {
    TriangleMesh mesh;
    for (const std::array<int, 3> &t : shape.triangles) {
        const Eigen::Vector3f a = toFloat(shape.vertices[static_cast<std::size_t>(t[0])]);
        const Eigen::Vector3f b = toFloat(shape.vertices[static_cast<std::size_t>(t[1])]);
        const Eigen::Vector3f c = toFloat(shape.vertices[static_cast<std::size_t>(t[2])]);
        const Eigen::Vector3f n = (b - a).cross(c - a).normalized();
        addTriangle(mesh, addVertex(mesh, a, n), addVertex(mesh, b, n), addVertex(mesh, c, n));
    }
    return mesh;
}

// The plane's frame: the unit normal, two unit tangents and its surface point nearest
// the body's origin.
struct PlaneFrame {
    Eigen::Vector3f normal, u, v, centre;
};

PlaneFrame planeFrame(const Shape &shape) {
    PlaneFrame frame;
    const Vector3 n = shape.normal.normalized();
    frame.normal = toFloat(n);
    frame.u = toFloat(n.unitOrthogonal());
    frame.v = frame.normal.cross(frame.u);
    frame.centre = toFloat(n * (shape.offset / shape.normal.norm()));
    return frame;
}

// Divided into cells so that the per-vertex fog of the renderer follows the distance.
TriangleMesh planeMesh(const Shape &shape) {
    const PlaneFrame f = planeFrame(shape);
    constexpr int kCells = 24;
    const float cell = 2 * kPlaneHalfSize / kCells;
    TriangleMesh mesh;
    for (int i = 0; i <= kCells; ++i) {
        for (int j = 0; j <= kCells; ++j) {
            const float s = -kPlaneHalfSize + static_cast<float>(i) * cell;
            const float t = -kPlaneHalfSize + static_cast<float>(j) * cell;
            addVertex(mesh, f.centre + s * f.u + t * f.v, f.normal);
        }
    }
    for (int i = 0; i < kCells; ++i) {
        for (int j = 0; j < kCells; ++j) {
            const auto at = [&](int a, int b) { return static_cast<std::uint32_t>(a * (kCells + 1) + b); };
            // u x v = normal: (i, j) -> (i + 1, j) -> (i + 1, j + 1) turns counter-clockwise.
            addTriangle(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1));
            addTriangle(mesh, at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

// The field's samples, each with the normal of the central differences of its
// neighbours' heights, and each cell's two triangles as the collision shape splits it.
TriangleMesh heightfieldMesh(const Shape &shape) {
    TriangleMesh mesh;
    const int rows = shape.rows, columns = shape.columns;
    const real dx = shape.spacing[0], dz = shape.spacing[1];
    const auto h = [&](int i, int j) {
        i = std::clamp(i, 0, rows - 1);
        j = std::clamp(j, 0, columns - 1);
        return shape.heights[static_cast<std::size_t>(i) * columns + j];
    };
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < columns; ++j) {
            // The surface y = h(x, z) has normal (-dh/dx, 1, -dh/dz).
            const real slopeX = (h(i, j + 1) - h(i, j - 1)) / (dx * (std::min(j + 1, columns - 1) - std::max(j - 1, 0)));
            const real slopeZ = (h(i + 1, j) - h(i - 1, j)) / (dz * (std::min(i + 1, rows - 1) - std::max(i - 1, 0)));
            addVertex(mesh, toFloat(Vector3(j * dx, h(i, j), i * dz)), toFloat(Vector3(-slopeX, 1, -slopeZ).normalized()));
        }
    }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * columns + j); };
    for (int i = 0; i + 1 < rows; ++i) {
        for (int j = 0; j + 1 < columns; ++j) {
            addTriangle(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1));
            addTriangle(mesh, at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
    return mesh;
}

}  // namespace

TriangleMesh shapeMesh(const Shape &shape, const Vector3 &origin) {
    const float r = static_cast<float>(shape.radius), length = static_cast<float>(shape.length);
    TriangleMesh mesh;
    switch (shape.type) {
    case ShapeType::Compound:
        // Each child placed in the compound's frame, moved to the body's (origin).
        for (const CompoundChild &child : shape.children) {
            const TriangleMesh part = shapeMesh(child.shape);
            const Eigen::Matrix3f turn = child.orientation.normalized().toRotationMatrix().cast<float>();
            const Eigen::Vector3f shift = toFloat(Vector3(child.position - origin));
            const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
            for (MeshVertex v : part.vertices) {
                const Eigen::Vector3f p = turn * Eigen::Vector3f(v.position[0], v.position[1], v.position[2]) + shift;
                const Eigen::Vector3f n = turn * Eigen::Vector3f(v.normal[0], v.normal[1], v.normal[2]);
                for (int k = 0; k < 3; ++k) v.position[k] = p[k], v.normal[k] = n[k];
                mesh.vertices.push_back(v);
            }
            for (std::uint32_t i : part.indices) mesh.indices.push_back(first + i);
        }
        return mesh;
    case ShapeType::Box: return boxMesh(toFloat(shape.halfExtents));
    case ShapeType::Sphere:
        addHemisphere(mesh, r, 0, 1, kRoundSegments / 4);
        addHemisphere(mesh, r, 0, -1, kRoundSegments / 4);
        return mesh;
    case ShapeType::Capsule:
        addTube(mesh, r, -length / 2, length / 2);
        addHemisphere(mesh, r, length / 2, 1, kRoundSegments / 4);
        addHemisphere(mesh, r, -length / 2, -1, kRoundSegments / 4);
        return mesh;
    case ShapeType::Cylinder:
        addTube(mesh, r, -length / 2, length / 2);
        addDisc(mesh, r, length / 2, true);
        addDisc(mesh, r, -length / 2, false);
        return mesh;
    case ShapeType::Convex: return hullMesh(shape.vertices);
    case ShapeType::Mesh: return triangleMesh(shape);
    case ShapeType::Plane: return planeMesh(shape);
    case ShapeType::Heightfield: return heightfieldMesh(shape);
    }
    return mesh;
}

PlaneAxes planeAxes(const Shape &shape) {
    const PlaneFrame f = planeFrame(shape);
    return PlaneAxes{f.centre, f.u, f.v};
}

Bounds bodyBounds(const World &world, BodyId id) {
    const Shape &shape = world.shape(id);
    const RigidBody &body = world.body(id);
    const Eigen::Vector3f centre = toFloat(body.getPosition());
    const Eigen::Matrix3f rotation = body.getOrientation().toRotationMatrix().cast<float>();
    Bounds bounds;
    switch (shape.type) {
    case ShapeType::Plane: break;
    case ShapeType::Box: {
        const Eigen::Vector3f reach = rotation.cwiseAbs() * toFloat(shape.halfExtents);
        bounds.add(centre - reach);
        bounds.add(centre + reach);
        break;
    }
    case ShapeType::Convex:
    case ShapeType::Mesh:
        for (const Vector3 &p : shape.vertices) bounds.add(centre + rotation * toFloat(p));
        break;
    case ShapeType::Heightfield: {
        const auto [low, high] = std::minmax_element(shape.heights.begin(), shape.heights.end());
        const real width = (shape.columns - 1) * shape.spacing[0], depth = (shape.rows - 1) * shape.spacing[1];
        for (const real x : {real(0), width})
            for (const real y : {*low, *high})
                for (const real z : {real(0), depth}) bounds.add(centre + rotation * toFloat(Vector3(x, y, z)));
        break;
    }
    case ShapeType::Compound: {
        // Each child's bounds grown to its bounding sphere, about the body's centre.
        const Vector3 origin = world.localCentreOfMass(id);
        for (const CompoundChild &child : shape.children) {
            real reach = child.shape.radius + child.shape.length / 2;
            if (child.shape.type == ShapeType::Box) reach = child.shape.halfExtents.norm();
            for (const Vector3 &p : child.shape.vertices) reach = std::max(reach, p.norm());
            const Eigen::Vector3f at = centre + rotation * toFloat(Vector3(child.position - origin));
            bounds.add(at - Eigen::Vector3f::Constant(static_cast<float>(reach)));
            bounds.add(at + Eigen::Vector3f::Constant(static_cast<float>(reach)));
        }
        break;
    }
    case ShapeType::Sphere:
    case ShapeType::Capsule:
    case ShapeType::Cylinder: {
        // The axis's two ends, each grown by the radius in every direction.
        const float half = shape.type == ShapeType::Sphere ? 0.0f : static_cast<float>(shape.length) / 2;
        const Eigen::Vector3f axis = rotation.col(2) * half;
        const Eigen::Vector3f r = Eigen::Vector3f::Constant(static_cast<float>(shape.radius));
        for (const Eigen::Vector3f &end : {Eigen::Vector3f(centre - axis), Eigen::Vector3f(centre + axis)}) {
            bounds.add(end - r);
            bounds.add(end + r);
        }
        break;
    }
    }
    return bounds;
}

Bounds sceneBounds(const World &world) {
    Bounds moving, all;
    for (BodyId id : world.bodies()) {
        if (!world.body(id).getPosition().allFinite()) continue;
        const Bounds bounds = bodyBounds(world, id);
        all.add(bounds);
        if (world.motion(id) != Motion::Static) moving.add(bounds);
    }
    return moving.empty() ? all : moving;
}

}  // namespace cyclone::viewer
