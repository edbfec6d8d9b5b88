// A shape against a triangle mesh. FCL reports one contact per triangle the shape
// overlaps; the triangles it does not touch yet but can reach within the step are found
// in the mesh's tree and measured by GJK (speculative contacts, as the convex pairs get).
//
// Which side of a triangle pushes: a two-sided mesh (the default) pushes a shape out to
// the side of the triangle its centre is on, a one-sided one to the side away from its
// solid (MeshSides); a normal never pushes a shape through its triangle.
//
// Inner edges: a contact with an edge or vertex where neighbours meet almost flat
// (mesh_features.h) takes the triangle's face normal, as Jolt's active edges do, and
// keeps the depth it had along its own normal, so a shape rolling or sliding across a
// floor of triangles meets no edge that the floor does not have. Face contacts claim
// their triangles' vertices; a contact on an edge or vertex whose vertices are already
// claimed adds nothing and is dropped, as in Jolt's InternalEdgeRemovingCollector. The
// rest are merged into one manifold per normal.
#include "collision/mesh_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision/broadphase.h"
#include "collision/contact_building.h"
#include "collision/gjk.h"
#include "collision/heightfield.h"
#include "collision/mesh_features.h"
#include "collision/shape_contact.h"

namespace cyclone::detail {
namespace {

// Most contacts one pair keeps: FCL's, then triangles within reach.
constexpr int kMaxMeshContacts = 2 * kMaxFclContacts;
// Deepest the walk through the mesh's tree goes (a balanced tree of 2^60 triangles).
constexpr int kMaxTreeDepth = 64;
// A triangle's vertices within this fraction of its longest edge (plus kPointTolerance)
// of the one furthest along a contact's normal touch the shape with it: the feature of
// a contact whose normal is within 0.06 degrees of an edge's perpendicular is the edge.
constexpr real kFeatureSlope = 1e-3;

struct MeshContact {
    Vector3 normal;
    real depth;
    // Points clipped along the normal are no deeper than this: the depth along the
    // contact's own normal when an inner edge's contact took the face normal, m.
    real cap;
    // The normal it had before an inner feature's contact took the face normal.
    Vector3 featureNormal;
    int triangle;
    bool face;
    bool inner;  // on an inner edge or vertex: the face normal, taken
    bool kept;
};

// The pair with its mesh side named.
struct MeshPair {
    const CollisionShape &a;
    const Matrix4 &poseA;
    const CollisionShape &b;
    const Matrix4 &poseB;
    bool meshIsB;
    const CollisionShape &mesh;
    const Matrix4 &meshPose;
    const CollisionShape &other;
    const Matrix4 &otherPose;
    Vector3 centre;  // the other shape's centroid, world
    real reach;      // how far the two may close within the step, m

    MeshPair(const CollisionShape &a_, const Matrix4 &poseA_, const CollisionShape &b_, const Matrix4 &poseB_,
             real reach_)
        : a(a_), poseA(poseA_), b(b_), poseB(poseB_), meshIsB(b_.hasTriangles()),
          mesh(meshIsB ? b_ : a_), meshPose(meshIsB ? poseB_ : poseA_), other(meshIsB ? a_ : b_),
          otherPose(meshIsB ? poseA_ : poseB_), centre(otherPose * other.centroid()), reach(reach_) {}

    // The normal (A to B) along which triangle t pushes the other shape out.
    Vector3 front(int t) const {
        const Vector3 n = meshPose.linear() * mesh.triangleNormal(t);
        bool outward = true;  // pushes to the side n faces
        switch (mesh.triangleSides()) {
            case MeshSides::Front: break;
            case MeshSides::Back: outward = false; break;
            case MeshSides::Both: {
                Vector3 v[3];
                int ids[3];
                mesh.triangle(t, v, ids);
                outward = n.dot(centre - meshPose * v[0]) >= 0;
                break;
            }
        }
        return outward != meshIsB ? n : Vector3(-n);
    }

    Pair pair(int t, real speculative) const {
        return Pair{a, poseA, meshIsB ? -1 : t, b, poseB, meshIsB ? t : -1, speculative, reach};
    }

