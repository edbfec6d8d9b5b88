// World::saveState and World::restoreState: everything the next step reads, as bytes.
//
// Design note. A state is the World less its build: shapes (and meshes) are not copied;
// each body names its shape by its place in WorldState::shapes, the shapes in the order
// of the addBody calls, so that a World built by the same calls reads it, and a state
// whose shapes' fingerprint differs is refused. What is copied is what a step reads of
// the steps before it and cannot make again: the bodies' records and dynamic state, the
// contact pairs with their manifolds, anchors and warm-start impulses, the end normals
// the next narrowphase can take, what the solver's kept Jacobians were made from (they
// are made again: snapshot/solver_slots.h), the joints and springs with their impulses,
// the sensors' overlaps, the islands, the events recorded between steps, and the
// broadphase's three trees node by node: the walk that lists the candidate pairs, and so
// the solve order, follows the trees' shapes, and FCL's incremental balancing compares
// node addresses, so the internal nodes are restored in the same order of addresses
// (their rank is saved). What is made again from what is stored (a body's transform, a
// tree's boxes, a slot's Jacobians) is stored instead wherever making it again would not
// give its bits: the save checks. Each struct's fields are listed once, in a function of
// StateFields that reads or writes them through io() or packed() (state_archive.h): a
// field added to a struct is one line there. Scratch that a step rewrites before it
// reads it is not saved. Sizes and timings: docs/rollback.md.
#include <algorithm>
#include <initializer_list>
#include <unordered_map>

#include "character/character_record.h"
#include "collision/time_of_impact.h"
#include "cyclone/detail/byte_fields.h"
#include "cyclone/detail/validation.h"
#include "snapshot/solver_slots.h"
#include "snapshot/state_archive.h"
#include "world/world_impl.h"

