/// \file
/// cyclone::World: rigid bodies with collision shapes, FCL contact detection, an impulse
/// solver, island sleep; events, queries and debug drawing.
///
/// Ownership: the World owns its bodies; a BodyId is a handle that stays valid until the
/// body is removed. Read a body through body(id); change it through the World's calls,
/// so that waking rules hold.
///
/// What wakes a body: every call that moves a body (setPosition, setOrientation), sets
/// its velocity (setVelocity, setRotation) or applies a force, torque or impulse
/// (applyImpulse, addForce, addForceAtPoint, addTorque) wakes it and its sleeping island;
/// so do setAwake(id, true), setCanSleep(id, false), setSettings (every body), adding a
/// spring or a joint (its bodies), setting a joint's motor speed or a new mouse target
/// (its bodies), and removing a spring, a joint or a body (the bodies it joined or touched);
/// setCollisionFilter and setPairCollision wake as they say. Sensors wake nothing.
/// During a step, a sleeping body that an awake or moving kinematic body's contact
/// (touching or speculative) reaches, or that a spring or a joint joins to an awake
/// body, wakes with its island and is solved in that same step with its real mass: a
/// hit on a sleeping body moves it as a hit on an awake one does. A joint that breaks
/// wakes its bodies. Reading (body(), events(),
/// rayCast(), overlap(), debugDraw(), ...) and setMaterial() wake nothing.
///
/// Errors: bad input throws cyclone::InvalidArgument naming the function, the field and
/// the value, and changes nothing.
///
/// Isolated bodies: a body whose state becomes non-finite (or that the solver cannot
/// move) during a step is isolated: out of collision, the solve and queries for good
/// (StepStats::isolatedBodies). It can still be read and removed; every call that would
/// change it (setPosition, setOrientation, setVelocity, setRotation, applyImpulse,
/// addForce..., setAwake, setCanSleep) throws InvalidArgument. To bring it back, remove
/// it and add a new body with a reset state.
///
/// Threads: a World is not thread-safe; its const calls may run concurrently with each
/// other, but not with a non-const call such as step().
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cyclone/body.h"
#include "cyclone/world/character.h"
#include "cyclone/world/contact_listener.h"
#include "cyclone/world/debug_draw.h"
#include "cyclone/world/error.h"
#include "cyclone/world/events.h"
#include "cyclone/world/joints.h"
#include "cyclone/world/queries.h"
#include "cyclone/world/settings.h"
#include "cyclone/world/shape.h"
#include "cyclone/world/stats.h"

namespace cyclone {

/// A physics world: bodies, springs, and the step that moves them. See the file
/// documentation of world.h for ownership, the wake rules and errors.
class World {
public:
    /// A world with the given settings; throws InvalidArgument on bad settings.
    explicit World(const WorldSettings &settings = WorldSettings());
    /// Destroys the world and its bodies.
    ~World();
    World(const World &) = delete;
    World &operator=(const World &) = delete;
    /// Moves the world; the moved-from World may only be destroyed or assigned to.
    World(World &&) noexcept;
    /// Moves the world; the moved-from World may only be destroyed or assigned to.
    World &operator=(World &&) noexcept;

    /// The settings in force.
    const WorldSettings &settings() const;
    /// Replaces the settings (validated; on refusal nothing changes). Wakes every body.
    void setSettings(const WorldSettings &settings);

    // --- Bodies -------------------------------------------------------------------------

