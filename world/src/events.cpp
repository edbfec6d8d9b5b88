// Events: contact begin and end found by comparing each pair's touching state with the
// one it had at the end of the last step; sleep and wake recorded where they happen
// (World::Impl::wake and sleepIsland).
//
// The state is kept per pair slot together with the two BodyIds it belonged to, so a
// slot reused by another pair, or a pair whose body was removed (its generation moved
// on), ends the old contact before the new one begins. Everything is in vectors that
// keep their capacity: a step in steady state allocates nothing here.
#include <algorithm>

#include "world_impl.h"

namespace cyclone {

void World::Impl::openStepEvents() {
    // The step's list starts with what calls recorded since the last step.
    std::swap(events, pendingEvents);
    pendingEvents.clear();
    eventSink = &events;
}

void World::Impl::closeStepEvents() { eventSink = &pendingEvents; }

void World::Impl::detectContactEvents() {
    if (contactTracks.size() < pairs.slots()) contactTracks.resize(pairs.slots());
    // Only slots the narrowphase saw or that were removed can have changed. Those whose
    // state did change (few: a resting scene has none) are taken in slot order, so that
    // events come in the same order whichever way they were found.
    const auto stateOf = [&](std::uint32_t p) {
        const detail::PairState *pair = p < pairs.slots() ? &pairs[p] : nullptr;
        const bool touching = pair && pair->alive && pair->touching();
        return ContactTrack{touching ? idOf(pair->a) : BodyId(), touching ? idOf(pair->b) : BodyId(), touching};
    };
    // The changed slots are moved to the front of eventSlots, in place: a list of their
    // own would allocate the first time a late step changes more than it ever held.
    std::size_t changed = 0;
    for (std::uint32_t p : eventSlots) {
        const ContactTrack &track = contactTracks[p];
        const ContactTrack now = stateOf(p);
        if (track.touching != now.touching || (now.touching && (track.a != now.a || track.b != now.b)))
            eventSlots[changed++] = p;
    }
    eventSlots.resize(changed);
    std::sort(eventSlots.begin(), eventSlots.end());
    eventSlots.erase(std::unique(eventSlots.begin(), eventSlots.end()), eventSlots.end());
    for (std::uint32_t p : eventSlots) {
        ContactTrack &track = contactTracks[p];
        const ContactTrack now = stateOf(p);
        if (track.touching && (!now.touching || track.a != now.a || track.b != now.b)) {
            events.contactEnds.push_back({track.a, track.b});
            track.touching = false;
        }
        if (!now.touching || track.touching) continue;
        track = now;

        // The deepest point stands for the contact.
        const detail::PairState *pair = &pairs[p];
        const BodyRecord &ra = bodies[pair->a];
        const BodyRecord &rb = bodies[pair->b];
        const Matrix4 poseA = ra.body.getTransform();
        const Matrix4 poseB = rb.body.getTransform();
        ContactBegin begin;
        begin.a = now.a;
        begin.b = now.b;
        bool first = true;
        for (const detail::ManifoldState &m : pair->manifolds) {
            for (int i = 0; i < m.count; ++i) {
                const detail::PersistentPoint &point = m.points[i];
                if (!first && !(point.depth > begin.depth)) continue;
                first = false;
                begin.depth = point.depth;
                begin.normal = m.normal;
                begin.point = 0.5 * (poseA * point.localA + poseB * point.localB);
            }
        }
        const Vector3 va = ra.body.getVelocity() + ra.body.getRotation().cross(begin.point - ra.body.getPosition());
        const Vector3 vb = rb.body.getVelocity() + rb.body.getRotation().cross(begin.point - rb.body.getPosition());
        begin.approachSpeed = (va - vb).dot(begin.normal);
        events.contactBegins.push_back(begin);
    }
    eventSlots.clear();
}

const WorldEvents &World::events() const { return impl_->events; }

}  // namespace cyclone