    // Whether contact c touches its triangle at an inner (inactive) edge or vertex, or
    // with the whole triangle: the triangle's vertices furthest along the normal.
    bool onInnerFeature(const MeshContact &c) const {
        const Vector3 towards = meshPose.linear().transpose() * (meshIsB ? Vector3(-c.normal) : c.normal);
        Vector3 v[3];
        int ids[3];
        mesh.triangle(c.triangle, v, ids);
        real top = -std::numeric_limits<real>::infinity();
        real longest = 0;
        for (int k = 0; k < 3; ++k) {
            top = std::max(top, v[k].dot(towards));
            longest = std::max(longest, (v[(k + 1) % 3] - v[k]).norm());
        }
        const real tolerance = kPointTolerance + kFeatureSlope * longest;
        int touching[3];
        int n = 0;
        for (int k = 0; k < 3; ++k)
            if (v[k].dot(towards) > top - tolerance) touching[n++] = k;
        const std::uint8_t active = mesh.activeFeatures(c.triangle);
        if (n == 3) return true;
        if (n == 1) return !(active & activeVertexBit(touching[0]));
        // Edge k runs from vertex k to k + 1; (0, 2) is edge 2.
        const int edge = (touching[0] + 1) % 3 == touching[1] ? touching[0] : touching[1];
        return !(active & activeEdgeBit(edge));
    }