    /// Adds a body and returns its handle; throws InvalidArgument (nothing added) on a bad
    /// shape, mass, inertia or number, a plane or mesh on a dynamic or kinematic body
    /// (sensor or not),
    /// a shape any point of which (a compound's child
    /// too) would lie beyond 1e12 m of the origin, or a duplicate non-empty name. A kinematic body
    /// added with a velocity or rotation moves from the first step. A dynamic body added awake (the default) is simulated from the
    /// next step; one added with `awake = false` sleeps until something wakes it.
    BodyId addBody(const BodySettings &settings);
    /// Removes a body; the bodies touching it or joined to it by a spring or a joint wake,
    /// and so do the others of its sleeping island. Its springs, joints and
    /// setPairCollision rules are removed, and its overlaps with sensors end (reported with
    /// the next step's events). Throws InvalidArgument on a stale handle or a character's
    /// capsule (removeCharacter removes it).
    void removeBody(BodyId id);
    /// True while `id` names a body of this world.
    bool contains(BodyId id) const;
    /// Every body, in the order they were added.
    std::vector<BodyId> bodies() const;
    /// Every body, in the order they were added, written into `out` (cleared first): no
    /// allocation once `out` has the capacity.
    void bodies(std::vector<BodyId> &out) const;
    /// Number of bodies.
    std::size_t bodyCount() const;
    /// The body with this name, if any.
    std::optional<BodyId> findBody(const std::string &name) const;

    /// Read-only access to a body's dynamic state (SI units; see RigidBody). Throws
    /// InvalidArgument on a stale handle.
    const RigidBody &body(BodyId id) const;
    /// The body's name (may be empty).
    const std::string &name(BodyId id) const;
    /// The body's shape, in its own frame.
    const Shape &shape(BodyId id) const;
    /// World-space origin of the body's shape frame, m: for a compound, the frame its
    /// children are placed in (where BodySettings::position put it); for any other shape,
    /// the centre of mass, body(id).getPosition(). The frame turns with the body
    /// (body(id).getOrientation()).
    Vector3 framePosition(BodyId id) const;
    /// The body's shape frame as a transform: framePosition() and the body's orientation.
    Matrix4 framePose(BodyId id) const;
    /// The centre of mass in the body's shape frame, m: zero except for a compound.
    Vector3 localCentreOfMass(BodyId id) const;
    /// How the body moves.
    Motion motion(BodyId id) const;
    /// The body's material.
    const Material &material(BodyId id) const;

    // --- Changing bodies: each wakes the body and its island ----------------------------