namespace cyclone::detail {
namespace {

constexpr std::uint32_t kStateTag = 0x54535943;  // "CYST"
constexpr std::uint32_t kStateVersion = 4;
/// Tag, version, payload length, checksum.
constexpr std::size_t kHeaderSize = 4 + 4 + 8 + 8;

using TreeNode = fcl::detail::NodeBase<fcl::AABBd>;
using Hierarchy = fcl::detail::HierarchyTree<fcl::AABBd>;

// FCL keeps the balancing path and the spare node protected: reached through a derived
// class's member pointers.
struct HierarchyAccess : Hierarchy {
    static unsigned int &path(Hierarchy &tree) { return tree.*(&HierarchyAccess::opath); }
    static TreeNode *&spare(Hierarchy &tree) { return tree.*(&HierarchyAccess::free_node); }
};

// A broadphase tree's node as saveTree writes it: a leaf's body index, or an internal
// node's rank among the tree's internal nodes by address; its box unless it is the one
// made again (a leaf's: its body's box; an internal node's: its children's merged).
struct SavedNode {
    bool leaf;
    bool madeAgain;
    fcl::AABBd box;
    std::uint32_t id;
};

/// A node's tag byte.
constexpr std::uint8_t kLeafNode = 1;
constexpr std::uint8_t kBoxMadeAgain = 2;

// The box of an internal node made from its children's.
fcl::AABBd mergedBox(const TreeNode &node) { return node.children[0]->bv + node.children[1]->bv; }

bool sameBox(const fcl::AABBd &x, const fcl::AABBd &y) {
    return std::memcmp(x.min_.data(), y.min_.data(), sizeof(Vector3)) == 0 &&
           std::memcmp(x.max_.data(), y.max_.data(), sizeof(Vector3)) == 0;
}

// The saved nodes of a tree, depth first; `objects` receives the leaves' collision
// objects in that order.
std::vector<SavedNode> readNodes(StateReader &a, const BodyStore &bodies, std::vector<fcl::CollisionObjectd *> &objects) {
    std::vector<SavedNode> nodes(a.count(0, 2));
    for (SavedNode &s : nodes) {
        std::uint8_t tag = 0;
        io(a, tag);
        packed(a, s.id);
        s.leaf = tag & kLeafNode;
        s.madeAgain = tag & kBoxMadeAgain;
        if (!s.madeAgain) io(a, s.box);
        if (!s.leaf) continue;
        if (s.id >= bodies.size() || !bodies[s.id].object) throw UnreadableState{"a tree names a body without a box"};
        if (s.madeAgain) s.box = bodies[s.id].object->getAABB();
        objects.push_back(bodies[s.id].object.get());
    }
    return nodes;
}

// The nodes FCL made when the objects were registered: leaves by body, internal ones for
// reuse.
struct MadeNodes {
    std::unordered_map<std::uint32_t, TreeNode *> leaves;
    std::vector<TreeNode *> pool;
};

MadeNodes madeNodes(const Hierarchy &tree) {
    MadeNodes made;
    std::vector<TreeNode *> stack{tree.getRoot()};
    while (!stack.empty()) {
        TreeNode *node = stack.back();
        stack.pop_back();
        if (node->isLeaf()) {
            made.leaves[bodyIndexOf(static_cast<fcl::CollisionObjectd *>(node->data))] = node;
            continue;
        }
        made.pool.push_back(node);
        stack.push_back(node->children[0]);
        stack.push_back(node->children[1]);
    }
    return made;
}

// Gives `tree` its spare node (none when `spareRank` is all ones) among the internal
// nodes of `pool`, which it sorts by address; returns the spare node, or nullptr.
const TreeNode *placeSpare(Hierarchy &tree, std::vector<TreeNode *> &pool, std::uint32_t spareRank) {
    const bool spare = spareRank != ~std::uint32_t(0);
    TreeNode *&spareNode = HierarchyAccess::spare(tree);
    if (spare && !spareNode) spareNode = new TreeNode();
    if (spare) pool.push_back(spareNode);
    std::sort(pool.begin(), pool.end(), std::less<TreeNode *>());
    if (spare) {
        if (spareRank >= pool.size()) throw UnreadableState{"a tree's spare node is out of range"};
        spareNode = pool[spareRank];
    } else {
        delete spareNode;
        spareNode = nullptr;
    }
    return spareNode;
}

// Links the `made` nodes depth first, as `nodes` were written (each internal node by its
// rank in the sorted pool, never the `spare` one); returns the root.
TreeNode *linkNodes(const std::vector<SavedNode> &nodes, const MadeNodes &made, const TreeNode *spare) {
    std::vector<std::pair<TreeNode *, int>> open;  // internal nodes still missing a child
    TreeNode *root = nullptr;
    std::vector<TreeNode *> linked;
    linked.reserve(nodes.size());
    for (const SavedNode &s : nodes) {
        TreeNode *node;
        if (s.leaf) {
            node = made.leaves.at(s.id);
        } else {
            if (s.id >= made.pool.size() || (spare && made.pool[s.id] == spare))
                throw UnreadableState{"a tree's node rank is out of range"};
            node = made.pool[s.id];
        }
        node->bv = s.box;
        linked.push_back(node);
        if (open.empty()) {
            if (root) throw UnreadableState{"a tree has two roots"};
            root = node;
            node->parent = nullptr;
        } else {
            std::pair<TreeNode *, int> &parent = open.back();
            parent.first->children[parent.second] = node;
            node->parent = parent.first;
            if (++parent.second == 2) open.pop_back();
        }
        if (!s.leaf) {
            node->children[0] = nullptr;
            node->children[1] = nullptr;
            open.push_back({node, 0});
        }
    }
    if (!open.empty()) throw UnreadableState{"a tree is cut short"};
    // Children come after their parents: boxes made again from the last node back.
    for (std::size_t k = nodes.size(); k-- > 0;)
        if (!nodes[k].leaf && nodes[k].madeAgain) linked[k]->bv = mergedBox(*linked[k]);
    return root;
}

// A fingerprint of a shape: what tells two different shapes apart without copying them.
std::uint64_t shapeFingerprint(const CollisionShape &shape) {
    struct Key {
        int type;
        int vertices;
        int children;
        real volume;
        real radius;
        real centroid[3];
        real inertia[9];
    } key{};
    key.type = static_cast<int>(shape.shape().type);
    key.vertices = static_cast<int>(shape.vertices().size());
    key.children = static_cast<int>(shape.children().size());
    key.volume = shape.volume();
    key.radius = shape.boundingRadius();
    for (int i = 0; i < 3; ++i) key.centroid[i] = shape.centroid()[i];
    for (int i = 0; i < 9; ++i) key.inertia[i] = shape.unitInertia().data()[i];
    return stateChecksum(reinterpret_cast<const std::uint8_t *>(&key), sizeof key);
}

std::uint64_t shapesFingerprint(const std::vector<std::shared_ptr<const CollisionShape>> &shapes, std::size_t count) {
    std::uint64_t h = count;
    for (std::size_t k = 0; k < count; ++k) h = (h ^ shapeFingerprint(*shapes[k])) * 0x100000001B3ull;
    return h;
}

}  // namespace

/// The fields of each part of the World's state (a friend of the classes that hold them).
struct StateFields {
    /// A body's dynamic state. Its transform and world inertia are made again from its
    /// pose when that gives their bits (RigidBody::calculateDerivedData keeps them so).
    template <class A>
    static void body(A &a, RigidBody &b) {
        io(a, b.position, b.orientation);
        io(a, b.motion, b.isAwake);
        std::uint8_t derived = 0;
        if constexpr (!A::kReading) {
            RigidBody made = b;
            made.calculateDerivedData();
            derived = std::memcmp(made.transformMatrix.data(), b.transformMatrix.data(), sizeof(Matrix4)) == 0 &&
                      std::memcmp(made.inverseInertiaTensorWorld.data(), b.inverseInertiaTensorWorld.data(),
                                  sizeof(Matrix3)) == 0;
        }
        io(a, derived);
        if (!derived) io(a, b.transformMatrix, b.inverseInertiaTensorWorld);
        else if constexpr (A::kReading) b.calculateDerivedData();
        // Zero in a body at rest or asleep: a bit each says so, and only the others follow;
        // the last step's acceleration is the body's own but under forces.
        std::uint8_t ownAcceleration = 0;
        if constexpr (!A::kReading)
            ownAcceleration = std::memcmp(b.lastFrameAcceleration.data(), b.acceleration.data(), sizeof(Vector3)) == 0;
        io(a, ownAcceleration);
        mostlyZero(a, {&b.velocity, &b.rotation, &b.forceAccum, &b.torqueAccum});
        if (!ownAcceleration) io(a, b.lastFrameAcceleration);
        else if constexpr (A::kReading) b.lastFrameAcceleration = b.acceleration;
    }

    /// What the bodies of a scene mostly share: material, kind, filter, damping, gravity,
    /// sleep threshold and integration schemes.
    template <class A>
    static void kind(A &a, BodyRecord &r) {
        RigidBody &b = r.body;
        io(a, r.material, r.immovable, r.kinematic, r.isPlane, r.ccd, r.layer, r.collidesWith, r.sensor);
        io(a, b.linearDamping, b.angularDamping, b.acceleration, b.sleepEpsilon, b.movingMotionCap, b.canSleep);
        io(a, b.gyroscopicStep, b.rotationStep);
    }

    template <class A>
    static void mass(A &a, BodyRecord &r) {
        io(a, r.body.inverseMass);
        inertia(a, r.body.inverseInertiaTensor);
    }

    /// Fields written by `fields` as a flag when their bytes are those of the last live
    /// body's (`last` holds them), else as they are.
    template <class A, class Fields>
    static void likeLast(A &a, BodyRecord &r, std::vector<std::uint8_t> &last, std::vector<std::uint8_t> &scratch,
                         Fields fields) {
        std::uint8_t same = 0;
        if constexpr (!A::kReading) {
            scratch.clear();
            StateWriter w(scratch);
            fields(w, r);
            same = !last.empty() && scratch == last;
            io(a, same);
            if (!same) a.bytes(scratch.data(), scratch.size());
            last.swap(scratch);
        } else {
            io(a, same);
            if (same) {
                if (last.empty()) throw UnreadableState{"a body repeats fields not given"};
                StateReader before(last.data(), last.size());
                fields(before, r);
            } else {
                fields(a, r);
                last.clear();
                StateWriter w(last);
                fields(w, r);
            }
        }
    }

