/// \file
/// What happened in a step: contacts that began or ended, bodies that fell asleep or
/// woke up. Read them with World::events() after World::step().
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/core.h"
#include "cyclone/world/joints.h"
#include "cyclone/world/settings.h"

namespace cyclone {

/// Two bodies' shapes began to touch: the narrowphase found them intersecting after a
/// step in which they did not (or in which the pair did not exist).
struct ContactBegin {
    /// One body of the pair (the one with the smaller BodyId::index).
    BodyId a;
    /// The other body of the pair.
    BodyId b;
    /// World-space point of the deepest contact, midway between the two surfaces, m.
    Vector3 point = Vector3::Zero();
    /// Unit contact normal, world space, pointing from `a` towards `b`.
    Vector3 normal = Vector3::UnitY();
    /// Penetration of the deepest contact point, m: > 0 overlapping, 0 touching, < 0 for
    /// bodies still apart: a speculative contact, made in the step in which the bodies,
    /// at their speeds, can close the gap (down to minus the distance they cover in the
    /// step), or a point kept just apart (down to -WorldSettings::speculativeDistance).
    real depth = 0;
    /// Speed at which the two bodies approached each other along `normal` at `point`
    /// when the contact was found, before the solver acted, m/s: > 0 approaching, < 0
    /// separating. An impact sound can be scaled by it.
    real approachSpeed = 0;
    /// BodySettings::userData of `a`.
    std::uint64_t userDataA = 0;
    /// BodySettings::userData of `b`.
    std::uint64_t userDataB = 0;
};

/// Two bodies that touched at the end of the previous step no longer do: they moved
/// apart, or one of them was removed (its BodyId is then stale: World::contains() is
/// false) or isolated for a non-finite state.
struct ContactEnd {
    /// One body of the pair (the one with the smaller BodyId::index).
    BodyId a;
    /// The other body of the pair.
    BodyId b;
    /// BodySettings::userData of `a` (as it was when the contact began).
    std::uint64_t userDataA = 0;
    /// BodySettings::userData of `b` (as it was when the contact began).
    std::uint64_t userDataB = 0;
};

/// The push a touching pair's contacts gave in the last step: for damage and impact sounds.
struct ContactImpulse {
    /// One body of the pair (the one with the smaller BodyId::index).
    BodyId a;
    /// The other body of the pair.
    BodyId b;
    /// BodySettings::userData of `a`.
    std::uint64_t userDataA = 0;
    /// BodySettings::userData of `b`.
    std::uint64_t userDataB = 0;
    /// The normal impulse of all the pair's contact points over the step (every sub-step),
    /// N s, >= 0: a box of mass m resting on the ground under g takes m g dt per step; one
    /// that lands at speed v and stops, about m v in that step.
    real normalImpulse = 0;
};

/// A joint broke: the mean force or torque it exerted during the step exceeded its
/// JointSettings::breakForce or breakTorque. It has been removed (its JointId is stale).
struct JointBreak {
    /// The joint, removed.
    JointId joint;
    /// Its mean force on body a during the step, world space, N.
    Vector3 force = Vector3::Zero();
    /// Its angular rows' mean torque on body a during the step, world space, N m.
    Vector3 torque = Vector3::Zero();
};

/// A body began or stopped overlapping a sensor (BodySettings::sensor).
struct SensorEvent {
    /// The sensor.
    BodyId sensor;
    /// The body it sees.
    BodyId body;
    /// BodySettings::userData of the sensor.
    std::uint64_t sensorUserData = 0;
    /// BodySettings::userData of the body.
    std::uint64_t bodyUserData = 0;
};

/// The events of one step, as returned by World::events().
///
/// Each list holds what happened in the last World::step() and in the World calls made
/// between the step before it and that step (a call that wakes a body reports the wake
/// in the events of the next step). Every event is reported exactly once. The lists are
/// in a deterministic order (pair slots for contacts, wake or sleep order for bodies);
/// their storage is reused from step to step, so reading them allocates nothing.
///
/// Pairs of bodies that are both asleep or static keep touching without events: a pile
/// that falls asleep reports no contact ends, and one that wakes reports no new begins
/// for the contacts it already had.
struct WorldEvents {
    /// Contacts that began.
    std::vector<ContactBegin> contactBegins;
    /// Contacts that ended.
    std::vector<ContactEnd> contactEnds;
    /// Bodies that began to overlap a sensor: found by the step's exact test (a sensor or a
    /// body added overlapping, asleep or not, is reported by the first step after it).
    /// Sorted by the sensor's BodyId::index, then the body's.
    std::vector<SensorEvent> sensorBegins;
    /// Bodies that stopped overlapping a sensor: they moved apart (found by the step, sorted
    /// as sensorBegins), or a call ended the overlap (World::removeBody of either, whose
    /// BodyId is then stale; a filter that now keeps them apart), reported in call order
    /// before the step's. An overlap that a call ended and the step found again is in
    /// both lists: read the ends first.
    std::vector<SensorEvent> sensorEnds;
    /// Dynamic bodies that fell asleep (an island at rest, or World::setAwake(id, false)).
    /// A body added asleep is not reported.
    std::vector<BodyId> fellAsleep;
    /// Dynamic bodies that woke up: touched by an awake body, joined to one by a spring,
    /// or woken by a World call (see World for the calls that wake).
    std::vector<BodyId> wokeUp;
    /// Joints that broke (and were removed) at the end of the step.
    std::vector<JointBreak> jointsBroken;
    /// Every pair the step solved (pairs with a simulated body and a contact not disabled,
    /// ContactListener), with its normal impulse; sorted by a's BodyId::index, then b's.
    std::vector<ContactImpulse> contactImpulses;

    /// Empties every list, keeping their storage.
    void clear() {
        contactBegins.clear();
        contactEnds.clear();
        sensorBegins.clear();
        sensorEnds.clear();
        fellAsleep.clear();
        wokeUp.clear();
        jointsBroken.clear();
        contactImpulses.clear();
    }
};

}  // namespace cyclone
