#include "collision/broadphase.h"

namespace cyclone::detail {
namespace {

// Where the walk puts its pairs, what decides where each goes (null: every pair is a
// candidate contact, and nothing is asked), and how many it may keep.
struct PairWalk {
    BroadphasePairs *out;
    const PairFilter *filter;
    std::size_t limit;
    bool complete = true;

    // False (and the walk stops) once the limit is reached.
    bool room() {
        if (out->contacts.size() + out->sensors.size() < limit) return true;
        complete = false;
        return false;
    }
};

// FCL calls this for every overlapping pair; recording them keeps the narrowphase (and
// its timing) a stage of its own. Returning true stops FCL's walk.
bool recordPair(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *data) {
    auto *walk = static_cast<PairWalk *>(data);
    if (!walk->room()) return true;
    walk->out->contacts.push_back({bodyIndexOf(o1), bodyIndexOf(o2)});
    return false;
}

// The same with a filter: a pair it drops is never a candidate.
bool recordFilteredPair(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *data) {
    auto *walk = static_cast<PairWalk *>(data);
    if (!walk->room()) return true;
    const CandidatePair pair{bodyIndexOf(o1), bodyIndexOf(o2)};
    switch (walk->filter->classify(pair.a, pair.b)) {
        case PairKind::Contact: walk->out->contacts.push_back(pair); break;
        case PairKind::Sensor: walk->out->sensors.push_back(pair); break;
        case PairKind::Filtered: ++walk->out->filtered; break;
    }
    return false;
}

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

bool Broadphase::findPairs(BroadphasePairs &out, const PairFilter *filter, std::size_t limit) {
    // Resting bodies stay inside their fat boxes: most steps of a settled scene change no
    // tree, and the walk would find the same pairs in the same order.
    if (changed_ || filter != lastFilter_ || limit != limit_) {
        flush();
        pairs_.clear();
        PairWalk walk{&pairs_, filter, limit};
        const auto record = filter ? recordFilteredPair : recordPair;
        if (!awake_.empty()) {
            awake_.collide(&walk, record);
            if (walk.complete && !asleep_.empty()) awake_.collide(&asleep_, &walk, record);
            if (walk.complete && !static_.empty()) awake_.collide(&static_, &walk, record);
        }
        changed_ = false;
        lastFilter_ = filter;
        limit_ = limit;
        complete_ = walk.complete;
    }
    out.contacts.insert(out.contacts.end(), pairs_.contacts.begin(), pairs_.contacts.end());
    out.sensors.insert(out.sensors.end(), pairs_.sensors.begin(), pairs_.sensors.end());
    out.filtered += pairs_.filtered;
    return complete_;
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
