#include "contacts/sensors.h"

#include <algorithm>

#include "collision/narrowphase.h"
#include "world/body_store.h"
#include "world/step_context.h"

namespace cyclone::detail {
namespace {

// FCL's yes-or-no test (no contact points): all a sensor needs.
bool overlapping(const BodyRecord &a, const BodyRecord &b) {
    // A height field's box is not its shape: its triangles are tested (narrowphase.h).
    if (a.shape->shape().type == ShapeType::Heightfield || b.shape->shape().type == ShapeType::Heightfield)
        return intersects(*a.shape, a.body.getTransform(), *b.shape, b.body.getTransform());
    fcl::CollisionRequestd request(1, false);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::CollisionResultd result;
    fcl::collide(a.shape->geometry().get(), a.body.getTransform(), b.shape->geometry().get(), b.body.getTransform(),
                 request, result);
    return result.isCollision();
}

bool bySensorThenBody(const SensorEvent &x, const SensorEvent &y) {
    return x.sensor.index != y.sensor.index ? x.sensor.index < y.sensor.index : x.body.index < y.body.index;
}

}  // namespace

void Sensors::added(const BodyStore &bodies, std::uint32_t index) {
    const BodyRecord &r = bodies[index];
    const bool awakeDynamic = !r.immovable && r.body.getAwake();
    if (r.sensor || (bodies.sensorCount > 0 && !awakeDynamic)) recheck(index);
}

void Sensors::moved(const BodyStore &bodies, std::uint32_t index) {
    if (bodies.sensorCount > 0 && bodies[index].immovable) recheck(index);
}

void Sensors::removed(const BodyStore &bodies, WorldEvents &events, std::uint32_t index) {
    for (std::uint32_t slot = 0; slot < overlaps_.slots(); ++slot) {
        const PairState &pair = overlaps_[slot];
        if (pair.alive && (pair.a == index || pair.b == index)) end(bodies, events, slot);
    }
}

void Sensors::filterChanged(const BodyStore &bodies, WorldEvents &events, std::uint32_t index) {
    for (std::uint32_t slot = 0; slot < overlaps_.slots(); ++slot) {
        const PairState &pair = overlaps_[slot];
        if (pair.alive && (pair.a == index || pair.b == index) && bodies.classify(pair.a, pair.b) != PairKind::Sensor)
            end(bodies, events, slot);
    }
    if (bodies.sensorCount > 0) recheck(index);
}

void Sensors::end(const BodyStore &bodies, WorldEvents &events, std::uint32_t slot) {
    const PairState &pair = overlaps_[slot];
    const bool aIsSensor = bodies[pair.a].sensor;
    const std::uint32_t sensor = aIsSensor ? pair.a : pair.b, body = aIsSensor ? pair.b : pair.a;
    events.sensorEnds.push_back(
        {bodies.idOf(sensor), bodies.idOf(body), bodies[sensor].userData, bodies[body].userData});
    overlaps_.remove(slot);
}

void Sensors::gatherAround(const BodyStore &bodies, Broadphase &broadphase, std::uint32_t index) {
    const auto consider = [&](std::uint32_t other) {
        if (other == index || bodies.classify(index, other) != PairKind::Sensor) return;
        candidates_.push_back(bodies[index].sensor ? CandidatePair{index, other} : CandidatePair{other, index});
    };
    const BodyRecord &r = bodies[index];
    if (r.isPlane) {
        // A half-space has no box to look up: every other body that is not a plane.
        for (std::uint32_t other : bodies.order)
            if (!bodies[other].isPlane && !bodies[other].isolated) consider(other);
        return;
    }
    found_.clear();
    broadphase.overlapping(r.object->getAABB(), found_);
    for (std::uint32_t other : found_) consider(other);
    for (std::uint32_t plane : bodies.planes) consider(plane);
}

void Sensors::update(const StepContext &context, const BodyStore &bodies, Broadphase &broadphase,
                     const std::vector<CandidatePair> &candidates, WorldEvents &events, StepStats &stats) {
    const std::uint64_t step = context.stepCount;
    const std::size_t beginsBefore = events.sensorBegins.size();
    const std::size_t endsBefore = events.sensorEnds.size();

    candidates_.clear();
    for (const CandidatePair &c : candidates)
        candidates_.push_back(bodies[c.a].sensor ? c : CandidatePair{c.b, c.a});
    if (checkedStep_.size() < bodies.size()) checkedStep_.resize(bodies.size(), 0);
    for (std::uint32_t index : rechecks_) {
        const BodyRecord &r = bodies[index];
        if (!r.alive || r.isolated || checkedStep_[index] == step) continue;
        checkedStep_[index] = step;
        gatherAround(bodies, broadphase, index);
    }
    rechecks_.clear();
    // Each pair once, sensor by sensor: the events come in this order.
    std::sort(candidates_.begin(), candidates_.end(),
              [](const CandidatePair &x, const CandidatePair &y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end(),
                                  [](const CandidatePair &x, const CandidatePair &y) { return x.a == y.a && x.b == y.b; }),
                      candidates_.end());

    for (const CandidatePair &c : candidates_) {
        ++stats.sensorPairs;
        if (overlapping(bodies[c.a], bodies[c.b])) {
            bool created = false;
            const std::uint32_t slot = overlaps_.findOrAdd(c.a, c.b, created);
            overlaps_[slot].lastSeen = step;
            if (created)
                events.sensorBegins.push_back({bodies.idOf(c.a), bodies.idOf(c.b), bodies[c.a].userData, bodies[c.b].userData});
        } else if (const long slot = overlaps_.find(c.a, c.b); slot >= 0) {
            end(bodies, events, static_cast<std::uint32_t>(slot));
        }
    }

    // An overlap the step did not report although one of its bodies was in the walk: their
    // boxes parted.
    for (std::uint32_t slot = 0; slot < overlaps_.slots(); ++slot) {
        const PairState &pair = overlaps_[slot];
        if (!pair.alive || pair.lastSeen == step) continue;
        const BodyRecord &a = bodies[pair.a];
        const BodyRecord &b = bodies[pair.b];
        if (a.simulated || a.moving || b.simulated || b.moving || checkedStep_[pair.a] == step ||
            checkedStep_[pair.b] == step)
            end(bodies, events, slot);
    }
    std::sort(events.sensorBegins.begin() + static_cast<std::ptrdiff_t>(beginsBefore), events.sensorBegins.end(),
              bySensorThenBody);
    std::sort(events.sensorEnds.begin() + static_cast<std::ptrdiff_t>(endsBefore), events.sensorEnds.end(),
              bySensorThenBody);
}

}  // namespace cyclone::detail
