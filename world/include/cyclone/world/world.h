// cyclone::World: rigid bodies with collision shapes, FCL contact detection, an impulse
// solver, and island sleep.
//
// Ownership: the World owns its bodies; a BodyId is a handle that stays valid until the
// body is removed. Read a body through body(id); change it through the World's calls,
// so that waking rules hold: any call that moves a body, sets its velocity or applies a
// force or impulse wakes it and its island.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cyclone/body.h"
#include "cyclone/world/error.h"
#include "cyclone/world/settings.h"
#include "cyclone/world/shape.h"
#include "cyclone/world/stats.h"

namespace cyclone {

class World {
public:
    /// A world with the given settings; throws InvalidArgument on bad settings.
    explicit World(const WorldSettings &settings = WorldSettings());
    ~World();
    World(const World &) = delete;
    World &operator=(const World &) = delete;
    World(World &&) noexcept;
    World &operator=(World &&) noexcept;

    /// The settings in force.
    const WorldSettings &settings() const;
    /// Replaces the settings (validated; on refusal nothing changes). Wakes every body.
    void setSettings(const WorldSettings &settings);

    // --- Bodies -------------------------------------------------------------------------

    /// Adds a body; throws InvalidArgument (nothing added) on a bad shape, mass, inertia,
    /// number, a plane or mesh on a dynamic body, or a duplicate non-empty name.
    BodyId addBody(const BodySettings &settings);
    /// Removes a body; bodies touching it wake. Throws InvalidArgument on a stale handle.
    void removeBody(BodyId id);
    /// True while `id` names a body of this world.
    bool contains(BodyId id) const;
    /// Every body, in the order they were added.
    std::vector<BodyId> bodies() const;
    /// Number of bodies.
    std::size_t bodyCount() const;
    /// The body with this name, if any.
    std::optional<BodyId> findBody(const std::string &name) const;

    /// Read-only access to a body's dynamic state.
    const RigidBody &body(BodyId id) const;
    /// The body's name (may be empty).
    const std::string &name(BodyId id) const;
    /// The body's shape.
    const Shape &shape(BodyId id) const;
    /// Whether the body is static.
    bool isStatic(BodyId id) const;
    /// The body's material.
    const Material &material(BodyId id) const;

    // --- Changing bodies: each wakes the body and its island ----------------------------

    void setPosition(BodyId id, const Vector3 &position);
    void setOrientation(BodyId id, const Quaternion &orientation);
    void setVelocity(BodyId id, const Vector3 &velocity);
    void setRotation(BodyId id, const Vector3 &rotation);
    /// Applies an impulse (N s) at the centre of mass.
    void applyImpulse(BodyId id, const Vector3 &impulse);
    /// Applies an impulse (N s) at a world-space point (m).
    void applyImpulse(BodyId id, const Vector3 &impulse, const Vector3 &point);
    /// Adds a force (N) at the centre of mass for the next step.
    void addForce(BodyId id, const Vector3 &force);
    /// Adds a force (N) at a world-space point (m) for the next step.
    void addForceAtPoint(BodyId id, const Vector3 &force, const Vector3 &point);
    /// Adds a torque (N m) for the next step.
    void addTorque(BodyId id, const Vector3 &torque);
    /// Wakes the body and its island, or puts the body's island to sleep.
    void setAwake(BodyId id, bool awake);
    /// Allows or forbids sleep for the body; forbidding wakes it.
    void setCanSleep(BodyId id, bool canSleep);
    /// Replaces the body's material (does not wake it).
    void setMaterial(BodyId id, const Material &material);

    // --- Springs ------------------------------------------------------------------------

    /// Adds a spring; it wakes the bodies it joins.
    SpringId addSpring(const SpringSettings &settings);
    /// Removes a spring; it wakes the bodies it joined.
    void removeSpring(SpringId id);

    // --- Stepping -----------------------------------------------------------------------

    /// Advances the world by dt seconds (finite, > 0).
    void step(real dt);
    /// Counters and per-stage timings of the last step.
    const StepStats &stats() const;
    /// Total kinetic energy of the dynamic bodies, J.
    real kineticEnergy() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace cyclone
