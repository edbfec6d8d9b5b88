// The World's joint calls: validation, adding and removing, reading, the motor's target.
#include <cmath>
#include <string>
#include <utility>

#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {
namespace {

const char *typeName(JointType type) {
    switch (type) {
        case JointType::Ball: return "Ball";
        case JointType::Hinge: return "Hinge";
        case JointType::Fixed: return "Fixed";
        case JointType::Slider: return "Slider";
        case JointType::Distance: return "Distance";
        case JointType::Mouse: return "Mouse";
    }
    return "?";
}

// A threshold: > 0, infinity allowed.
void requireThreshold(const char *function, const char *field, real value) {
    if (!(value > 0)) detail::refuse(function, field, "must be > 0 (infinity: never breaks), got " + detail::show(value));
}

// A spring's frequency (> 0) and damping ratio (>= 0), both finite.
void validateSpring(const char *function, const std::string &field, real frequency, real dampingRatio) {
    if (!(frequency > 0) || !std::isfinite(frequency))
        detail::refuse(function, field + ".frequency", "must be finite and > 0, got " + detail::show(frequency));
    if (!(dampingRatio >= 0) || !std::isfinite(dampingRatio))
        detail::refuse(function, field + ".dampingRatio", "must be finite and >= 0, got " + detail::show(dampingRatio));
}

// A servo: its target (a hinge's within [-pi, pi]), spring and largest force.
void validateServo(const char *function, JointType type, const JointServo &servo) {
    if (!std::isfinite(servo.target)) detail::refuse(function, "servo.target", "must be finite, got " + detail::show(servo.target));
    if (type == JointType::Hinge && (servo.target < -M_PI || servo.target > M_PI))
        detail::refuse(function, "servo.target", "a hinge's target must be within [-pi, pi], got " + detail::show(servo.target));
    validateSpring(function, "servo", servo.frequency, servo.dampingRatio);
    detail::requireNonNegative(function, "servo.maxForce", servo.maxForce);
}

// A ball joint's swing cone (half-angles in (0, pi], a normal perpendicular to the twist
// axis when they differ) and twist range (within [-pi, pi]); other types have neither.
void validateBallLimits(const char *function, const JointSettings &s, const std::string &type, const Vector3 &axis) {
    const bool ball = s.type == JointType::Ball;
    if (s.swingLimit && !ball) detail::refuse(function, "swingLimit", "only ball joints have it (" + type + " joint)");
    if (s.twistLimit && !ball) detail::refuse(function, "twistLimit", "only ball joints have it (" + type + " joint)");
    if (s.normal && !s.swingLimit)
        detail::refuse(function, "normal", "only ball joints with a swing limit have it (" + type + " joint)");
    if (s.swingLimit) {
        const JointSwingLimit &c = *s.swingLimit;
        for (const auto &[field, angle] : {std::pair("swingLimit.normalAngle", c.normalAngle),
                                           std::pair("swingLimit.binormalAngle", c.binormalAngle)}) {
            if (!(angle > 0 && angle <= M_PI)) detail::refuse(function, field, "must be in (0, pi], got " + detail::show(angle));
        }
        if (!s.normal && c.normalAngle != c.binormalAngle)
            detail::refuse(function, "normal", "is required when the swing limit's two half-angles differ");
        if (s.normal) {
            detail::requireFinite(function, "normal", *s.normal);
            const real length = s.normal->norm();
            if (!(length > 1e-12) || !std::isfinite(length))
                detail::refuse(function, "normal", "must not be zero, got " + detail::show(*s.normal));
            if (std::abs(s.normal->dot(axis)) > 1e-6 * length)
                detail::refuse(function, "normal", "must be perpendicular to axis, got " + detail::show(*s.normal) +
                                                       " with axis " + detail::show(axis));
        }
    }
    if (s.twistLimit) {
        const JointLimits &l = *s.twistLimit;
        if (!std::isfinite(l.lower)) detail::refuse(function, "twistLimit.lower", "must be finite, got " + detail::show(l.lower));
        if (!std::isfinite(l.upper)) detail::refuse(function, "twistLimit.upper", "must be finite, got " + detail::show(l.upper));
        if (!(l.lower <= l.upper && l.lower >= -M_PI && l.upper <= M_PI))
            detail::refuse(function, "twistLimit", "must satisfy -pi <= lower <= upper <= pi, got [" + detail::show(l.lower) +
                                                       ", " + detail::show(l.upper) + "]");
    }
}

// A mouse joint's or a distance joint's second anchor, a mouse joint's one dynamic body,
// and its pull; other types have neither anchorB nor pull. `a` is the record of body a.
void validatePull(const char *function, const JointSettings &s, const std::string &type, const detail::BodyRecord &a) {
    const bool distance = s.type == JointType::Distance;
    const bool mouse = s.type == JointType::Mouse;
    if (s.anchorB) {
        if (!distance && !mouse)
            detail::refuse(function, "anchorB",
                           "only distance joints (the second anchor) and mouse joints (the target) have it (" + type + " joint)");
        detail::requirePlace(function, "anchorB", *s.anchorB);
    }
    if (mouse) {
        if (s.b) detail::refuse(function, "b", "must be empty: a mouse joint pulls a towards a world point");
        if (a.immovable) detail::refuse(function, "a", "must be dynamic: a mouse joint pulls it");
    }
    if (s.pull) {
        if (!mouse) detail::refuse(function, "pull", "only mouse joints have it (" + type + " joint)");
        const JointPull &p = *s.pull;
        if (!(p.frequency > 0) || !std::isfinite(p.frequency))
            detail::refuse(function, "pull.frequency", "must be finite and > 0, got " + detail::show(p.frequency));
        if (!(p.dampingRatio >= 0) || !std::isfinite(p.dampingRatio))
            detail::refuse(function, "pull.dampingRatio", "must be finite and >= 0, got " + detail::show(p.dampingRatio));
        if (!(p.maxForce > 0))
            detail::refuse(function, "pull.maxForce", "must be > 0 (infinity: no limit), got " + detail::show(p.maxForce));
    }
}

// The joint's axis normalised, when it has one (`used`: a hinge's, a slider's, a limited
// ball joint's); else as given.
Vector3 checkedAxis(const char *function, const Vector3 &axis, bool used) {
    if (!used) return axis;
    detail::requireFinite(function, "axis", axis);
    const real length = axis.norm();
    if (!(length > 1e-12) || !std::isfinite(length))
        detail::refuse(function, "axis", "must not be zero, got " + detail::show(axis));
    return axis / length;
}

// A hinge's or a slider's limits, motor and servo (one of the two); other types have none.
void validateAxialDrive(const char *function, const JointSettings &s, const std::string &type) {
    const bool axial = s.type == JointType::Hinge || s.type == JointType::Slider;
    if (s.limits) {
        if (!axial) detail::refuse(function, "limits", "only hinge and slider joints have limits (" + type + " joint)");
        const JointLimits &l = *s.limits;
        if (!std::isfinite(l.lower)) detail::refuse(function, "limits.lower", "must be finite, got " + detail::show(l.lower));
        if (!std::isfinite(l.upper)) detail::refuse(function, "limits.upper", "must be finite, got " + detail::show(l.upper));
        if (!(l.lower <= l.upper))
            detail::refuse(function, "limits", "lower must be <= upper, got [" + detail::show(l.lower) + ", " +
                                                   detail::show(l.upper) + "]");
        if (s.type == JointType::Hinge && (l.lower < -M_PI || l.upper > M_PI))
            detail::refuse(function, "limits", "a hinge's limits must be within [-pi, pi], got [" +
                                                   detail::show(l.lower) + ", " + detail::show(l.upper) + "]");
    }
    if (s.motor) {
        if (!axial) detail::refuse(function, "motor", "only hinge and slider joints have motors (" + type + " joint)");
        if (!std::isfinite(s.motor->speed))
            detail::refuse(function, "motor.speed", "must be finite, got " + detail::show(s.motor->speed));
        detail::requireNonNegative(function, "motor.maxForce", s.motor->maxForce);
    }
    if (s.servo) {
        if (!axial) detail::refuse(function, "servo", "only hinge and slider joints have servos (" + type + " joint)");
        if (s.motor) detail::refuse(function, "servo", "a joint has a motor (a speed) or a servo (a target), not both");
        validateServo(function, s.type, *s.servo);
    }
}

// Friction (ball joints and hinges) and the spring of soft limits (joints with limits).
void validateFrictionAndLimitSpring(const char *function, const JointSettings &s, const std::string &type) {
    const bool axial = s.type == JointType::Hinge || s.type == JointType::Slider;
    const bool limitedBall = s.type == JointType::Ball && (s.swingLimit || s.twistLimit);
    if (s.friction != 0) {
        if (s.type != JointType::Ball && s.type != JointType::Hinge)
            detail::refuse(function, "friction", "only ball joints and hinges have it (" + type + " joint)");
        detail::requireNonNegative(function, "friction", s.friction);
    }
    if (s.limitSpring) {
        if (!axial && !limitedBall)
            detail::refuse(function, "limitSpring", "only hinges, sliders and ball joints with a swing or twist limit have it (" + type + " joint)");
        if (!s.limits && !limitedBall) detail::refuse(function, "limitSpring", "the joint has no limits to make soft");
        validateSpring(function, "limitSpring", s.limitSpring->frequency, s.limitSpring->dampingRatio);
    }
}

// A distance joint's range and spring; other types have neither.
void validateDistance(const char *function, const JointSettings &s, const std::string &type) {
    const bool distance = s.type == JointType::Distance;
    if ((s.minDistance || s.maxDistance || s.stiffness != 0 || s.damping != 0) && !distance) {
        const char *field = s.minDistance ? "minDistance" : s.maxDistance ? "maxDistance" : s.stiffness != 0 ? "stiffness" : "damping";
        detail::refuse(function, field, std::string("only distance joints have it (") + type + " joint)");
    }
    if (!distance) return;
    const real at = (s.anchor - s.anchorB.value_or(s.anchor)).norm();
    if (s.minDistance) detail::requireNonNegative(function, "minDistance", *s.minDistance);
    if (s.maxDistance) detail::requireNonNegative(function, "maxDistance", *s.maxDistance);
    const real lo = s.minDistance.value_or(at);
    const real hi = s.maxDistance.value_or(at);
    if (!(lo <= hi))
        detail::refuse(function, "maxDistance", "must be >= minDistance, got min " + detail::show(lo) + ", max " +
                                                    detail::show(hi));
    detail::requireNonNegative(function, "stiffness", s.stiffness);
    detail::requireNonNegative(function, "damping", s.damping);
}

// Everything addJoint refuses, before anything changes; returns the axis normalised.
Vector3 validate(const detail::WorldState &w, const JointSettings &s) {
    static const char *function = "World::addJoint";
    if (s.type != JointType::Ball && s.type != JointType::Hinge && s.type != JointType::Fixed &&
        s.type != JointType::Slider && s.type != JointType::Distance && s.type != JointType::Mouse)
        detail::refuse(function, "type", "is not a JointType, got " + std::to_string(static_cast<int>(s.type)));
    const std::string type = typeName(s.type);
    const detail::BodyRecord &a = w.bodies.record(s.a, function);
    const detail::BodyRecord *b = s.b ? &w.bodies.record(*s.b, function) : nullptr;
    if (s.b && *s.b == s.a) detail::refuse(function, "b", "must differ from a");
    if (a.immovable && (!b || b->immovable))
        detail::refuse(function, "a", "one of the joined bodies must be dynamic (a static or kinematic body cannot move)");
    detail::requirePlace(function, "anchor", s.anchor);
    validatePull(function, s, type, a);
    const bool axial = s.type == JointType::Hinge || s.type == JointType::Slider;
    const bool limitedBall = s.type == JointType::Ball && (s.swingLimit || s.twistLimit);
    const Vector3 axis = checkedAxis(function, s.axis, axial || limitedBall);
    validateAxialDrive(function, s, type);
    validateBallLimits(function, s, type, axis);
    validateFrictionAndLimitSpring(function, s, type);
    validateDistance(function, s, type);
    requireThreshold(function, "breakForce", s.breakForce);
    requireThreshold(function, "breakTorque", s.breakTorque);
    return axis;
}

// The joint `id` names; refused with `function`'s name when it names none.
detail::JointRecord &jointRecord(detail::WorldState &w, JointId id, const char *function) {
    if (!w.joints.contains(id)) detail::refuse(function, "id", "does not name a joint of this world");
    return w.joints.records[id.index];
}

void wakeJoined(detail::WorldState &w, BodyId a, const std::optional<BodyId> &b) {
    if (w.bodies.contains(a) && !w.bodies[a.index].immovable) w.wake(a.index);
    if (b && w.bodies.contains(*b) && !w.bodies[b->index].immovable) w.wake(b->index);
}

}  // namespace