    /// The bytes of the last live body's kind and mass (likeLast).
    struct LastBody {
        std::vector<std::uint8_t> kind, mass, scratch;
    };

    /// An inverse inertia tensor: a flag, then its diagonal when the rest is zero, else all.
    template <class A>
    static void inertia(A &a, Matrix3 &m) {
        std::uint8_t diagonal = 0;
        if constexpr (!A::kReading) {
            const Matrix3 d = m.diagonal().asDiagonal();
            diagonal = std::memcmp(d.data(), m.data(), sizeof(Matrix3)) == 0;
        }
        io(a, diagonal);
        if (!diagonal) {
            io(a, m);
            return;
        }
        Vector3 entries = m.diagonal();
        io(a, entries);
        if constexpr (A::kReading) m = entries.asDiagonal();
    }

    /// Vectors written as a mask of those whose bits are all zero, then the others.
    template <class A>
    static void mostlyZero(A &a, std::initializer_list<Vector3 *> vectors) {
        std::uint8_t zero = 0;
        int k = 0;
        if constexpr (!A::kReading) {
            static const Vector3 kZero = Vector3::Zero();
            for (const Vector3 *v : vectors) zero |= (std::memcmp(v->data(), kZero.data(), sizeof(Vector3)) == 0) << k++;
        }
        io(a, zero);
        k = 0;
        for (Vector3 *v : vectors) {
            if (!(zero >> k++ & 1)) io(a, *v);
            else if constexpr (A::kReading) v->setZero();
        }
    }

    /// A signed index that is -1 or more, packed as one more than it.
    template <class A>
    static void packedIndex(A &a, int &index) {
        std::uint32_t plusOne = static_cast<std::uint32_t>(index + 1);
        packed(a, plusOne);
        if constexpr (A::kReading) index = static_cast<int>(plusOne) - 1;
    }

    /// A body's options set after it was added (gravity scale, locks, surface velocity,
    /// one-way direction, user data): a flag, then the options unless all are the defaults.
    template <class A>
    static void options(A &a, BodyRecord &r) {
        std::uint8_t defaults = 0;
        if constexpr (!A::kReading) {
            static const Vector3 kZero = Vector3::Zero();
            const auto zero = [](const Vector3 &v) { return std::memcmp(v.data(), kZero.data(), sizeof(Vector3)) == 0; };
            defaults = r.gravityScale == 1 && !r.locked.any() && zero(r.surfaceVelocity) && zero(r.oneWay) &&
                       r.userData == 0;
        }
        io(a, defaults);
        if (!defaults) io(a, r.gravityScale, r.locked, r.surfaceVelocity, r.oneWay, r.userData);
        else if constexpr (A::kReading) {
            r.gravityScale = 1;
            r.locked = LockedAxes();
            r.surfaceVelocity.setZero();
            r.oneWay.setZero();
            r.userData = 0;
        }
    }

    /// A live body's record but its shape and collision object.
    template <class A>
    static void record(A &a, BodyRecord &r, LastBody &last) {
        packed(a, r.shapeIndex);
        io(a, r.name, r.moving, r.isolated, r.simulated, r.held, r.tree);
        likeLast(a, r, last.kind, last.scratch, [](auto &archive, BodyRecord &record) { kind(archive, record); });
        likeLast(a, r, last.mass, last.scratch, [](auto &archive, BodyRecord &record) { mass(archive, record); });
        packedIndex(a, r.sleepingIsland);
        packedIndex(a, r.island);
        packedIndex(a, r.solverIndex);
        packedIndex(a, r.awakeSlot);
        packed(a, r.pairs);
        packed(a, r.rank);
        packed(a, r.keptApart);
        options(a, r);
        body(a, r.body);
    }

    template <class A>
    static void bodyLists(A &a, BodyStore &s) {
        packed(a, s.free);
        packed(a, s.order);
        packed(a, s.awake);
        io(a, s.awakeSorted);
        packed(a, s.nextRank);
        packed(a, s.simulated);
        packed(a, s.kinematic);
        packed(a, s.moving);
        io(a, s.filteredCount, s.sensorCount, s.roundCount, s.keptApartCount, s.lockedCount, s.ruledCount);
        io(a, s.isolatedCount);
        packed(a, s.planes);
    }

    /// A manifold; its step numbers as steps before `now`.
    template <class A>
    static void manifold(A &a, ManifoldState &m, std::uint64_t now) {
        std::uint8_t count = static_cast<std::uint8_t>(m.count);
        io(a, m.normal, m.localNormal, count, m.frictionImpulse, m.twistImpulse);
        packed(a, m.anchorsId);
        packed(a, m.solverSlot);
        packedStep(a, m.solverStep, now);
        std::uint32_t children[2] = {static_cast<std::uint32_t>(m.childA), static_cast<std::uint32_t>(m.childB)};
        packed(a, children[0]);
        packed(a, children[1]);
        if constexpr (A::kReading) {
            m.count = count;
            m.childA = static_cast<int>(children[0]);
            m.childB = static_cast<int>(children[1]);
        }
        if (m.count > Manifold::kMaxPoints) throw UnreadableState{"a manifold's point count is out of range"};
        for (int i = 0; i < m.count; ++i) {
            PersistentPoint &point = m.points[i];
            std::uint8_t id = static_cast<std::uint8_t>(point.id);
            io(a, point.localA, point.localB, point.depth, point.normalImpulse, id);
            if constexpr (A::kReading) point.id = id;
        }
    }