    /// Moves the body's centre of mass (for a compound, not its frame: see
    /// setFramePosition()) to `position` (m, finite, each coordinate within
    /// 1e12 m of the origin); a plane is refused. Wakes the body and its island; a moved
    /// static body wakes the bodies touching it.
    void setPosition(BodyId id, const Vector3 &position);
    /// Moves the body so that the origin of its shape frame (framePosition()) lies at
    /// `position` (m, finite, within 1e12 m of the origin): setPosition() for a compound's
    /// frame. Wakes as setPosition() does.
    void setFramePosition(BodyId id, const Vector3 &position);
    /// Turns the body about its centre of mass to `orientation` (finite; normalised;
    /// (0,0,0,0) means identity); a plane is refused. Wakes as setPosition() does.
    void setOrientation(BodyId id, const Quaternion &orientation);
    /// Sets the linear velocity (m/s, finite) of a dynamic body, which wakes it and its
    /// island, or of a kinematic body, which keeps it until it is set again; a kinematic
    /// body set in motion wakes the bodies touching it. A static body is refused.
    void setVelocity(BodyId id, const Vector3 &velocity);
    /// Sets the angular velocity (rad/s, world axes, finite) of a dynamic or kinematic
    /// body, waking as setVelocity() does.
    void setRotation(BodyId id, const Vector3 &rotation);
    /// Sets a kinematic body's velocity and rotation so that it reaches `targetPosition`
    /// (m, finite) and `targetOrientation` (finite; normalised; (0,0,0,0) means identity)
    /// after one step of `dt` seconds (finite, > 0; the dt the next step() is given),
    /// turning the shorter way; it keeps them afterwards, so call it each step, or set
    /// zero velocities to stop. Wakes as setVelocity() does. A static or dynamic body is
    /// refused.
    void moveKinematic(BodyId id, const Vector3 &targetPosition, const Quaternion &targetOrientation, real dt);
    /// Applies an impulse (N s, finite) at the centre of mass of a dynamic body: its
    /// velocity changes by impulse / mass at once. Wakes it and its island.
    void applyImpulse(BodyId id, const Vector3 &impulse);
    /// Applies an impulse (N s, finite) at a world-space point (m, finite) of a dynamic
    /// body, changing its velocity and rotation at once. Wakes it and its island.
    void applyImpulse(BodyId id, const Vector3 &impulse, const Vector3 &point);
    /// Adds a force (N, finite) at the centre of mass of a dynamic body for the next step
    /// only. Wakes it and its island.
    void addForce(BodyId id, const Vector3 &force);
    /// Adds a force (N, finite) at a world-space point (m, finite) of a dynamic body for
    /// the next step only. Wakes it and its island.
    void addForceAtPoint(BodyId id, const Vector3 &force, const Vector3 &point);
    /// Adds a torque (N m, world axes, finite) to a dynamic body for the next step only.
    /// Wakes it and its island.
    void addTorque(BodyId id, const Vector3 &torque);
    /// Wakes the dynamic body and its island (true), or puts the body's island to sleep
    /// at once (false; velocities zeroed).
    void setAwake(BodyId id, bool awake);
    /// Allows or forbids sleep for a dynamic body; forbidding wakes it and its island.
    void setCanSleep(BodyId id, bool canSleep);
    /// Puts the body on collision layer `layer` ([0, 31]) and makes it collide with the
    /// layers of `collidesWith` (bit k for layer k); two bodies touch only when each one's
    /// mask holds the other's layer (a sensor and the body it sees too). Contacts and
    /// sensor overlaps the new filter forbids end at once (reported with the next step's
    /// events); the body and what it touched wake.
    void setCollisionFilter(BodyId id, int layer, std::uint32_t collidesWith);
    /// Whether bodies `a` and `b` (two different bodies) may touch, or the sensor among them
    /// see the other, as far as the pair is concerned: `collide` false keeps them apart
    /// whatever their layers (a projectile and its shooter, a ragdoll's limbs), true (the
    /// default of every pair) leaves it to the layers. False ends their contact or overlap
    /// at once (reported with the next step's events) and wakes a dynamic body that
    /// touched the other; true wakes the dynamic ones so that they meet again. The rule
    /// lasts until it is changed or one of the bodies is removed. Throws InvalidArgument
    /// on a stale handle or a == b.
    void setPairCollision(BodyId a, BodyId b, bool collide);
    /// The pair's rule set by setPairCollision (true unless set false).
    bool pairCollision(BodyId a, BodyId b) const;
    /// Whether the body is a sensor (BodySettings::sensor).
    bool isSensor(BodyId id) const;
    /// Replaces the body's material (friction >= 0, restitution in [0, 1]). Wakes
    /// nothing: it acts at the body's next contact.
    void setMaterial(BodyId id, const Material &material);

    /// Sets the factor of the world's gravity that acts on a dynamic body (finite; 0
    /// floats, -1 falls up). Wakes it and its island. A static or kinematic body is refused.
    void setGravityScale(BodyId id, real scale);
    /// The body's gravity scale (BodySettings::gravityScale).
    real gravityScale(BodyId id) const;
    /// Locks a dynamic body's motion along and about the given world axes (see
    /// LockedAxes), from its current pose; the locked components of its velocity are
    /// dropped at once. Wakes it and its island. A static or kinematic body is refused.
    void setLockedAxes(BodyId id, const LockedAxes &axes);
    /// The axes locked on the body (BodySettings::lockedAxes).
    const LockedAxes &lockedAxes(BodyId id) const;
    /// Replaces the body's user data (BodySettings::userData). Wakes nothing.
    void setUserData(BodyId id, std::uint64_t userData);
    /// The body's user data (BodySettings::userData).
    std::uint64_t userData(BodyId id) const;

    // --- Springs ------------------------------------------------------------------------

