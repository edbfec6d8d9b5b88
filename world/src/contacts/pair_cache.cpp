#include "contacts/pair_cache.h"

#include <algorithm>
#include <limits>

#include "collision/round_side.h"

namespace cyclone::detail {
namespace {

std::size_t hash(std::uint64_t key) {
    // A 64-bit mix (splitmix64's finaliser): neighbouring body indices spread out.
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ULL;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebULL;
    key ^= key >> 31;
    return static_cast<std::size_t>(key);
}

// The squared distance between the points of a round core below two anchors (infinite
// when the side is not round).
real coreDistance2(const RoundCore &core, const Vector3 &a, const Vector3 &b) {
    if (core.radius == 0) return std::numeric_limits<real>::infinity();
    return (nearestCorePoint(core, a) - nearestCorePoint(core, b)).squaredNorm();
}

}  // namespace

std::size_t PairCache::position(std::uint64_t k) const {
    const std::size_t mask = table_.size() - 1;
    std::size_t at = hash(k) & mask;
    while (table_[at].key != k && table_[at].key != kEmpty) at = (at + 1) & mask;
    return at;
}

void PairCache::insert(std::uint64_t k, std::uint32_t slot) {
    if (2 * (used_ + 1) > table_.size()) {
        std::vector<Entry> old(std::max<std::size_t>(64, 2 * table_.size()));
        old.swap(table_);
        for (const Entry &e : old)
            if (e.key != kEmpty) table_[position(e.key)] = e;
    }
    table_[position(k)] = {k, slot};
    ++used_;
}

void PairCache::erase(std::uint64_t k) {
    const std::size_t mask = table_.size() - 1;
    std::size_t hole = position(k);
    if (table_[hole].key == kEmpty) return;
    // Backward-shift deletion: move later entries of the probe run into the hole when
    // their home position does not lie between the hole and them.
    for (std::size_t next = (hole + 1) & mask; table_[next].key != kEmpty; next = (next + 1) & mask) {
        const std::size_t home = hash(table_[next].key) & mask;
        const bool stays = hole <= next ? (hole < home && home <= next) : (hole < home || home <= next);
        if (stays) continue;
        table_[hole] = table_[next];
        hole = next;
    }
    table_[hole] = Entry();
    --used_;
}

std::uint32_t PairCache::findOrAdd(std::uint32_t i, std::uint32_t j, bool &created) {
    const std::uint64_t k = key(i, j);
    const long found = find(i, j);
    if (found >= 0) {
        created = false;
        return static_cast<std::uint32_t>(found);
    }
    created = true;
    std::uint32_t slot;
    if (!free_.empty()) {
        slot = free_.back();
        free_.pop_back();
    } else {
        slot = static_cast<std::uint32_t>(pairs_.size());
        pairs_.resize(slot + 1);
    }
    PairState &p = pairs_[slot];
    p.a = std::min(i, j);
    p.b = std::max(i, j);
    p.manifolds.clear();
    p.lastSeen = 0;
    p.testedStill = false;
    p.testedStep = 0;
    p.alive = true;
    insert(k, slot);
    return slot;
}

long PairCache::find(std::uint32_t i, std::uint32_t j) const {
    if (table_.empty()) return -1;
    const Entry &e = table_[position(key(i, j))];
    return e.key == kEmpty ? -1 : long(e.slot);
}

void PairCache::remove(std::uint32_t pair) {
    PairState &p = pairs_[pair];
    if (!p.alive) return;
    erase(key(p.a, p.b));
    p.alive = false;
    p.manifolds.clear();
    free_.push_back(pair);
}

void refreshFromAnchors(ManifoldState &m, const Matrix4 &poseA, const Matrix4 &poseB) {
    m.normal = poseA.linear() * m.localNormal;
    // (A's point - B's point) . n, with A's point taken along the normal in A's frame
    // (A's rotation turns localNormal into n): B's points are needed for the order anyway.
    const real offsetA = poseA.translation().dot(m.normal);
    Vector3 pointB[Manifold::kMaxPoints];
    real depth[Manifold::kMaxPoints];
    for (int i = 0; i < m.count; ++i) {
        PersistentPoint &p = m.points[i];
        pointB[i] = poseB * p.localB;
        p.depth = p.localA.dot(m.localNormal) + offsetA - pointB[i].dot(m.normal);
        depth[i] = p.depth;
    }
    // In the order a fresh manifold would have: a frozen order makes Gauss-Seidel favour
    // the same corner step after step, and a tall stack sways.
    int order[Manifold::kMaxPoints];
    contactOrder(pointB, depth, m.count, m.normal, order);
    if (std::is_sorted(order, order + m.count)) return;  // already in that order
    PersistentPoint before[Manifold::kMaxPoints];
    std::copy(m.points, m.points + m.count, before);
    for (int i = 0; i < m.count; ++i) m.points[i] = before[order[i]];
}

void keepNearPoints(std::vector<ManifoldState> &manifolds, const Matrix4 &poseA, const Matrix4 &poseB, real distance,
                    std::uint64_t &anchorsIssued) {
    std::size_t used = 0;
    for (ManifoldState &m : manifolds) {
        m.anchorsId = ++anchorsIssued;  // points may go, and the manifold may take another's place
        m.normal = poseA.linear() * m.localNormal;
        int kept = 0;
        for (int i = 0; i < m.count; ++i) {
            PersistentPoint p = m.points[i];
            const Vector3 gap = poseA * p.localA - poseB * p.localB;
            p.depth = gap.dot(m.normal);
            if (gap.norm() >= distance) continue;
            m.points[kept++] = p;
        }
        m.count = kept;
        if (kept > 0) manifolds[used++] = m;
    }
    manifolds.resize(used);
}

void mergeManifold(ManifoldState &state, const Manifold &fresh, const Matrix4 &poseA, const Matrix4 &poseB,
                   const CollisionShape &shapeA, const CollisionShape &shapeB, real matchDistance,
                   std::uint64_t anchorsId) {
    ManifoldState old = state;
    state.anchorsId = anchorsId;
    const bool sameNormal = old.count > 0 && old.normal.dot(fresh.normal) > 0.95;
    // The patch's friction belongs to the contact as a whole: it carries over while the
    // normal does, whichever points the fresh manifold has.
    if (!sameNormal) {
        state.frictionImpulse.setZero();
        state.twistImpulse = 0;
    }
    state.normal = fresh.normal;
    state.childA = fresh.childA;
    state.childB = fresh.childB;
    state.localNormal = poseA.linear().transpose() * fresh.normal;
    state.count = fresh.count;
    const real match2 = matchDistance * matchDistance;
    const RoundCore coreA = sameNormal ? roundSideAt(shapeA, fresh.childA, state.localNormal) : RoundCore();
    const RoundCore coreB =
        sameNormal ? roundSideAt(shapeB, fresh.childB, -(poseB.linear().transpose() * fresh.normal)) : RoundCore();
    for (int i = 0; i < fresh.count; ++i) {
        PersistentPoint &p = state.points[i];
        p.localA = poseA.inverse() * fresh.points[i].pointA;
        p.localB = poseB.inverse() * fresh.points[i].pointB;
        p.depth = fresh.points[i].depth;
        p.normalImpulse = 0;
        p.id = i;
        if (!sameNormal) continue;
        real best = match2;
        for (int j = 0; j < old.count; ++j) {
            const real d2 = std::min({(old.points[j].localA - p.localA).squaredNorm(),
                                      coreDistance2(coreA, old.points[j].localA, p.localA),
                                      coreDistance2(coreB, old.points[j].localB, p.localB)});
            if (d2 < best) {
                best = d2;
                p.normalImpulse = old.points[j].normalImpulse;
            }
        }
    }
}

}  // namespace cyclone::detail
