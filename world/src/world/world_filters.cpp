// Which pairs may touch or be seen: pair rules (World::setPairCollision), sensors, and
// what a change of either costs the broadphase and the sensors.
#include <algorithm>
#include <string>

#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {
namespace {

void requireBody(const detail::BodyStore &bodies, const char *function, const char *field, BodyId id) {
    if (!bodies.contains(id))
        detail::refuse(function, field, "does not name a body of this world (index " + std::to_string(id.index) +
                                            ", generation " + std::to_string(id.generation) + ")");
}

void eraseFrom(std::vector<std::uint32_t> &list, std::uint32_t value) {
    const auto at = std::find(list.begin(), list.end(), value);
    if (at == list.end()) return;
    *at = list.back();
    list.pop_back();
}

}  // namespace

void detail::WorldState::filterChanged(std::uint32_t index) {
    // The broadphase replays its last walk while no tree changes: it must ask again.
    broadphase.invalidate();
    sensors.filterChanged(bodies, *events.sink, index);
}

void detail::WorldState::leaveFilters(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    sensors.removed(bodies, *events.sink, index);
    for (std::uint32_t other : r.keptApart) {
        eraseFrom(bodies[other].keptApart, index);
        --bodies.keptApartCount;
    }
    r.keptApart.clear();
    if (r.sensor) --bodies.sensorCount;
    r.sensor = false;
}

void World::setPairCollision(BodyId a, BodyId b, bool collide) {
    static const char *function = "World::setPairCollision";
    Impl &w = *impl_;
    requireBody(w.bodies, function, "a", a);
    requireBody(w.bodies, function, "b", b);
    if (a == b) detail::refuse(function, "b", "must name another body than a");
    if (collide != w.bodies.keptApart(a.index, b.index)) return;  // already so

    detail::BodyRecord &ra = w.bodies[a.index];
    detail::BodyRecord &rb = w.bodies[b.index];
    if (collide) {
        eraseFrom(ra.keptApart, b.index);
        eraseFrom(rb.keptApart, a.index);
        --w.bodies.keptApartCount;
        // Two sleeping bodies would not meet again until something woke them.
        if (!ra.immovable) w.wake(a.index);
        if (!rb.immovable) w.wake(b.index);
    } else {
        ra.keptApart.push_back(b.index);
        rb.keptApart.push_back(a.index);
        ++w.bodies.keptApartCount;
        if (const long p = w.contacts.pairs.find(a.index, b.index); p >= 0) {
            // What rested on the other loses its support.
            if (w.contacts.pairs[p].touching()) {
                if (!ra.immovable) w.wake(a.index);
                if (!rb.immovable) w.wake(b.index);
            }
            w.contacts.removePair(w.bodies, static_cast<std::uint32_t>(p));
        }
    }
    w.filterChanged(a.index);
    w.filterChanged(b.index);
}

bool World::pairCollision(BodyId a, BodyId b) const {
    static const char *function = "World::pairCollision";
    const Impl &w = *impl_;
    requireBody(w.bodies, function, "a", a);
    requireBody(w.bodies, function, "b", b);
    return !w.bodies.keptApart(a.index, b.index);
}

bool World::isSensor(BodyId id) const { return impl_->bodies.record(id, "World::isSensor").sensor; }

}  // namespace cyclone