    /// A pair cache's live slots (its table is made again from them). A pair that does
    /// not touch has no relative pose: only a touching pair's is read (manifold reuse).
    template <class A>
    static void pairCache(A &a, PairCache &cache, std::uint64_t now) {
        std::size_t slots = a.count(cache.pairs_.size(), 1);
        if constexpr (A::kReading) {
            cache.pairs_.assign(slots, PairState());
        }
        for (std::size_t p = 0; p < slots; ++p) {
            PairState &pair = cache.pairs_[p];
            // 0: a free slot; else one more than the pair's manifolds.
            std::uint32_t tag = pair.alive ? static_cast<std::uint32_t>(pair.manifolds.size()) + 1 : 0;
            packed(a, tag);
            if constexpr (A::kReading) pair.alive = tag != 0;
            if (!pair.alive) continue;
            packed(a, pair.a);
            packed(a, pair.b);
            packedStep(a, pair.lastSeen, now);
            const std::size_t n = tag - 1;
            if (n > 255) throw UnreadableState{"a pair has too many manifolds"};
            if (n == 0) continue;
            if constexpr (A::kReading) pair.manifolds.resize(n);
            RelativePose &pose = pair.manifolds[0].tested;
            io(a, pose.position, pose.orientation);
            for (ManifoldState &m : pair.manifolds) {
                manifold(a, m, now);
                if constexpr (A::kReading) m.tested = pose;
            }
        }
        packed(a, cache.free_);
        if constexpr (A::kReading) {
            std::size_t size = 16;
            while (size < 2 * slots) size *= 2;
            cache.table_.assign(size, PairCache::Entry());
            cache.used_ = 0;
            for (std::size_t p = 0; p < slots; ++p)
                if (cache.pairs_[p].alive)
                    cache.insert(PairCache::key(cache.pairs_[p].a, cache.pairs_[p].b), static_cast<std::uint32_t>(p));
        }
    }

    /// The contact events' tracks: their count, then the touching ones (a track that does
    /// not touch is read only for that).
    template <class A>
    static void tracks(A &a, ContactTracks &tracks, std::size_t pairSlots) {
        const std::size_t n = a.count(tracks.slots(), 0);
        if (n > std::max(pairSlots, tracks.slots())) throw UnreadableState{"the contact tracks outnumber the pairs"};
        std::uint32_t touching = 0;
        if constexpr (A::kReading) {
            tracks.reset(n);
        } else {
            for (std::uint32_t slot = 0; slot < n; ++slot) touching += tracks.at(slot).touching;
        }
        packed(a, touching);
        std::uint32_t slot = 0;
        for (std::uint32_t k = 0; k < touching; ++k) {
            if constexpr (!A::kReading) {
                while (!tracks.at(slot).touching) ++slot;
            }
            packed(a, slot);
            if (slot >= n) throw UnreadableState{"a contact track is out of range"};
            ContactTrack t = tracks.at(slot);
            packed(a, t.a.index);
            packed(a, t.a.generation);
            packed(a, t.b.index);
            packed(a, t.b.generation);
            packed(a, t.userDataA);
            packed(a, t.userDataB);
            t.touching = true;
            if constexpr (A::kReading) tracks.begin(slot, t);
            ++slot;
        }
    }

    /// Which body of pair `pair` the memo's shape `shape` is (1: A, 2: B; 0: neither),
    /// when the memo tested it at the pose it stands at.
    static std::uint8_t standingSide(const WorldState &w, const PairState &pair, const CollisionShape *shape,
                                     const Eigen::Matrix<real, 3, 4> &pose) {
        for (std::uint8_t side : {1, 2}) {
            const BodyRecord &r = w.bodies[side == 1 ? pair.a : pair.b];
            if (shape != r.shape.get()) continue;
            // Both bodies may share the shape: the pose tells which one the memo tested.
            const Eigen::Matrix<real, 3, 4> now = r.body.getTransform().matrix().topRows<3>();
            if (std::memcmp(now.data(), pose.data(), sizeof pose) == 0) return side;
        }
        return 0;
    }

    /// The end normals (the landing correction's memos, which the next narrowphase takes
    /// in place of FCL's test when its pair's shapes stand bit for bit at the poses the
    /// memo tested): those whose shapes stand there, each shape as which body's it is and
    /// its pose as that body's. The others hold only for a body put back at those poses
    /// bit for bit, and then give what the test gives (docs/solver.md, "Landing
    /// correction"). The table from pair slot to entry is made again.
    static void saveEndNormals(StateWriter &a, const WorldState &w) {
        const ContactManager &c = w.contacts;
        std::vector<std::pair<const ContactManager::EndNormal *, std::uint8_t>> standing;
        for (const ContactManager::EndNormal &e : c.endNormals_) {
            if (e.pair >= c.pairs.slots() || !c.pairs[e.pair].alive) continue;
            const PairState &pair = c.pairs[e.pair];
            const std::uint8_t sideA = standingSide(w, pair, e.memo.a, e.memo.poseA);
            const std::uint8_t sideB = standingSide(w, pair, e.memo.b, e.memo.poseB);
            if (sideA != 0 && sideB != 0) standing.push_back({&e, static_cast<std::uint8_t>(sideA | sideB << 2)});
        }
        a.count(standing.size());
        for (auto [entry, sides] : standing) {
            ContactManager::EndNormal e = *entry;
            packed(a, e.pair);
            packedStep(a, e.step, w.stepCount);
            io(a, sides, e.memo.touching);
            if (e.memo.touching) io(a, e.memo.normal);
        }
    }

    static void restoreEndNormals(StateReader &a, WorldState &w) {
        ContactManager &c = w.contacts;
        c.endNormals_.resize(a.count(0, 4));
        c.endNormalOf_.assign(c.pairs.slots(), ContactManager::kNoSlot);
        for (std::size_t k = 0; k < c.endNormals_.size(); ++k) {
            ContactManager::EndNormal &e = c.endNormals_[k];
            NormalMemo &m = e.memo;
            std::uint8_t sides = 0;
            packed(a, e.pair);
            packedStep(a, e.step, w.stepCount);
            io(a, sides, m.touching);
            m.normal = Vector3::UnitY();
            if (m.touching) io(a, m.normal);
            const std::uint8_t sideA = sides & 3, sideB = sides >> 2;
            if (e.pair >= c.pairs.slots() || !c.pairs[e.pair].alive || sideA == 0 || sideA > 2 || sideB == 0 || sideB > 2)
                throw UnreadableState{"an end normal names no pair"};
            const PairState &pair = c.pairs[e.pair];
            const BodyRecord &ra = w.bodies[sideA == 1 ? pair.a : pair.b];
            const BodyRecord &rb = w.bodies[sideB == 1 ? pair.a : pair.b];
            m.a = ra.shape.get();
            m.b = rb.shape.get();
            m.poseA = ra.body.getTransform().matrix().topRows<3>();
            m.poseB = rb.body.getTransform().matrix().topRows<3>();
            c.endNormalOf_[e.pair] = static_cast<std::uint32_t>(k);
        }
    }