    /// Adds a spring (see SpringSettings for units and ranges); it wakes the dynamic
    /// bodies it joins, and from then on an awake end wakes the other.
    SpringId addSpring(const SpringSettings &settings);
    /// Removes a spring; it wakes the dynamic bodies it joined. Throws InvalidArgument on
    /// a stale handle.
    void removeSpring(SpringId id);

    // --- Joints -------------------------------------------------------------------------

    /// Adds a joint (see JointSettings for units, defaults and ranges) at the bodies'
    /// current poses; it wakes the dynamic bodies it joins, and from then on an awake end
    /// wakes the other, and the two sleep together. Unless collideConnected, the two
    /// bodies stop colliding with each other (a contact they have ends at once). Throws
    /// InvalidArgument (nothing added) on a stale body, b equal to a, no dynamic body, or
    /// a field out of its range.
    JointId addJoint(const JointSettings &settings);
    /// Removes a joint; it wakes the dynamic bodies it joined. Throws InvalidArgument on a
    /// stale handle.
    void removeJoint(JointId id);
    /// True while `id` names a joint of this world (removing a body removes its joints;
    /// a broken joint is removed).
    bool contains(JointId id) const;
    /// The joint's mean force and torque in the last step it was solved in, and its
    /// error and angle or offset at the bodies' current poses. Throws InvalidArgument on a
    /// stale handle.
    JointState jointState(JointId id) const;
    /// The joint's settings as given (the axis normalised). Throws InvalidArgument on a
    /// stale handle.
    const JointSettings &jointSettings(JointId id) const;
    /// Sets the target speed of a hinge's or slider's motor (rad/s or m/s, finite); it
    /// wakes the joint's dynamic bodies. Throws InvalidArgument on a stale handle, a joint
    /// without a motor, or a non-finite speed.
    void setMotorSpeed(JointId id, real speed);
    /// Sets a servo's target (angle, rad, within [-pi, pi] for a hinge; offset, m, for a
    /// slider; finite) and wakes the joint's dynamic bodies. Throws InvalidArgument on a
    /// stale handle, a joint without a servo, or a target out of range.
    void setServoTarget(JointId id, real target);
    /// Moves a mouse joint's target (world space, m, finite, within kMaxCoordinate = 1e12 m of the origin);
    /// a new target wakes the body it pulls. Throws InvalidArgument on a stale handle, a
    /// joint that is not a mouse joint, or a target out of range.
    void setMouseTarget(JointId id, const Vector3 &target);

    // --- Characters (cyclone/world/character.h) -------------------------------------------

    /// Adds a character standing with its feet at settings.position, and its capsule as a
    /// kinematic body (CharacterState::body); it moves from the next step. Throws
    /// InvalidArgument (nothing added) on a field out of its range.
    CharacterId addCharacter(const CharacterSettings &settings);
    /// Removes a character and its capsule. Throws InvalidArgument on a stale handle.
    void removeCharacter(CharacterId id);
    /// The velocity the character walks at from the next step on, m/s, finite: its part
    /// across the up direction is the walk; an upward part while it is on the ground is a
    /// jump at that speed (ignored while airborne). Throws InvalidArgument on a stale
    /// handle or a non-finite velocity.
    void setCharacterVelocity(CharacterId id, const Vector3 &desired);
    /// The character's state after the last step. Throws InvalidArgument on a stale handle.
    CharacterState character(CharacterId id) const;

    // --- Stepping -----------------------------------------------------------------------

    /// Advances the world by dt seconds (in [kMinStep, kMaxStep] = [1e-6, 1]; 1/60 is typical). Use a fixed dt
    /// (FixedStepper does it for a game loop): results depend on it, and a fixed one
    /// keeps runs reproducible.
    void step(real dt);
    /// Counters and per-stage timings of the last step.
    const StepStats &stats() const;
    /// Total kinetic energy of the dynamic bodies, J, >= 0; infinite only when it exceeds
    /// the largest double (about 1.8e308 J).
    real kineticEnergy() const;

