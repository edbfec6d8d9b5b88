// World::saveState and World::restoreState: everything the next step reads, as bytes.
//
// Design note. A state is the World less its build: shapes (and meshes) are not copied;
// each body names its shape by its place in WorldState::shapes, the shapes in the order
// of the addBody calls, so that a World built by the same calls reads it, and a state
// whose shapes' fingerprint differs is refused. What is copied is what a step reads of
// the steps before it: the bodies' records and dynamic state, the contact pairs with
// their manifolds, anchors and warm-start impulses, the end normals the narrowphase
// reuses, the solver's kept Jacobians (a slot keeps them while its bodies hardly move),
// the joints and springs with their impulses, the sensors' overlaps, the islands, the
// events recorded between steps, and the broadphase's three trees node by node: the walk
// that lists the candidate pairs, and so the solve order, follows the trees' shapes, and
// FCL's incremental balancing compares node addresses, so the internal nodes are
// restored in the same order of addresses (their rank is saved). Each struct's fields are
// listed once, in a function of StateFields that reads or writes them through io()
// (state_archive.h): a field added to a struct is one line there. Scratch that a step
// rewrites before it reads it is not saved. Sizes and timings: docs/rollback.md.
#include <algorithm>
#include <initializer_list>
#include <unordered_map>

#include "collision/time_of_impact.h"
#include "cyclone/detail/byte_fields.h"
#include "cyclone/detail/validation.h"
#include "snapshot/state_archive.h"
#include "world/world_impl.h"