    // Sorts out a new contact: a face contact, or one on an inner feature that takes the
    // face normal `front`.
    void classify(MeshContact &c, const Vector3 &front) const {
        c.cap = std::numeric_limits<real>::infinity();
        c.featureNormal = c.normal;
        c.kept = true;
        c.inner = false;
        c.face = c.normal.dot(front) > kFaceCosine;
        if (c.face || !onInnerFeature(c)) return;
        c.normal = front;
        c.face = true;
        c.inner = true;
        c.cap = c.depth;
    }
};

// Adds a contact for triangle t if the other shape comes closer to it than `reach`
// (measured by GJK between the shape and the triangle), or touches or overlaps it.
void addTriangleWithinReach(const MeshPair &m, int t, real reach, real speculative, MeshContact *contacts,
                            int &count) {
    const Pair pair = m.pair(t, speculative);
    const auto support = [&](const Vector3 &d) {
        return Vector3(pair.a.supportPoint(pair.poseA, d, pair.triangleA) -
                       pair.b.supportPoint(pair.poseB, -d, pair.triangleB));
    };
    const Vector3 front = m.front(t);
    MeshContact &c = contacts[count];
    c.triangle = t;
    // The closest points of A - B: the line from B's to A's, so the normal (A to B)
    // is its opposite.
    Vector3 closest;
    const bool apart = closestToOrigin(support, -front, closest);
    const real distance = apart ? closest.norm() : 0;
    if (!(distance < reach)) return;
    if (distance > kPointTolerance) {
        c.normal = -closest / distance;
        if (c.normal.dot(front) < 0) return;  // behind a one-sided triangle
        c.depth = -distance;
    } else {
        // Touching, which FCL does not report: the normal as for its contacts.
        NormalRule rule;
        rule.oneSided = true;
        rule.front = front;
        SupportFeature fa, fb;
        c.normal = chooseNormal(pair, front, rule, true, fa, fb, c.depth);
        if (!(c.depth > -speculative)) return;
    }
    m.classify(c, front);
    if (c.face) c.normal = front;
    ++count;
}

// The contact of a triangle FCL found touching the other shape, along FCL's normal
// `rawNormal` (A to B) refined to the triangle's own best normal.
void addTouchingTriangle(const MeshPair &m, int triangle, const Vector3 &rawNormal, real keep, MeshContact *contacts,
                         int &count) {
    NormalRule rule;
    rule.oneSided = true;
    rule.front = m.front(triangle);
    // FCL's normals against triangles, even its exact sphere-triangle ones, describe
    // the triangle alone: refinement finds each triangle's own best normal.
    MeshContact &c = contacts[count];
    SupportFeature fa, fb;
    c.normal = chooseNormal(m.pair(triangle, keep), rawNormal, rule, true, fa, fb, c.depth);
    if (!(c.depth > -keep)) return;
    c.triangle = triangle;
    m.classify(c, rule.front);
    ++count;
}

// A height field's triangles under the other shape's box grown by the reach
// (heightfield.h), as a mesh's: those FCL's triangle test finds touching it, then those
// it comes closer to than `reach` (addTriangleWithinReach).
void addHeightfieldTriangles(const MeshPair &m, real reach, real keep, MeshContact *contacts, int &count) {
    const fcl::AABBd box = placedBox(*m.other.geometry(), m.meshPose.inverse() * m.otherPose, reach);
    HeightfieldGrid(m.mesh.shape()).forEachTriangleIn(box.min_, box.max_, [&](int t) {
        fcl::Vector3d corners[3];
        int ids[3];
        m.mesh.triangle(t, corners, ids);
        fcl::Vector3d normal;
        double depth = 0;
        if (shapeTriangleContact(m.other.geometry().get(), m.otherPose, corners, m.meshPose, normal, depth)) {
            // FCL's normal runs from the shape to the triangle.
            const real length = normal.norm();
            if (length > kMinNormalLength)
                addTouchingTriangle(m, t, m.meshIsB ? Vector3(normal / length) : Vector3(-normal / length), keep,
                                    contacts, count);
        } else if (reach > 0) {
            addTriangleWithinReach(m, t, reach, keep, contacts, count);
        }
        return count < kMaxMeshContacts;
    });
}

// Adds a contact for each triangle not in `reported` that the other shape does not touch
// but comes closer to than `reach`: found in the mesh's tree with the other shape's box
// grown by the reach, measured by GJK between the shape and the triangle.
void addTrianglesWithinReach(const MeshPair &m, real reach, real speculative, const int *reported, int reportedCount,
                             MeshContact *contacts, int &count) {
    const auto *model = static_cast<const fcl::BVHModel<fcl::OBBRSSd> *>(m.mesh.geometry().get());
    const fcl::AABBd &local = m.other.geometry()->aabb_local;
    const Matrix3 toMesh = m.meshPose.linear().transpose();
    fcl::OBBd query;
    query.axis = toMesh * m.otherPose.linear();
    query.To = toMesh * (m.otherPose * boxCentre(local) - m.meshPose.translation());
    query.extent = 0.5 * (local.max_ - local.min_) + Vector3::Constant(reach);

    int stack[kMaxTreeDepth];
    int depth = 0;
    stack[depth++] = 0;
    while (depth > 0 && count < kMaxMeshContacts) {
        const fcl::BVNode<fcl::OBBRSSd> &node = model->getBV(stack[--depth]);
        if (!node.bv.obb.overlap(query)) continue;
        if (!node.isLeaf()) {
            if (depth + 2 > kMaxTreeDepth) continue;
            stack[depth++] = node.rightChild();
            stack[depth++] = node.leftChild();
            continue;
        }
        const int t = node.primitiveId();
        if (std::find(reported, reported + reportedCount, t) != reported + reportedCount) continue;
        addTriangleWithinReach(m, t, reach, speculative, contacts, count);
    }
}

// Contact c's points clipped along `normal`, no deeper than its cap, added to `points`.
//
// Along its face normal a triangle holds only what lies over it. When a face contact's
// features do not overlap along the normal (a shape beside the triangle, within reach of
// it or touching its edge), clipping falls back to the shapes' nearest points along the
// normal: a vertex of the triangle and the point the normal's overlap puts under it,
// nowhere on the shape, at the overlap's depth rather than the gap. A capsule rolling on
// its side 2 cm beside a vertex, 1 mm above it, met such a point at depth 0 and bumped 6
// mm; with a speculative inner edge's contact it met one 8 cm apart but 2 m from its
// centre, where its turning closed the gap within a step, and jumped 8 cm. Such a contact
// gives no point: the triangle the shape lies over, in the same plane, holds it. Edge and
// vertex contacts keep the fallback (docs/meshes.md).
void clipContact(const MeshPair &m, const MeshContact &c, const Vector3 &normal, real speculative, PointSet &points) {
    const Pair pair = m.pair(c.triangle, speculative);
    SupportFeature fa, fb;
    m.a.supportingFeature(m.poseA, normal, pair.triangleA, fa);
    m.b.supportingFeature(m.poseB, -normal, pair.triangleB, fb);
    const bool pointIfApart = !c.face;
    if (!(c.cap < std::numeric_limits<real>::infinity())) {
        clipFeatures(pair, normal, fa, fb, points, pointIfApart);
        return;
    }
    PointSet clipped;
    clipFeatures(pair, normal, fa, fb, clipped, pointIfApart);
    for (int k = 0; k < clipped.count; ++k) {
        const PointSet::Point &p = clipped.points[k];
        if (p.depth <= c.cap) {
            points.add(p.pointA, p.pointB, p.depth, p.landing);
        } else if (m.meshIsB) {
            points.add(p.pointA, p.pointA - c.cap * normal, c.cap);
        } else {
            points.add(p.pointB + c.cap * normal, p.pointB, c.cap);
        }
    }
}

// Drops the contacts of edges and vertices that face contacts (or the features kept
// before them) already hold: with face contacts first, then those of inner features,
// then the rest deepest first, as Jolt orders them, a feature touching the other shape
// (the triangle's vertices furthest towards it) adds nothing once its vertices are claimed.
void dropClaimedFeatures(const MeshPair &m, MeshContact *contacts, int count) {
    const auto rank = [](const MeshContact &c) { return c.face ? (c.inner ? 1 : 0) : 2; };
    std::sort(contacts, contacts + count, [&](const MeshContact &x, const MeshContact &y) {
        return rank(x) != rank(y) ? rank(x) < rank(y) : x.depth > y.depth;
    });
    int claimed[3 * kMaxMeshContacts];
    int claimedCount = 0;
    auto isClaimed = [&](int vertex) { return std::find(claimed, claimed + claimedCount, vertex) != claimed + claimedCount; };
    for (int i = 0; i < count; ++i) {
        MeshContact &c = contacts[i];
        Vector3 v[3];
        int t[3];
        m.mesh.triangle(c.triangle, v, t);
        if (!c.face || c.inner) {
            const Vector3 &n = c.featureNormal;
            const Vector3 towards = m.meshPose.linear().transpose() * (m.meshIsB ? Vector3(-n) : n);
            real top = -std::numeric_limits<real>::infinity();
            for (int k = 0; k < 3; ++k) top = std::max(top, v[k].dot(towards));
            bool covered = true;
            for (int k = 0; k < 3; ++k)
                if (v[k].dot(towards) > top - kPointTolerance && !isClaimed(t[k])) covered = false;
            if (covered) {
                c.kept = false;
                continue;
            }
        }
        for (int k = 0; k < 3; ++k)
            if (!isClaimed(t[k])) claimed[claimedCount++] = t[k];
    }
}

// One manifold per normal: the clipped points of all its triangles, reduced once so that
// the points where triangles split a face do not crowd out its corners. Returns how many
// were appended.
int appendByNormal(const MeshPair &m, MeshContact *contacts, int count, real keep, std::vector<Manifold> &out) {
    int appended = 0;
    for (int i = 0; i < count; ++i) {
        if (!contacts[i].kept) continue;
        const Vector3 normal = contacts[i].normal;
        PointSet points;
        for (int j = i; j < count; ++j) {
            MeshContact &c = contacts[j];
            if (!c.kept || c.normal.dot(normal) < kMergeCosine) continue;
            c.kept = false;
            if (points.count + kMaxClipped > kMaxMerged) {
                // Rarely many triangles: keep the best four so far and go on.
                Manifold partial;
                reduce(points.points, points.count, normal, partial);
                points.count = 0;
                for (int k = 0; k < partial.count; ++k)
                    points.add(partial.points[k].pointA, partial.points[k].pointB, partial.points[k].depth);
            }
            // Clipped along the manifold's normal, so that every point's depth is
            // measured along the normal the manifold reports.
            clipContact(m, c, normal, keep, points);
        }
        appended += appendReduced(points, normal, out);
    }
    return appended;
}

}  // namespace

int meshContacts(const CollisionShape &a, const Matrix4 &poseA, const CollisionShape &b, const Matrix4 &poseB,
                 real speculative, real reach, const RawContact *raw, int rawCount, std::vector<Manifold> &out) {
    const MeshPair m(a, poseA, b, poseB, reach);
    const int triangles = m.mesh.triangleCount();
    const real keep = std::max(speculative, reach);

    MeshContact contacts[kMaxMeshContacts];
    int count = 0;
    int reported[kMaxFclContacts];
    int reportedCount = 0;
    for (int i = 0; i < rawCount && i < kMaxFclContacts; ++i) {
        const int triangle = m.meshIsB ? raw[i].triangleB : raw[i].triangleA;
        if (triangle < 0 || triangle >= triangles) continue;
        reported[reportedCount++] = triangle;
        addTouchingTriangle(m, triangle, raw[i].normal, keep, contacts, count);
    }
    if (m.mesh.shape().type == ShapeType::Heightfield) {
        addHeightfieldTriangles(m, reach, keep, contacts, count);
    } else if (reach > 0) {
        addTrianglesWithinReach(m, reach, keep, reported, reportedCount, contacts, count);
    }
    dropClaimedFeatures(m, contacts, count);
    return appendByNormal(m, contacts, count, keep, out);
}

}  // namespace cyclone::detail
