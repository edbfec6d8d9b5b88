#include "broadphase.h"

namespace cyclone::detail {
namespace {

// FCL calls this for every overlapping pair; recording them keeps the narrowphase (and
// its timing) a stage of its own.
bool recordPair(fcl::CollisionObjectd *o1, fcl::CollisionObjectd *o2, void *data) {
    auto *out = static_cast<std::vector<CandidatePair> *>(data);
    out->push_back({bodyIndexOf(o1), bodyIndexOf(o2)});
    return false;
}

}  // namespace

Broadphase::Broadphase() = default;

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
    if (auto *source = manager(from)) source->unregisterObject(object);
    if (auto *target = manager(to)) {
        target->registerObject(object);
        target->update(object);
    }
}

void Broadphase::refitAwake(const std::vector<fcl::CollisionObjectd *> &moved) {
    if (!moved.empty()) awake_.update(moved);
}

void Broadphase::refit(fcl::CollisionObjectd *object, Tree tree) {
    if (auto *m = manager(tree)) m->update(object);
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

void Broadphase::findPairs(std::vector<CandidatePair> &out) {
    if (awake_.empty()) return;
    awake_.collide(&out, recordPair);
    if (!asleep_.empty()) awake_.collide(&asleep_, &out, recordPair);
    if (!static_.empty()) awake_.collide(&static_, &out, recordPair);
}

}  // namespace cyclone::detail
