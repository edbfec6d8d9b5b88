// How a body moves between awake, asleep and isolated. A body sleeps and wakes with its
// island (RigidBody::setAwake), moving between the broadphase's awake and sleeping trees;
// an isolated body (non-finite state) leaves collision and the solve for good. A body
// woken during a step, before its contacts are final, joins that step's solve
// (Integration::admit): a hit on a sleeping body is a hit on a body with mass.
#include "world/body_transitions.h"
#include "world/world_impl.h"

namespace cyclone::detail {

void WorldState::wake(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    if (r.immovable || r.isolated) return;
    if (r.sleepingIsland < 0) {
        if (!r.body.getAwake()) {
            r.body.setAwake(true);
            events.sink->wokeUp.push_back(bodies.idOf(index));
        } else if (r.held) {
            // A held body wakes as a sleeping one does: its sleep average at twice the
            // threshold, so that it is solved for about a second (dynamics/holding.h).
            r.body.setAwake(true);
        }
        bodies.updateAwakeList(index);
        integration.admit(bodies, BodyTransitions(*this), index);
        return;
    }
    const int island = r.sleepingIsland;
    for (std::uint32_t m : islands.sleeping[island]) {
        BodyRecord &member = bodies[m];
        member.sleepingIsland = -1;
        member.body.setAwake(true);
        events.sink->wokeUp.push_back(bodies.idOf(m));
        member.object->place(member.body.getTransform(), kBroadphaseMargin);
        setTree(m, Tree::Awake);
        bodies.updateAwakeList(m);
        integration.admit(bodies, BodyTransitions(*this), m);
    }
    islands.sleeping[island].clear();
    islands.freeSleeping.push_back(island);
}

void WorldState::sleepIsland(const std::uint32_t *members, int count, bool report) {
    int island;
    if (!islands.freeSleeping.empty()) {
        island = islands.freeSleeping.back();
        islands.freeSleeping.pop_back();
    } else {
        island = static_cast<int>(islands.sleeping.size());
        islands.sleeping.emplace_back();
    }
    std::vector<std::uint32_t> &list = islands.sleeping[island];
    list.clear();
    for (int i = 0; i < count; ++i) {
        BodyRecord &r = bodies[members[i]];
        if (!r.alive || r.immovable || r.sleepingIsland >= 0) continue;
        list.push_back(members[i]);
        r.body.setAwake(false);  // its velocities zeroed
        r.seen.look(r.body, stepCount + 1);
        r.held = false;
        r.sleepingIsland = island;
        r.island = -1;
        setTree(members[i], Tree::Asleep);
        bodies.updateAwakeList(members[i]);
        if (report) events.sink->fellAsleep.push_back(bodies.idOf(members[i]));
    }
    if (list.empty()) islands.freeSleeping.push_back(island);
}

void WorldState::isolate(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    if (!r.isolated) ++bodies.isolatedCount;
    r.isolated = true;
    r.simulated = false;
    r.held = false;
    bodies.updateAwakeList(index);
    setTree(index, Tree::None);
    contacts.removePairsOf(bodies, index);
    sensors.removed(bodies, *events.sink, index);
}

void WorldState::setTree(std::uint32_t index, Tree tree) {
    BodyRecord &r = bodies[index];
    if (!r.object) {
        r.tree = Tree::None;
        return;
    }
    broadphase.place(r.object.get(), r.tree, tree);
    r.tree = tree;
}

void WorldState::refreshCollisionObject(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    r.seen.look(r.body, stepCount + 1);
    if (r.object && r.object->place(r.body.getTransform(), kBroadphaseMargin))
        broadphase.refit(r.object.get(), r.tree);
    sensors.moved(bodies, index);
    if (!r.immovable) {
        wake(index);
        return;
    }
    // A moved static body wakes what touched it.
    for (std::uint32_t p : bodies[index].pairs) {
        const PairState &pair = contacts.pairs[p];
        const std::uint32_t other = pair.a == index ? pair.b : pair.a;
        if (!bodies[other].immovable) wake(other);
    }
}

void BodyTransitions::wake(std::uint32_t index) const { world_->wake(index); }

void BodyTransitions::isolate(std::uint32_t index) const { world_->isolate(index); }

void BodyTransitions::setTree(std::uint32_t index, Tree tree) const { world_->setTree(index, tree); }

void BodyTransitions::refresh(std::uint32_t index) const { world_->refreshCollisionObject(index); }

}  // namespace cyclone::detail
