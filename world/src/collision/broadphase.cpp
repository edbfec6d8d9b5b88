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

fcl::DynamicAABBTreeCollisionManagerd *Broadphase::manager(Tree tree) {
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
    if (auto *source = manager(from)) source->unregisterObject(object);
    if (auto *target = manager(to)) {
        target->registerObject(object);
        target->update(object);
    }
}

void Broadphase::refitAwake(const std::vector<fcl::CollisionObjectd *> &moved) {
    if (moved.empty()) return;
    awake_.update(moved);
    changed_ = true;
    ++changes_;
}

void Broadphase::refit(fcl::CollisionObjectd *object, Tree tree) {
    if (auto *m = manager(tree)) {
        m->update(object);
        changed_ = true;
        ++changes_;
    }
}

const fcl::detail::NodeBase<fcl::AABBd> *Broadphase::root(Tree tree) const {
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
    static_cast<BoxProbe *>(probe_.get())->setBox(box);
    ProbeQuery query{probe_.get(), &out};
    for (fcl::DynamicAABBTreeCollisionManagerd *tree : {&awake_, &asleep_, &static_})
        if (!tree->empty()) tree->collide(probe_.get(), &query, recordOther);
}

}  // namespace cyclone::detail