    // --- Saved states (rollback) --------------------------------------------------------

    /// Everything the next step reads, as bytes: the bodies' poses, velocities, pending
    /// forces and sleep states, the contacts and their warm-start impulses, the joints,
    /// springs, sensor overlaps, the broadphase's trees and the id generations. Shapes are
    /// not copied: a state names them by the order of the addBody calls, so it can be
    /// restored in this World or in another built by the same calls. Settings are not part
    /// of it. See docs/rollback.md for its size.
    std::vector<std::uint8_t> saveState() const;
    /// Puts the World back in `state` (from saveState() of this World or of one built by the
    /// same calls): stepping on gives the same bits as the saving World did. Bodies, joints
    /// and springs added since are gone, those removed are back with the same ids; the
    /// events of the last step are cleared. Throws InvalidArgument, changing nothing, on a
    /// damaged state (its checksum fails) or one of another World (other shapes).
    void restoreState(const std::vector<std::uint8_t> &state);
    /// Sets the listener that sees each contact manifold before it is solved (see
    /// ContactListener), or removes it (nullptr). The World does not own it; it must
    /// outlive its use. Without a listener, and without bodies that have a
    /// BodySettings::oneWay or surfaceVelocity, the step pays nothing for the stage.
    void setContactListener(ContactListener *listener);
    /// The listener set by setContactListener (nullptr: none).
    ContactListener *contactListener() const;

    // --- Events -------------------------------------------------------------------------

    /// The events of the last step: contacts that began and ended, bodies that fell
    /// asleep and woke up (see WorldEvents for what is reported when). Valid until the
    /// next step(); empty before the first one.
    const WorldEvents &events() const;

    // --- Queries ------------------------------------------------------------------------

    /// The closest body that the ray from `origin` (m, finite, within 1e12 m of the origin)
    /// along `direction` (finite, not zero; normalised here) meets within `maxDistance`
    /// (m, > 0, may be infinite), among those `filter` accepts; none when it meets
    /// nothing. Exact for every shape type. A solid shape (or a plane's half-space) that
    /// contains `origin` is not hit: the ray starts inside it and leaves it. Sleeping and
    /// static bodies are hit like awake ones; bodies isolated for a non-finite state are
    /// not. Ties at the same distance go to the body with the smaller BodyId::index.
    std::optional<RayHit> rayCast(const Vector3 &origin, const Vector3 &direction,
                                  real maxDistance = std::numeric_limits<real>::infinity(),
                                  const QueryFilter &filter = QueryFilter()) const;

    /// Every body the ray meets within `maxDistance`, into `out` (cleared first), nearest
    /// first, one hit per body (where the ray first meets it), ties by the smaller
    /// BodyId::index; returns their count. The ray, the filter, the refusals and the hits
    /// are rayCast()'s: its hit is the first of these.
    std::size_t rayCastAll(const Vector3 &origin, const Vector3 &direction, std::vector<RayHit> &out,
                           real maxDistance = std::numeric_limits<real>::infinity(),
                           const QueryFilter &filter = QueryFilter()) const;

    /// The first body that `shape` (any shape but a plane or a mesh; a compound is placed
    /// by its frame), placed at `position` (m, finite, within 1e12 m of the origin) with
    /// `orientation` (finite; normalised; (0,0,0,0) means identity) and moved by
    /// `translation` (m, finite, not zero) without turning, touches, among those `filter`
    /// accepts; none when it touches nothing on the way. Validated as for addBody(): every
    /// point of the shape, at the start and at the end, within 1e12 m of the origin. The shapes are apart by at most
    /// 0.1 mm, never overlapping, at the distance reported (conservative advancement on
    /// the GJK distance; planes exact). A body the shape overlaps at the start is hit at
    /// 0 only if the translation goes deeper into it; otherwise it is left out, so that a
    /// character standing on the ground can cast along it. Ties go to the smaller
    /// BodyId::index. The building block of a character controller.
    std::optional<ShapeCastHit> shapeCast(const Shape &shape, const Vector3 &position, const Quaternion &orientation,
                                          const Vector3 &translation,
                                          const QueryFilter &filter = QueryFilter()) const;