    /// The contacts. The step's lists (its pairs, their places, the candidates' slots of
    /// the last look-up) are rewritten before they are read, or only hint: not saved.
    template <class A>
    static void contacts(A &a, ContactManager &c, std::uint64_t now) {
        pairCache(a, c.pairs, now);
        packed(a, c.touchingPairs);
        packed(a, c.anchorsIssued_);
        if constexpr (A::kReading) {
            c.stepIndex_.clear();
            c.stepPairs_.clear();
            c.candidateSlots_.clear();
        }
        tracks(a, c.tracks_, c.pairs.slots());
        packed(a, c.eventSlots_);
    }

    template <class A>
    static void sensors(A &a, Sensors &s, std::uint64_t now) {
        pairCache(a, s.overlaps_, now);
        io(a, s.rechecks_, s.checkedStep_);
    }

    template <class A>
    static void islands(A &a, Islands &i) {
        io(a, i.sleeping, i.freeSleeping, i.start_, i.members_);
    }

    // A character's capsule is made from its settings, as addCharacter makes it.
    template <class A>
    static void characters(A &a, Characters &c) {
        const std::size_t n = a.count(c.records.size(), 2);
        if constexpr (A::kReading) c.records.resize(n);
        for (CharacterRecord &r : c.records) {
            io(a, r.alive, r.generation);
            if (!r.alive) continue;
            io(a, r.settings, r.body, r.feet, r.desired, r.flight, r.push, r.velocity);
            io(a, r.onGround, r.groundBody, r.groundNormal, r.groundPoint, r.groundStart);
            if constexpr (A::kReading) r.capsule = characterCapsule(r.settings);
        }
        io(a, c.free);
    }

    template <class A>
    static void joints(A &a, JointSet &j) {
        io(a, j.records, j.free, j.count);
        if constexpr (A::kReading) {
            j.excluded_.clear();
            for (const JointRecord &r : j.records)
                if (r.alive && r.settings.b && !r.settings.collideConnected)
                    ++j.excluded_[JointSet::pairKey(r.settings.a.index, r.settings.b->index)];
        }
    }

    /// A solver slot's manifold: the kept Jacobians and the rest, and only the points in
    /// use (those past `count` are never read; a kept slot has the same points).
    template <class A>
    static void solverManifold(A &a, SolverManifold &m) {
        auto *bytes = reinterpret_cast<std::uint8_t *>(&m);
        a.bytes(bytes, static_cast<std::size_t>(reinterpret_cast<std::uint8_t *>(&m.points[0]) - bytes));
        if (m.count < 0 || m.count > kMaxManifoldPoints) throw UnreadableState{"a solver manifold's point count is out of range"};
        a.bytes(m.points, static_cast<std::size_t>(m.count) * sizeof(SolverPoint));
    }

    /// A slot's stamp (the carrier as a byte: 0xFF none yet). A stamped pose the same as
    /// the one last written for its body (`last`, by body index; a step stamps all of a
    /// body's slots it makes anew at one pose) is a flag.
    template <class A>
    static void stamp(A &a, JacobianStamp &s, const std::uint32_t (&bodies)[2], std::vector<const StampedBody *> &last) {
        packed(a, s.anchorsId);
        io(a, s.rowOf);
        for (int k = 0; k < 2; ++k) {
            StampedBody &b = s.body[k];
            const StampedBody *&before = last[bodies[k]];
            std::uint8_t same = 0;
            if constexpr (!A::kReading)
                same = before && std::memcmp(before->position.data(), b.position.data(), sizeof(Vector3)) == 0 &&
                       std::memcmp(before->orientation.coeffs().data(), b.orientation.coeffs().data(),
                                   sizeof(Quaternion)) == 0;
            io(a, b.movable, same);
            if (same && !before) throw UnreadableState{"a stamp repeats a pose not given"};
            if (!same) io(a, b.position, b.orientation);
            else if constexpr (A::kReading) {
                b.position = before->position;
                b.orientation = before->orientation;
            }
            before = &b;
        }
        std::uint8_t carrier = s.carrier ? static_cast<std::uint8_t>(*s.carrier) : 0xFF;
        io(a, carrier);
        if constexpr (A::kReading) {
            if (carrier != 0xFF && carrier > static_cast<std::uint8_t>(Carrier::B))
                throw UnreadableState{"a slot's carrier is out of range"};
            s.carrier = carrier == 0xFF ? std::nullopt : std::optional<Carrier>(static_cast<Carrier>(carrier));
            s.kept = false;
        }
    }

    /// Bodies at stamped poses, their transforms and world inertia made from them: the
    /// last pose asked of each body is kept (a body's slots are mostly stamped at one).
    class PosedBodies {
    public:
        explicit PosedBodies(std::size_t bodies) : entry_(bodies, -1) { posed_.reserve(bodies); }
        SolverManifold fresh;             ///< Room for a slot made again.
        std::vector<SolverBody> carried;  ///< Room for remakeJacobians.
        const RigidBody &at(const RigidBody &body, std::uint32_t index, const StampedBody &stamped) {
            int &k = entry_[index];
            if (k >= 0 && std::memcmp(posed_[k].position.data(), stamped.position.data(), sizeof(Vector3)) == 0 &&
                std::memcmp(posed_[k].orientation.coeffs().data(), stamped.orientation.coeffs().data(),
                            sizeof(Quaternion)) == 0)
                return posed_[k];
            if (k < 0) {
                k = static_cast<int>(posed_.size());
                posed_.push_back(body);  // never past the room reserved: one per body
            } else {
                posed_[k] = body;
            }
            RigidBody &b = posed_[k];
            b.position = stamped.position;
            b.orientation = stamped.orientation;
            b.calculateDerivedData();
            return b;
        }

    private:
        std::vector<int> entry_;
        std::vector<RigidBody> posed_;
    };

    /// The manifold that took a solver slot in the last step, and its pair's bodies.
    struct SlotSource {
        const ManifoldState *manifold = nullptr;
        std::uint32_t a = 0, b = 0;
    };