JointId World::addJoint(const JointSettings &settings) {
    Impl &w = *impl_;
    JointSettings s = settings;
    s.axis = validate(w, settings);
    const JointId id = w.joints.add(w.bodies, s);
    if (s.b && !s.collideConnected) {
        // The pair's contacts end now, as a collision filter's do.
        detail::BodyRecord &a = w.bodies[s.a.index];
        for (std::size_t k = a.pairs.size(); k-- > 0;) {
            const std::uint32_t p = a.pairs[k];
            const detail::PairState &pair = w.contacts.pairs[p];
            if ((pair.a == s.a.index && pair.b == s.b->index) || (pair.b == s.a.index && pair.a == s.b->index))
                w.contacts.removePair(w.bodies, p);
        }
    }
    wakeJoined(w, s.a, s.b);
    return id;
}

void World::removeJoint(JointId id) {
    Impl &w = *impl_;
    const detail::JointRecord &j = jointRecord(w, id, "World::removeJoint");
    const BodyId a = j.settings.a;
    const std::optional<BodyId> b = j.settings.b;
    w.joints.remove(id.index);
    wakeJoined(w, a, b);
}

bool World::contains(JointId id) const { return impl_->joints.contains(id); }

JointState World::jointState(JointId id) const {
    const detail::JointRecord &j = jointRecord(*impl_, id, "World::jointState");
    JointState state;
    state.force = j.force;
    state.torque = j.torque;
    impl_->joints.measure(impl_->bodies, j, &state.error, &state.position);
    return state;
}

