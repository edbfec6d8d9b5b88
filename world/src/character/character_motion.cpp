// Moving a character over one step, after the bodies moved: carried by its ground, walked
// and slid (collide and slide: cast, stop short, slide along what stopped it, a few
// rounds), stepped up, kept to the ground. Everything is done by casting its capsule
// (queries/queries.h, World::shapeCast's cast) from where it stands, so it never overlaps
// what it meets and keeps kSkin from it.
#include <algorithm>
#include <cmath>

#include "character/character_record.h"
#include "queries/queries.h"
#include "world/body_store.h"
#include "world/body_transitions.h"

namespace cyclone::detail {
namespace {

constexpr real kSkin = 0.001;       // gap kept from what the capsule touches, m
constexpr int kSlides = 4;          // cast-and-slide rounds per move
constexpr real kShortest = 1e-9;    // moves shorter than this are not cast, m
constexpr real kEdgeProbe = 0.01;   // how far beyond an edge the ground under it is looked for, m
constexpr real kEdgeLean = 0.1;     // an edge touched with a normal below this along up (84 deg from it) is a side
constexpr real kPushFriction = 1;   // a pushed character's slide slows at this times |gravity|

class CharacterMove {
public:
    CharacterMove(const Vector3 &gravity, BodyStore &bodies, const QueryScene &queries,
                  BodyTransitions transitions, CharacterRecord &c, real dt)
        : bodies_(bodies), queries_(queries), transitions_(transitions), c_(c), dt_(dt), gravity_(gravity),
          up_(characterUp(gravity)), upright_(uprightFor(up_)), filter_(characterFilter(bodies, c)),
          cosMaxSlope_(std::cos(c.settings.maxSlope)), weight_(c.settings.mass * gravity.norm()) {}

    void run() {
        const Vector3 start = c_.feet;
        const bool wasOnGround = c_.onGround;
        carry();
        const bool jumps = wasOnGround && c_.desired.dot(up_) > 0;
        walk(wasOnGround && !jumps, jumps);
        findGround(wasOnGround && !jumps);
        slowPush();
        placeCapsule();
        c_.velocity = (c_.feet - start) / dt_;
    }

private:
    bool walkable(const Vector3 &normal) const { return normal.dot(up_) >= cosMaxSlope_; }
    Vector3 across(const Vector3 &v) const { return v - up_ * v.dot(up_); }

    // The motion across up, turned to run along ground of this normal (same reach across).
    Vector3 along(const Vector3 &motion, const Vector3 &normal) const {
        const Vector3 flat = across(motion);
        return flat - up_ * (normal.dot(flat) / normal.dot(up_));
    }

    // Casts the capsule standing at `feet` along `motion` and moves `feet` up to kSkin short
    // of what it meets (measured along the normal); returns what it met.
    std::optional<ShapeCastHit> moveUntilHit(Vector3 &feet, const Vector3 &motion) const {
        const real length = motion.norm();
        if (!(length > kShortest)) return std::nullopt;
        auto hit = shapeCast(queries_, c_.capsule, capsuleCentre(c_, up_, feet), upright_, motion, filter_);
        if (!hit) {
            feet += motion;
            return hit;
        }
        // A grazing approach would back off far along the motion for a small gap: at most 20 skins.
        const real approach = std::max(-motion.dot(hit->normal) / length, real(0.05));
        feet += motion * (std::max(real(0), hit->distance - kSkin / approach) / length);
        return hit;
    }

    // Follows the ground body's move over the step: up and down at once (the ground moved
    // as much), across by a cast (so that walls stop it).
    void carry() {
        if (!c_.onGround || !c_.groundBody || !bodies_.contains(*c_.groundBody)) return;
        const BodyRecord &ground = bodies_[c_.groundBody->index];
        if (ground.immovable && !ground.kinematic) return;
        const Vector3 shift = ground.body.getTransform() * (c_.groundStart.inverse() * c_.feet) - c_.feet;
        c_.feet += up_ * shift.dot(up_);
        moveUntilHit(c_.feet, across(shift));
    }

    // Walks along the ground, or flies under gravity (exact for a constant acceleration).
    void walk(bool grounded, bool jumps) {
        walkVelocity_ = across(c_.desired) + c_.push;
        if (grounded) {
            c_.flight.setZero();
            slide(along(walkVelocity_ * dt_, c_.groundNormal), true);
            return;
        }
        const Vector3 before = jumps ? Vector3(up_ * c_.desired.dot(up_)) : c_.flight;
        c_.flight = before + gravity_ * dt_;
        slide(walkVelocity_ * dt_ + (before + c_.flight) / 2 * dt_, false);
    }

    void slide(Vector3 motion, bool grounded) {
        for (int round = 0; round < kSlides && motion.norm() > kShortest; ++round) {
            const auto hit = moveUntilHit(c_.feet, motion);
            if (!hit) return;
            push(*hit);
            Vector3 rest = motion * (1 - hit->fraction);
            const Vector3 &normal = hit->normal;
            stopFlight(normal);
            if (walkable(normal)) {
                rest = along(rest, normal);  // a slope, or the ground it lands on
            } else {
                if (grounded && climb(rest)) return;
                // On the ground a steep slope is a wall: it slides along, not up.
                Vector3 wall = grounded ? across(normal) : normal;
                wall = wall.norm() > kShortest ? Vector3(wall.normalized()) : normal;
                rest -= std::min(real(0), rest.dot(wall)) * wall;
            }
            motion = rest;
        }
    }

    // The flight loses its part into a surface met (a landing, a ceiling, a steep slope
    // it then slides down).
    void stopFlight(const Vector3 &normal) {
        const real into = c_.flight.dot(normal);
        if (into < 0) c_.flight -= into * normal;
    }