    static std::vector<SlotSource> slotSources(const WorldState &w, std::size_t slots) {
        std::vector<SlotSource> sources(slots);
        const PairCache &pairs = w.contacts.pairs;
        for (std::uint32_t p = 0; p < pairs.slots(); ++p) {
            if (!pairs[p].alive) continue;
            for (const ManifoldState &m : pairs[p].manifolds)
                if (m.solverStep == w.stepCount && m.solverSlot < slots) sources[m.solverSlot] = {&m, pairs[p].a, pairs[p].b};
        }
        return sources;
    }

    /// Slot `m` made again from its stamp, its source's anchors and `normal`; false when
    /// the source's points do not fit the stamp's rows.
    static bool remade(const WorldState &w, const JacobianStamp &stamp, const SlotSource &source, const Vector3 &normal,
                       SolverManifold &m, PosedBodies &posed) {
        const ManifoldState &from = *source.manifold;
        m = SolverManifold();
        m.normal = normal;
        m.count = from.count;
        if (m.count < 0 || m.count > kMaxManifoldPoints) return false;
        for (int i = 0; i < from.count; ++i) {
            const int id = from.points[i].id;
            if (id < 0 || id >= kMaxManifoldPoints || stamp.rowOf[id] < 0 || stamp.rowOf[id] >= m.count) return false;
            m.points[stamp.rowOf[id]].localA = from.points[i].localA;
            m.points[stamp.rowOf[id]].localB = from.points[i].localB;
        }
        const BodyRecord &ra = w.bodies[source.a];
        const BodyRecord &rb = w.bodies[source.b];
        const RigidBody &posedA = posed.at(ra.body, source.a, stamp.body[0]);
        const RigidBody &posedB = posed.at(rb.body, source.b, stamp.body[1]);
        m.a = stamp.body[0].movable ? 1 : 0;
        m.b = stamp.body[1].movable ? 2 : 0;
        remakeJacobians(m, stamp.carrier, stampedSolverBody(stamp.body[0], ra, posedA),
                        stampedSolverBody(stamp.body[1], rb, posedB), posedA, posedB, posed.carried);
        return true;
    }

    /// The normal a slot's Jacobians were made with: a flag when it is its manifold's.
    template <class A>
    static void slotNormal(A &a, Vector3 &normal, const ManifoldState &m) {
        std::uint8_t same = 0;
        if constexpr (!A::kReading) same = std::memcmp(normal.data(), m.normal.data(), sizeof(Vector3)) == 0;
        io(a, same);
        if (!same) io(a, normal);
        else if constexpr (A::kReading) normal = m.normal;
    }

    /// The solver's slots, each Unkept, Remade or Copied (snapshot/solver_slots.h).
    static void saveSolver(StateWriter &a, const WorldState &w) {
        ConstraintSolver &s = const_cast<ConstraintSolver &>(w.solver);
        const std::size_t n = a.count(s.manifolds_.size());
        const std::vector<SlotSource> sources = slotSources(w, n);
        std::vector<const StampedBody *> last(w.bodies.size(), nullptr);
        PosedBodies posed(w.bodies.size());
        for (std::size_t k = 0; k < n; ++k) {
            JacobianStamp &st = s.stamps_[k];
            SolverManifold &m = s.manifolds_[k];
            const SlotSource &source = sources[k];
            SlotForm form = SlotForm::Unkept;
            if (source.manifold && st.anchorsId != 0 && source.manifold->anchorsId == st.anchorsId) {
                const bool carried = st.carrier && *st.carrier != Carrier::None;
                form = remade(w, st, source, m.normal, posed.fresh, posed) && sameJacobians(posed.fresh, m, carried)
                           ? SlotForm::Remade
                           : SlotForm::Copied;
            }
            io(a, form);
            if (form == SlotForm::Unkept) continue;
            const std::uint32_t bodies[2] = {source.a, source.b};
            stamp(a, st, bodies, last);
            if (form == SlotForm::Remade) slotNormal(a, m.normal, *source.manifold);
            else solverManifold(a, m);
        }
    }

    static void restoreSolver(StateReader &a, WorldState &w) {
        ConstraintSolver &s = w.solver;
        const std::size_t n = a.count(0, 1);
        s.manifolds_.resize(n);
        s.stamps_.resize(n);
        const std::vector<SlotSource> sources = slotSources(w, n);
        std::vector<const StampedBody *> last(w.bodies.size(), nullptr);
        PosedBodies posed(w.bodies.size());
        for (std::size_t k = 0; k < n; ++k) {
            JacobianStamp &st = s.stamps_[k];
            SlotForm form = SlotForm::Unkept;
            io(a, form);
            if (form == SlotForm::Unkept) {
                st = JacobianStamp();  // names no anchors: the next step makes the slot anew
                continue;
            }
            if (form != SlotForm::Remade && form != SlotForm::Copied) throw UnreadableState{"a solver slot's form is unknown"};
            const SlotSource &source = sources[k];
            if (!source.manifold) throw UnreadableState{"a solver slot has no manifold"};
            const std::uint32_t bodies[2] = {source.a, source.b};
            stamp(a, st, bodies, last);
            if (form == SlotForm::Copied) {
                solverManifold(a, s.manifolds_[k]);
                continue;
            }
            Vector3 normal;
            slotNormal(a, normal, *source.manifold);
            if (source.manifold->anchorsId != st.anchorsId || !remade(w, st, source, normal, s.manifolds_[k], posed))
                throw UnreadableState{"a solver slot's anchors are not its manifold's"};
        }
    }

    /// A collision object's fat box, and its box when that differs (BodyObject::place
    /// makes them equal).
    template <class A>
    static void boxes(A &a, BodyObject &object) {
        io(a, object.fat_);
        std::uint8_t apart = 0;
        if constexpr (!A::kReading) apart = !(object.aabb.min_ == object.fat_.min_ && object.aabb.max_ == object.fat_.max_);
        io(a, apart);
        if (apart) io(a, object.aabb);
        else if constexpr (A::kReading) object.aabb = object.fat_;
    }