const JointSettings &World::jointSettings(JointId id) const {
    return jointRecord(*impl_, id, "World::jointSettings").settings;
}

void World::setMotorSpeed(JointId id, real speed) {
    static const char *function = "World::setMotorSpeed";
    Impl &w = *impl_;
    detail::JointRecord &j = jointRecord(w, id, function);
    if (!j.settings.motor) detail::refuse(function, "id", "names a joint without a motor");
    if (!std::isfinite(speed)) detail::refuse(function, "speed", "must be finite, got " + detail::show(speed));
    j.settings.motor->speed = speed;
    wakeJoined(w, j.settings.a, j.settings.b);
}

void World::setServoTarget(JointId id, real target) {
    static const char *function = "World::setServoTarget";
    Impl &w = *impl_;
    detail::JointRecord &j = jointRecord(w, id, function);
    if (!j.settings.servo) detail::refuse(function, "id", "names a joint without a servo");
    if (!std::isfinite(target)) detail::refuse(function, "target", "must be finite, got " + detail::show(target));
    if (j.settings.type == JointType::Hinge && (target < -M_PI || target > M_PI))
        detail::refuse(function, "target", "a hinge's target must be within [-pi, pi], got " + detail::show(target));
    j.settings.servo->target = target;
    wakeJoined(w, j.settings.a, j.settings.b);
}

void World::setMouseTarget(JointId id, const Vector3 &target) {
    static const char *function = "World::setMouseTarget";
    Impl &w = *impl_;
    detail::JointRecord &j = jointRecord(w, id, function);
    if (j.settings.type != JointType::Mouse) detail::refuse(function, "id", "names a joint that is not a mouse joint");
    detail::requirePlace(function, "target", target);
    if (j.localB == target) return;
    j.localB = target;
    j.settings.anchorB = target;
    wakeJoined(w, j.settings.a, j.settings.b);
}

}  // namespace cyclone
