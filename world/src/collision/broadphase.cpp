#include "collision/broadphase.h"

namespace cyclone::detail {
namespace {

using Node = fcl::detail::NodeBase<fcl::AABBd>;

// Where a walk puts its pairs, what decides where each goes (null: every pair is a
// candidate contact, and nothing is asked), and how many it may keep.
struct PairWalk {
    BroadphasePairs *out;
    const PairFilter *filter;
    std::size_t limit;
    /// Counts the pairs of every piece, to stop each once all have passed the limit.
    std::atomic<std::size_t> *walked = nullptr;
    bool complete = true;

    // False (and the walk stops) once the limit is reached.
    bool room() {
        const std::size_t found = walked ? walked->fetch_add(1, std::memory_order_relaxed)
                                         : out->contacts.size() + out->sensors.size();
        if (found < limit) return true;
        complete = false;
        return false;
    }

    // Records the pair of two leaves' objects; true stops the walk.
    bool record(const Node *first, const Node *second) {
        if (!room()) return true;
        const CandidatePair pair{bodyIndexOf(static_cast<const fcl::CollisionObjectd *>(first->data)),
                                 bodyIndexOf(static_cast<const fcl::CollisionObjectd *>(second->data))};
        if (!filter) {
            out->contacts.push_back(pair);
            return false;
        }
        switch (filter->classify(pair.a, pair.b)) {
            case PairKind::Contact: out->contacts.push_back(pair); break;
            case PairKind::Sensor: out->sensors.push_back(pair); break;
            case PairKind::Filtered: ++out->filtered; break;
        }
        return false;
    }
};

// FCL's AABB::overlap and AABB::size, the same arithmetic written here so that it
// inlines: libfcl instantiates them out of line, two calls for each pair of nodes the walk
// meets (6.3 million overlap calls in mixed1000's first 150 steps).
bool boxesOverlap(const fcl::AABBd &x, const fcl::AABBd &y) {
    return !(x.min_.array() > y.max_.array()).any() && !(x.max_.array() < y.min_.array()).any();
}
real boxSize(const fcl::AABBd &box) { return (box.max_ - box.min_).squaredNorm(); }

// Whether the walk splits `first` (else `second`) at a pair of nodes that are not both
// leaves: the one with the larger box, as FCL's walk does.
bool splitsFirst(const Node *first, const Node *second) {
    return second->isLeaf() || (!first->isLeaf() && boxSize(first->bv) > boxSize(second->bv));
}

// The pairs between two subtrees, in FCL's order; true stops the walk.
bool walkBetween(const Node *first, const Node *second, PairWalk &walk) {
    if (!boxesOverlap(first->bv, second->bv)) return false;
    if (first->isLeaf() && second->isLeaf()) return walk.record(first, second);
    if (splitsFirst(first, second))
        return walkBetween(first->children[0], second, walk) || walkBetween(first->children[1], second, walk);
    return walkBetween(first, second->children[0], walk) || walkBetween(first, second->children[1], walk);
}

// The pairs within a subtree, in FCL's order: each child's, then between the children.
bool walkWithin(const Node *node, PairWalk &walk) {
    if (node->isLeaf()) return false;
    return walkWithin(node->children[0], walk) || walkWithin(node->children[1], walk) ||
           walkBetween(node->children[0], node->children[1], walk);
}

// Pieces a walk is cut into, at least: a few per thread, so that uneven pieces even out.
constexpr std::size_t kWalkPieces = 32;
// A walk of fewer awake bodies than this is not cut: it is too short to share.
constexpr std::size_t kMinCutLeaves = 256;

// An object that is only a box: what the trees test against in overlapping().
class BoxProbe : public fcl::CollisionObjectd {
public:
    BoxProbe() : fcl::CollisionObjectd(std::make_shared<fcl::Boxd>(1, 1, 1)) {}
    void setBox(const fcl::AABBd &box) { aabb = box; }
};

struct ProbeQuery {
    const fcl::CollisionObjectd *probe;
    std::vector<std::uint32_t> *out;
};

bool recordOther(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *data) {
    auto *query = static_cast<ProbeQuery *>(data);
    query->out->push_back(bodyIndexOf(o1 == query->probe ? o2 : o1));
    return false;
}

}  // namespace

Broadphase::Broadphase() : probe_(std::make_unique<BoxProbe>()) {}

fcl::DynamicAABBTreeCollisionManagerd *Broadphase::manager(Tree tree) const {
    switch (tree) {
        case Tree::Awake: return &awake_;
        case Tree::Asleep: return &asleep_;
        case Tree::Static: return &static_;
        case Tree::None: break;
    }
    return nullptr;
}

void Broadphase::place(fcl::CollisionObjectd *object, Tree from, Tree to) {
    if (from == to) return;
    changed_ = true;
    ++changes_;
    if (auto *source = manager(from)) {
        std::vector<fcl::CollisionObjectd *> &waiting = arrivals_[static_cast<int>(from) - 1];
        if (!waiting.empty()) flushTree(from);
        source->unregisterObject(object);
    }
    if (to != Tree::None) {
        arrivals_[static_cast<int>(to) - 1].push_back(object);
        waiting_.store(true, std::memory_order_release);
    }
}

void Broadphase::flush() const {
    if (!waiting_.load(std::memory_order_acquire)) return;
    const std::lock_guard<std::mutex> lock(flushing_);
    if (!waiting_.load(std::memory_order_relaxed)) return;
    rebuiltLeaves_ = 0;
    insertedLeaves_ = 0;
    for (Tree tree : {Tree::Awake, Tree::Asleep, Tree::Static}) flushTree(tree);
    waiting_.store(false, std::memory_order_release);
}

void Broadphase::flushTree(Tree tree) const {
    std::vector<fcl::CollisionObjectd *> &waiting = arrivals_[static_cast<int>(tree) - 1];
    if (waiting.empty()) return;
    fcl::DynamicAABBTreeCollisionManagerd &target = *manager(tree);
    const std::size_t leaves = target.size();
    if (2 * waiting.size() < leaves) {
        for (fcl::CollisionObjectd *object : waiting) target.registerObject(object);
        // FCL rebalances on an update: it measures the height (O(n)) and rebuilds the
        // tree top-down when it is more than 10 levels above log2 n (else a few rotations).
        target.update(waiting.back());
        insertedLeaves_ += waiting.size();
    } else {
        // The tree's leaves in its own order, then the arrivals in theirs: the rebuilt tree
        // depends on nothing but the calls made (not on addresses), so runs repeat.
        std::vector<fcl::CollisionObjectd *> all;
        all.reserve(leaves + waiting.size());
        std::vector<const fcl::detail::NodeBase<fcl::AABBd> *> stack;
        if (const auto *top = target.getTree().getRoot()) stack.push_back(top);
        while (!stack.empty()) {
            const auto *node = stack.back();
            stack.pop_back();
            if (node->isLeaf()) {
                all.push_back(static_cast<fcl::CollisionObjectd *>(node->data));
            } else {
                stack.push_back(node->children[1]);
                stack.push_back(node->children[0]);
            }
        }
        all.insert(all.end(), waiting.begin(), waiting.end());
        target.clear();
        target.registerObjects(all);  // top-down build, median splits: O(n log n)
        rebuiltLeaves_ += all.size();
    }
    waiting.clear();
}

void Broadphase::refitAwake(const std::vector<fcl::CollisionObjectd *> &moved) {
    if (moved.empty()) return;
    flush();
    awake_.update(moved);
    changed_ = true;
    ++changes_;
}

void Broadphase::refit(fcl::CollisionObjectd *object, Tree tree) {
    flush();
    if (auto *m = manager(tree)) {
        m->update(object);
        changed_ = true;
        ++changes_;
    }
}

const fcl::detail::NodeBase<fcl::AABBd> *Broadphase::root(Tree tree) const {
    flush();
    switch (tree) {
        case Tree::Awake: return awake_.getTree().getRoot();
        case Tree::Asleep: return asleep_.getTree().getRoot();
        case Tree::Static: return static_.getTree().getRoot();
        case Tree::None: break;
    }
    return nullptr;
}

bool Broadphase::mustWalk(const PairFilter *filter, std::size_t limit) {
    // Resting bodies stay inside their fat boxes: most steps of a settled scene change no
    // tree, and the walk would find the same pairs in the same order.
    if (!changed_ && filter == lastFilter_ && limit == limit_) return false;
    flush();
    changed_ = false;
    lastFilter_ = filter;
    limit_ = limit;
    return true;
}

int Broadphase::cutWalk() {
    // The whole walk, then each piece replaced by the pieces it walks in turn (dropping
    // those that find nothing), until there are enough or none can be cut.
    std::vector<WalkNodes> &cut = cut_, &next = nextCut_;
    cut.clear();
    walked_.store(0, std::memory_order_relaxed);
    if (const Node *awake = awake_.empty() ? nullptr : awake_.getTree().getRoot()) {
        cut.push_back({awake, nullptr});
        for (const auto *other : {&asleep_, &static_})
            if (!other->empty()) cut.push_back({awake, other->getTree().getRoot()});
    }
    for (bool split = awake_.size() >= kMinCutLeaves; split && cut.size() < kWalkPieces;) {
        split = false;
        next.clear();
        for (const WalkNodes &piece : cut) {
            const Node *first = piece.first;
            const Node *second = piece.second;
            if (!second) {
                if (first->isLeaf()) continue;
                split = true;
                next.push_back({first->children[0], nullptr});
                next.push_back({first->children[1], nullptr});
                next.push_back({first->children[0], first->children[1]});
            } else if (!boxesOverlap(first->bv, second->bv)) {
                split = true;
            } else if (first->isLeaf() && second->isLeaf()) {
                next.push_back(piece);
            } else {
                split = true;
                if (splitsFirst(first, second)) {
                    next.push_back({first->children[0], second});
                    next.push_back({first->children[1], second});
                } else {
                    next.push_back({first, second->children[0]});
                    next.push_back({first, second->children[1]});
                }
            }
        }
        cut.swap(next);
    }
    if (pieces_.size() < cut.size()) pieces_.resize(cut.size());
    for (std::size_t k = 0; k < cut.size(); ++k) {
        pieces_[k].nodes = cut[k];
        pieces_[k].pairs.clear();
    }
    pieceCount_ = static_cast<int>(cut.size());
    return pieceCount_;
}

void Broadphase::walkPiece(int piece, const PairFilter *filter, std::size_t limit) {
    WalkPiece &p = pieces_[static_cast<std::size_t>(piece)];
    PairWalk walk{&p.pairs, filter, limit, &walked_};
    if (p.nodes.second) walkBetween(p.nodes.first, p.nodes.second, walk);
    else walkWithin(p.nodes.first, walk);
}

void Broadphase::joinWalk(const PairFilter *filter, std::size_t limit) {
    pairs_.clear();
    if (walked_.load(std::memory_order_relaxed) < limit) {
        // Every piece ran to its end: their pairs, in order, are the walk's.
        for (int k = 0; k < pieceCount_; ++k) {
            const BroadphasePairs &found = pieces_[static_cast<std::size_t>(k)].pairs;
            pairs_.contacts.insert(pairs_.contacts.end(), found.contacts.begin(), found.contacts.end());
            pairs_.sensors.insert(pairs_.sensors.end(), found.sensors.begin(), found.sensors.end());
            pairs_.filtered += found.filtered;
        }
        complete_ = true;
        return;
    }
    // Past the limit: the first pairs of the walk's order are kept, as one walk finds them.
    PairWalk walk{&pairs_, filter, limit};
    if (const Node *awake = awake_.empty() ? nullptr : awake_.getTree().getRoot()) {
        bool stopped = walkWithin(awake, walk);
        for (const auto *other : {&asleep_, &static_})
            if (!stopped && !other->empty()) stopped = walkBetween(awake, other->getTree().getRoot(), walk);
    }
    complete_ = walk.complete;
}

}  // namespace cyclone::detail

namespace cyclone::detail {

void Broadphase::overlapping(const fcl::AABBd &box, std::vector<std::uint32_t> &out) {
    flush();
    static_cast<BoxProbe *>(probe_.get())->setBox(box);
    ProbeQuery query{probe_.get(), &out};
    for (fcl::DynamicAABBTreeCollisionManagerd *tree : {&awake_, &asleep_, &static_})
        if (!tree->empty()) tree->collide(probe_.get(), &query, recordOther);
}

}  // namespace cyclone::detail