    template <class A>
    static void events(A &a, WorldEvents &e) {
        io(a, e.contactBegins, e.contactEnds, e.sensorBegins, e.sensorEnds, e.fellAsleep, e.wokeUp, e.jointsBroken);
    }

    /// What a state holds after the broadphase: contacts, sensors, islands, joints,
    /// springs, characters, the solver's kept data and the events recorded between steps.
    template <class A>
    static void managers(A &a, WorldState &w) {
        contacts(a, w.contacts, w.stepCount);
        if constexpr (A::kReading) restoreEndNormals(a, w);
        else saveEndNormals(a, w);
        sensors(a, w.sensors, w.stepCount);
        islands(a, w.islands);
        joints(a, w.joints);
        io(a, w.springs.records, w.springs.free);
        characters(a, w.characters);
        if constexpr (A::kReading) restoreSolver(a, w);
        else saveSolver(a, w);
        events(a, w.events.pending);
    }

    // --- The broadphase's trees ---------------------------------------------------------

    static Hierarchy &hierarchy(fcl::DynamicAABBTreeCollisionManagerd &manager) {
        return const_cast<Hierarchy &>(manager.getTree());
    }

    /// Writes a tree: its balancing path, then its nodes depth first (internal: box and
    /// the rank of its address; leaf: body index and box), then the spare node's rank.
    static void saveTree(StateWriter &a, fcl::DynamicAABBTreeCollisionManagerd &manager) {
        Hierarchy &tree = hierarchy(manager);
        io(a, HierarchyAccess::path(tree));
        std::vector<const TreeNode *> internal;
        std::vector<const TreeNode *> order;
        std::vector<const TreeNode *> stack;
        if (tree.getRoot()) stack.push_back(tree.getRoot());
        while (!stack.empty()) {
            const TreeNode *node = stack.back();
            stack.pop_back();
            order.push_back(node);
            if (node->isLeaf()) continue;
            internal.push_back(node);
            stack.push_back(node->children[1]);
            stack.push_back(node->children[0]);
        }
        TreeNode *spare = HierarchyAccess::spare(tree);
        if (spare) internal.push_back(spare);
        std::vector<const TreeNode *> byAddress = internal;
        std::sort(byAddress.begin(), byAddress.end(), std::less<const TreeNode *>());
        const auto rank = [&](const TreeNode *node) {
            return static_cast<std::uint32_t>(std::lower_bound(byAddress.begin(), byAddress.end(), node,
                                                               std::less<const TreeNode *>()) -
                                              byAddress.begin());
        };
        a.count(order.size());
        for (const TreeNode *node : order) {
            const bool leaf = node->isLeaf();
            std::uint32_t id = leaf ? bodyIndexOf(static_cast<const fcl::CollisionObjectd *>(node->data)) : rank(node);
            const fcl::AABBd made =
                leaf ? static_cast<const fcl::CollisionObjectd *>(node->data)->getAABB() : mergedBox(*node);
            const bool madeAgain = sameBox(made, node->bv);
            std::uint8_t tag = (leaf ? kLeafNode : 0) | (madeAgain ? kBoxMadeAgain : 0);
            io(a, tag);
            packed(a, id);
            if (!madeAgain) {
                fcl::AABBd box = node->bv;
                io(a, box);
            }
        }
        std::uint32_t spareRank = spare ? rank(spare) : ~std::uint32_t(0);
        io(a, spareRank);
    }

    /// Reads a tree written by saveTree: registers its leaves' objects, then links the
    /// nodes FCL made into the saved shape, the internal ones in the saved address order.
    static void restoreTree(StateReader &a, fcl::DynamicAABBTreeCollisionManagerd &manager, BodyStore &bodies) {
        manager.clear();
        Hierarchy &tree = hierarchy(manager);
        unsigned int path = 0;
        io(a, path);
        std::vector<fcl::CollisionObjectd *> objects;
        const std::vector<SavedNode> nodes = readNodes(a, bodies, objects);
        std::uint32_t spareRank = 0;
        io(a, spareRank);
        if (objects.empty()) {
            HierarchyAccess::path(tree) = path;
            return;
        }
        const std::size_t internalCount = nodes.size() - objects.size();
        if (internalCount + 1 != objects.size()) throw UnreadableState{"a tree's node counts disagree"};
        manager.registerObjects(objects);
        MadeNodes made = madeNodes(tree);
        const TreeNode *spare = placeSpare(tree, made.pool, spareRank);
        tree.getRoot() = linkNodes(nodes, made, spare);
        HierarchyAccess::path(tree) = path;
    }

    /// Bytes enough for most states of `w` (growing the state as it is written copied
    /// it several times over): a body's record and box, a pair slot, a touching pair's
    /// pose and manifolds, a solver slot's stamp, each rounded up.
    static std::size_t roomFor(const WorldState &w) {
        return kHeaderSize + 1024 + 256 * w.bodies.size() + 16 * w.contacts.pairs.slots() +
               512 * w.contacts.touchingPairs.size() + 160 * w.solver.manifolds_.size();
    }

    static void save(const WorldState &state, std::vector<std::uint8_t> &out);
    static void restore(WorldState &w, const std::uint8_t *data, std::size_t size);
    static void restoreBody(StateReader &a, WorldState &w, std::uint32_t index, LastBody &last);
};

void StateFields::save(const WorldState &state, std::vector<std::uint8_t> &out) {
    // Saving reads only; StateFields' functions take what they list by reference.
    WorldState &w = const_cast<WorldState &>(state);
    StateWriter a(out);
    std::uint64_t fingerprint = shapesFingerprint(w.shapes.all(), w.shapes.size());
    io(a, fingerprint);
    a.count(w.shapes.size());
    io(a, w.stepCount);

    BodyStore &bodies = w.bodies;
    a.count(bodies.size());
    LastBody last;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        BodyRecord &r = bodies[static_cast<std::uint32_t>(k)];
        io(a, r.alive, r.generation);
        if (!r.alive) continue;
        record(a, r, last);
        if (r.object) boxes(a, *r.object);
    }
    bodyLists(a, bodies);