    /// shapeCast() for a shape that also turns as it moves: over the cast it turns from
    /// `orientation` to `endOrientation` (both finite unit quaternions, norm within 1e-6
    /// of 1) the shorter way, at a constant angular velocity about the point `position`
    /// (its frame's origin), which moves by `translation` (m, finite; zero for a turn in
    /// place) at a constant velocity. The hit, the filter, the refusals, the tolerance and
    /// the start rule are shapeCast()'s (a body touched at the start is hit at 0 only if
    /// the point that touches it moves into it), `distance` is the fraction times the
    /// translation's length, and every point of the shape, at the start and at the end,
    /// must be within 1e12 m of the origin. Equal orientations give shapeCast()'s answer
    /// (and a zero translation with them is refused, field "translation"). A half turn
    /// goes about the vector part of endOrientation times orientation's conjugate. Solved
    /// by conservative advancement: no point moves faster towards a target than the
    /// translation's part plus the turn's rate times its farthest point's distance from
    /// `position`, so a cast that passes a body within a few tolerances takes many small
    /// steps there (at most 256 per pair of convex pieces; if they run out, it reports a
    /// touch where it stopped, the shapes still apart).
    std::optional<ShapeCastHit> shapeCast(const Shape &shape, const Vector3 &position, const Quaternion &orientation,
                                          const Vector3 &translation, const Quaternion &endOrientation,
                                          const QueryFilter &filter = QueryFilter()) const;

    /// The bodies whose shapes intersect (overlap or touch) `shape` placed at `position`
    /// (m, finite, within 1e12 m of the origin) with `orientation` (finite, normalised;
    /// (0,0,0,0) means identity), among those `filter` accepts, written into `out`
    /// (cleared first) in increasing BodyId::index. Returns how many. `shape` is
    /// validated as for addBody() (every point within 1e12 m of the origin); a plane is refused (it is unbounded); a compound is
    /// placed by its frame. Tested exactly with FCL (a compound child by child).
    std::size_t overlap(const Shape &shape, const Vector3 &position, const Quaternion &orientation,
                        std::vector<BodyId> &out, const QueryFilter &filter = QueryFilter()) const;

    // --- Debug drawing ------------------------------------------------------------------

    /// Draws the world through `draw` as `options` asks (validated first: a bad option
    /// throws InvalidArgument before anything is drawn): shapes as wireframes coloured by
    /// state (awake, asleep, static, isolated), broadphase boxes, and the contact points
    /// and normals of touching pairs. A `draw` that calls a member of the World that may
    /// change it (removeBody, step, any non-const one) makes debugDraw throw
    /// InvalidArgument (field "draw") as soon as that call of `draw` returns; what it changed stays changed.
    void debugDraw(DebugDraw &draw, const DebugDrawOptions &options = DebugDrawOptions()) const;

private:
    struct Impl;
    /// The World's state, checked at every use: a call on a moved-from World throws
    /// InvalidArgument (function "World", field "this") instead of reaching a null state.
    class State {
    public:
        State();
        ~State();
        State(State &&) noexcept;
        State &operator=(State &&) noexcept;
        State &operator=(std::unique_ptr<Impl> impl);
        Impl *operator->() const { return get(); }
        Impl &operator*() const { return *get(); }
        /// The same for the World's non-const members, counted: a callback that must only
        /// read (QueryFilter::accept, a DebugDraw) is refused once it made such a call.
        Impl *operator->() { return changing(); }
        Impl &operator*() { return *changing(); }

    private:
        Impl *get() const {
            if (!impl_) throwMovedFrom();
            return impl_.get();
        }
        Impl *changing();
        [[noreturn]] static void throwMovedFrom();
        std::unique_ptr<Impl> impl_;
    };
    State impl_;
};

}  // namespace cyclone