    // Up by the step height, across, and down onto walkable ground: false when blocked.
    bool climb(const Vector3 &rest) {
        const Vector3 ahead = across(rest);
        const real reach = ahead.norm();
        if (!(c_.settings.stepHeight > 0) || reach < kShortest) return false;
        Vector3 feet = c_.feet;
        moveUntilHit(feet, up_ * c_.settings.stepHeight);
        const real lifted = (feet - c_.feet).dot(up_);
        if (lifted < kSkin) return false;
        const Vector3 raised = feet;
        moveUntilHit(feet, ahead);
        if ((feet - raised).norm() < reach / 2) return false;  // a wall higher than a step
        const auto down = moveUntilHit(feet, -up_ * lifted);
        Vector3 normal;
        if (!down || !supports(*down, feet, normal)) return false;
        // The height of what it lands on, not of its feet, which a round bottom resting
        // on a step's edge keeps lower.
        if ((down->point - c_.feet).dot(up_) > c_.settings.stepHeight + kSkin) return false;
        c_.feet = feet;
        return true;
    }

    // Whether what the capsule touches at `feet` holds it up: walkable ground, or the edge
    // of walkable ground (a step's nose), whose surface beyond the edge decides.
    bool supports(const ShapeCastHit &hit, const Vector3 &feet, Vector3 &normal) const {
        normal = hit.normal;
        if (walkable(hit.normal)) return true;
        if (hit.normal.dot(up_) <= kEdgeLean) return false;
        Vector3 out = across(hit.point - feet);
        if (!(out.norm() > kShortest)) return false;
        out.normalize();
        const auto ground = rayCast(queries_, hit.point + (out + up_) * kEdgeProbe, -up_, 3 * kEdgeProbe, filter_);
        if (!ground || !walkable(ground->normal)) return false;
        normal = ground->normal;
        return true;
    }

    // On the ground: down to it (by up to the step height when it stood on ground and
    // does not jump, so that it walks down steps and slopes), or airborne.
    void findGround(bool stick) {
        Vector3 feet = c_.feet;
        const auto hit = moveUntilHit(feet, -up_ * ((stick ? c_.settings.stepHeight : 0) + 2 * kSkin));
        Vector3 normal;
        if (c_.flight.dot(up_) <= 0 && hit && supports(*hit, feet, normal)) {
            c_.feet = feet;
            c_.onGround = true;
            c_.groundBody = hit->body;
            c_.groundNormal = normal;
            c_.flight.setZero();
            press(hit->body, hit->point);
            return;
        }
        c_.onGround = false;
        c_.groundBody.reset();
        c_.groundNormal = up_;
    }

    // Pushes a dynamic body it walks into towards its walking velocity, with at most its
    // weight, at its centre of mass (where along a face it touches is arbitrary; once per
    // body and step).
    void push(const ShapeCastHit &hit) {
        BodyRecord &b = bodies_[hit.body.index];
        if (b.immovable || std::find(pushed_.begin(), pushed_.end(), hit.body.index) != pushed_.end()) return;
        pushed_.push_back(hit.body.index);
        const Vector3 into = -hit.normal;
        const real approach = walkVelocity_.dot(into) - b.body.getVelocity().dot(into);
        if (!(approach > 0)) return;
        applyImpulse(hit.body.index, into * std::min(approach * b.body.getMass(), weight_ * dt_));
    }

    // Its weight on a dynamic body it stands on.
    void press(BodyId ground, const Vector3 &point) {
        if (bodies_[ground.index].immovable) return;
        RigidBody &body = bodies_[ground.index].body;
        transitions_.wake(ground.index);
        const Vector3 impulse = -up_ * (weight_ * dt_);
        body.addVelocity(impulse * body.getInverseMass());
        body.addRotation(body.getInverseInertiaTensorWorld() * (point - body.getPosition()).cross(impulse));
    }

    void applyImpulse(std::uint32_t index, const Vector3 &impulse) {
        transitions_.wake(index);
        bodies_[index].body.addVelocity(impulse * bodies_[index].body.getInverseMass());
    }

    // A push given by a body that ran into it slows on the ground as by friction.
    void slowPush() {
        const real speed = c_.push.norm();
        if (!c_.onGround || !(speed > 0)) return;
        const real loss = kPushFriction * gravity_.norm() * dt_;
        c_.push *= speed > loss ? (speed - loss) / speed : 0;
    }

    void placeCapsule() {
        BodyRecord &r = bodies_[c_.body.index];
        const Vector3 centre = capsuleCentre(c_, up_, c_.feet);
        if (r.body.getPosition() == centre && r.body.getOrientation().coeffs() == upright_.coeffs()) return;
        r.body.setPosition(centre);
        r.body.setOrientation(upright_);
        transitions_.refresh(c_.body.index);
    }

    BodyStore &bodies_;
    const QueryScene &queries_;  ///< The same bodies, and the broadphase trees, for the casts.
    const BodyTransitions transitions_;
    CharacterRecord &c_;
    const real dt_;
    const Vector3 gravity_;
    const Vector3 up_;
    const Quaternion upright_;
    const QueryFilter filter_;
    const real cosMaxSlope_;
    const real weight_;                ///< mass |gravity|, N: the most it pushes with
    Vector3 walkVelocity_ = Vector3::Zero();
    std::vector<std::uint32_t> pushed_;  ///< Bodies pushed this step.
};

}  // namespace

void Characters::update(const Vector3 &gravity, BodyStore &bodies, const QueryScene &queries,
                        BodyTransitions transitions, real dt) {
    for (CharacterRecord &c : records)
        if (c.alive) CharacterMove(gravity, bodies, queries, transitions, c, dt).run();
}

}  // namespace cyclone::detail