namespace cyclone::detail {
namespace {

constexpr std::uint32_t kStateTag = 0x54535943;  // "CYST"
constexpr std::uint32_t kStateVersion = 1;
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
// node's rank among the tree's internal nodes by address.
struct SavedNode {
    bool leaf;
    fcl::AABBd box;
    std::uint32_t id;
};

// The saved nodes of a tree, depth first; `objects` receives the leaves' collision
// objects in that order.
std::vector<SavedNode> readNodes(StateReader &a, const BodyStore &bodies, std::vector<fcl::CollisionObjectd *> &objects) {
    std::vector<SavedNode> nodes(a.count(0, 1 + sizeof(fcl::AABBd) + 4));
    for (SavedNode &s : nodes) {
        std::uint8_t leaf = 0;
        io(a, leaf, s.box, s.id);
        s.leaf = leaf != 0;
        if (!s.leaf) continue;
        if (s.id >= bodies.size() || !bodies[s.id].object) throw UnreadableState{"a tree names a body without a box"};
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
    template <class A>
    static void body(A &a, RigidBody &b) {
        io(a, b.inverseMass, b.inverseInertiaTensor, b.linearDamping, b.angularDamping);
        io(a, b.position, b.orientation, b.acceleration);
        io(a, b.inverseInertiaTensorWorld, b.motion, b.sleepEpsilon, b.movingMotionCap, b.isAwake, b.canSleep);
        io(a, b.gyroscopicStep, b.rotationStep, b.transformMatrix);
        // Zero in a body at rest or asleep: a bit each says so, and only the others follow.
        mostlyZero(a, {&b.velocity, &b.rotation, &b.forceAccum, &b.torqueAccum, &b.lastFrameAcceleration});
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

    /// A live body's record but its shape and collision object.
    template <class A>
    static void record(A &a, BodyRecord &r) {
        io(a, r.shapeIndex, r.name, r.material, r.immovable, r.kinematic, r.moving, r.isPlane, r.ccd);
        io(a, r.isolated, r.simulated, r.tree, r.sleepingIsland, r.island, r.solverIndex, r.pairs, r.awakeSlot);
        io(a, r.rank, r.layer, r.collidesWith, r.sensor, r.keptApart);
        body(a, r.body);
    }

    template <class A>
    static void bodyLists(A &a, BodyStore &s) {
        io(a, s.free, s.order, s.awake, s.awakeSorted, s.nextRank, s.simulated, s.kinematic, s.moving);
        io(a, s.filteredCount, s.sensorCount, s.roundCount, s.keptApartCount, s.isolatedCount, s.planes);
    }

    template <class A>
    static void manifold(A &a, ManifoldState &m) {
        io(a, m.normal, m.localNormal, m.count, m.frictionImpulse, m.twistImpulse, m.anchorsId);
        io(a, m.solverSlot, m.solverStep, m.childA, m.childB);
        if (m.count < 0 || m.count > Manifold::kMaxPoints) throw UnreadableState{"a manifold's point count is out of range"};
        for (int i = 0; i < m.count; ++i) io(a, m.points[i]);
    }

    /// A pair cache's slots (its table is made again from them).
    template <class A>
    static void pairCache(A &a, PairCache &cache) {
        std::size_t slots = a.count(cache.pairs_.size(), 1);
        if constexpr (A::kReading) {
            cache.pairs_.assign(slots, PairState());
            cache.relativePoses_.assign(slots, RelativePose());
        }
        for (std::size_t p = 0; p < slots; ++p) {
            PairState &pair = cache.pairs_[p];
            io(a, pair.alive);
            if (!pair.alive) continue;
            io(a, pair.a, pair.b, pair.lastSeen, cache.relativePoses_[p]);
            std::size_t n = a.count(pair.manifolds.size(), 1);
            if constexpr (A::kReading) pair.manifolds.resize(n);
            for (ManifoldState &m : pair.manifolds) manifold(a, m);
        }
        io(a, cache.free_);
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

    template <class A>
    static void contacts(A &a, ContactManager &c, const BodyStore &bodies) {
        pairCache(a, c.pairs);
        io(a, c.touchingPairs, c.anchorsIssued_, c.stepIndex_, c.stepPairs_, c.candidateSlots_);
        io(a, c.endNormalOf_, c.tracks_, c.eventSlots_);
        std::size_t n = a.count(c.endNormals_.size(), 1);
        if constexpr (A::kReading) c.endNormals_.resize(n);
        for (ContactManager::EndNormal &e : c.endNormals_) {
            // The memo names the pair's shapes: saved as which body's shape each is.
            NormalMemo &m = e.memo;
            io(a, e.pair, e.step, m.poseA, m.poseB, m.touching, m.normal);
            std::uint8_t sides[2] = {0, 0};
            const CollisionShape *memoShapes[2] = {m.a, m.b};
            const PairState *pair = e.pair < c.pairs.slots() ? &c.pairs[e.pair] : nullptr;
            if constexpr (!A::kReading) {
                for (int k = 0; k < 2; ++k) {
                    if (!memoShapes[k] || !pair || !pair->alive) continue;
                    sides[k] = memoShapes[k] == bodies[pair->a].shape.get() ? 1 : memoShapes[k] == bodies[pair->b].shape.get() ? 2 : 0;
                }
            }
            io(a, sides);
            if constexpr (A::kReading) {
                const auto shapeOf = [&](std::uint8_t side) -> const CollisionShape * {
                    if (side == 0 || !pair || !pair->alive) return nullptr;
                    return bodies[side == 1 ? pair->a : pair->b].shape.get();
                };
                m.a = shapeOf(sides[0]);
                m.b = shapeOf(sides[1]);
            }
        }
    }

    template <class A>
    static void sensors(A &a, Sensors &s) {
        pairCache(a, s.overlaps_);
        io(a, s.rechecks_, s.checkedStep_);
    }

    template <class A>
    static void islands(A &a, Islands &i) {
        io(a, i.sleeping, i.freeSleeping, i.start_, i.members_);
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

    template <class A>
    static void solver(A &a, ConstraintSolver &s) {
        const std::size_t n = a.count(s.manifolds_.size(), 1);
        if constexpr (A::kReading) s.manifolds_.resize(n);
        for (SolverManifold &m : s.manifolds_) solverManifold(a, m);
        io(a, s.stamps_);
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
    /// springs, the solver's kept data and the events recorded between steps.
    template <class A>
    static void managers(A &a, WorldState &w) {
        contacts(a, w.contacts, w.bodies);
        sensors(a, w.sensors);
        islands(a, w.islands);
        joints(a, w.joints);
        io(a, w.springs.records, w.springs.free);
        solver(a, w.solver);
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
            std::uint8_t leaf = node->isLeaf();
            fcl::AABBd box = node->bv;
            io(a, leaf, box);
            std::uint32_t id = leaf ? bodyIndexOf(static_cast<const fcl::CollisionObjectd *>(node->data)) : rank(node);
            io(a, id);
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

    static void save(const WorldState &state, std::vector<std::uint8_t> &out);
    static void restore(WorldState &w, const std::uint8_t *data, std::size_t size);
    static void restoreBody(StateReader &a, WorldState &w, std::uint32_t index);
};

void StateFields::save(const WorldState &state, std::vector<std::uint8_t> &out) {
    // Saving reads only; StateFields' functions take what they list by reference.
    WorldState &w = const_cast<WorldState &>(state);
    StateWriter a(out);
    std::uint64_t fingerprint = shapesFingerprint(w.shapes, w.shapes.size());
    io(a, fingerprint);
    a.count(w.shapes.size());
    io(a, w.stepCount, w.plan);

    BodyStore &bodies = w.bodies;
    a.count(bodies.size());
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        BodyRecord &r = bodies[static_cast<std::uint32_t>(k)];
        io(a, r.alive, r.generation);
        if (!r.alive) continue;
        record(a, r);
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

void StateFields::restoreBody(StateReader &a, WorldState &w, std::uint32_t index) {
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
    record(a, r);
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
    if (shapes > w.shapes.size() || shapesFingerprint(w.shapes, shapes) != fingerprint)
        throw UnreadableState{"is from another World: its bodies were added with other shapes"};
    io(a, w.stepCount, w.plan);

    // The trees hold the objects of the bodies about to be replaced: emptied first.
    Broadphase &b = w.broadphase;
    for (auto *manager : {&b.awake_, &b.asleep_, &b.static_}) manager->clear();
    for (std::vector<fcl::CollisionObjectd *> &waiting : b.arrivals_) waiting.clear();
    BodyStore &bodies = w.bodies;
    const std::size_t slots = a.count(0, 5);
    bodies.records.resize(slots);
    for (std::size_t k = 0; k < slots; ++k) restoreBody(a, w, static_cast<std::uint32_t>(k));
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