    Broadphase &b = w.broadphase;
    for (auto *manager : {&b.awake_, &b.asleep_, &b.static_}) saveTree(a, *manager);
    for (const std::vector<fcl::CollisionObjectd *> &waiting : b.arrivals_) {
        std::vector<std::uint32_t> indices;
        for (const fcl::CollisionObjectd *object : waiting) indices.push_back(bodyIndexOf(object));
        io(a, indices);
    }
    io(a, b.changes_);

    managers(a, w);
}

void StateFields::restoreBody(StateReader &a, WorldState &w, std::uint32_t index, LastBody &last) {
    BodyRecord &r = w.bodies[index];
    const bool wasAlive = r.alive;
    const std::uint32_t oldShape = r.shapeIndex;
    io(a, r.alive, r.generation);
    if (!r.alive) {
        const std::uint32_t generation = r.generation;
        r = BodyRecord();
        r.generation = generation;
        return;
    }
    record(a, r, last);
    r.seen.renew(r.body, w.stepCount + 1);  // not saved: every pair is tested afresh
    if (r.shapeIndex >= w.shapes.size()) throw UnreadableState{"names a shape this World does not have"};
    // A body that kept its slot and shape keeps its collision object (and ccd core).
    const bool same = wasAlive && oldShape == r.shapeIndex && r.shape == w.shapes[r.shapeIndex];
    r.shape = w.shapes[r.shapeIndex];
    r.boundingRadius = r.shape->boundingRadius();
    if (!r.ccd) r.core.reset();
    else if (!same || !r.core) r.core = makeCore(sweptShape(*r.shape));
    if (r.isPlane) {
        r.object.reset();
        return;
    }
    if (!same || !r.object) {
        r.object = std::make_unique<BodyObject>(r.shape->geometry(), r.body.getTransform());
        r.object->setUserData(reinterpret_cast<void *>(static_cast<std::uintptr_t>(index)));
    }
    // Only awake bodies' objects lie away from their bodies' poses between steps, and the
    // step places those before reading them.
    r.object->setTransform(r.body.getTransform());
    boxes(a, *r.object);
}

void StateFields::restore(WorldState &w, const std::uint8_t *data, std::size_t size) {
    StateReader a(data, size);
    std::uint64_t fingerprint = 0;
    io(a, fingerprint);
    const std::size_t shapes = a.count(0, 0);
    if (shapes > w.shapes.size() || shapesFingerprint(w.shapes.all(), shapes) != fingerprint)
        throw UnreadableState{"is from another World: its bodies were added with other shapes"};
    io(a, w.stepCount);

    // The trees hold the objects of the bodies about to be replaced: emptied first.
    Broadphase &b = w.broadphase;
    for (auto *manager : {&b.awake_, &b.asleep_, &b.static_}) manager->clear();
    for (std::vector<fcl::CollisionObjectd *> &waiting : b.arrivals_) waiting.clear();
    BodyStore &bodies = w.bodies;
    const std::size_t slots = a.count(0, 5);
    bodies.records.resize(slots);
    LastBody last;
    for (std::size_t k = 0; k < slots; ++k) restoreBody(a, w, static_cast<std::uint32_t>(k), last);
    bodyLists(a, bodies);
    bodies.names.clear();
    for (std::uint32_t index : bodies.order)
        if (!bodies[index].name.empty()) bodies.names.emplace(bodies[index].name, index);

    for (auto *manager : {&b.awake_, &b.asleep_, &b.static_}) restoreTree(a, *manager, bodies);
    bool waiting = false;
    for (std::vector<fcl::CollisionObjectd *> &arrivals : b.arrivals_) {
        std::vector<std::uint32_t> indices;
        io(a, indices);
        for (std::uint32_t i : indices) {
            if (i >= bodies.size() || !bodies[i].object) throw UnreadableState{"a tree's arrival has no box"};
            arrivals.push_back(bodies[i].object.get());
        }
        waiting |= !arrivals.empty();
    }
    b.waiting_.store(waiting);
    io(a, b.changes_);
    b.changed_ = true;  // the next walk lists the pairs of the restored trees

    managers(a, w);
    w.events.events.clear();
    w.events.sink = &w.events.pending;
    if (!a.done()) throw UnreadableState{"has bytes past its end"};
}

}  // namespace cyclone::detail

namespace cyclone {

std::vector<std::uint8_t> World::saveState() const {
    std::vector<std::uint8_t> out(detail::kHeaderSize);
    out.reserve(detail::StateFields::roomFor(*impl_));
    detail::StateFields::save(*impl_, out);
    const std::uint64_t length = out.size() - detail::kHeaderSize;
    detail::put(out, 0, detail::kStateTag);
    detail::put(out, 4, detail::kStateVersion);
    detail::put(out, 8, length);
    detail::put(out, 16, detail::stateChecksum(out.data() + detail::kHeaderSize, length));
    return out;
}

void World::restoreState(const std::vector<std::uint8_t> &state) {
    static const char *function = "World::restoreState";
    if (state.size() < detail::kHeaderSize)
        detail::refuse(function, "state", "is " + std::to_string(state.size()) + " bytes, too short for a saved state");
    if (detail::take<std::uint32_t>(state, 0) != detail::kStateTag)
        detail::refuse(function, "state", "is not a saved World state (its tag differs)");
    const auto version = detail::take<std::uint32_t>(state, 4);
    if (version != detail::kStateVersion)
        detail::refuse(function, "state", "has format version " + std::to_string(version) + ", this World reads " +
                                              std::to_string(detail::kStateVersion));
    const auto length = detail::take<std::uint64_t>(state, 8);
    if (length != state.size() - detail::kHeaderSize)
        detail::refuse(function, "state", "is damaged: its length says " + std::to_string(length) + " bytes, it has " +
                                              std::to_string(state.size() - detail::kHeaderSize));
    const std::uint8_t *payload = state.data() + detail::kHeaderSize;
    if (detail::take<std::uint64_t>(state, 16) != detail::stateChecksum(payload, length))
        detail::refuse(function, "state", "is damaged: its checksum fails");
    try {
        detail::StateFields::restore(*impl_, payload, length);
    } catch (const detail::UnreadableState &e) {
        detail::refuse(function, "state", e.problem);
    }
}

}  // namespace cyclone
