/// \file
/// cyclone::RigidBody, the dynamics core: mass, inertia, damping, state, forces and sleep,
/// in SI units (m, kg, s, rad, N, N m). Inside a World, read bodies with World::body() and
/// change them through the World's calls, which keep the wake rules of islands (see
/// world.h); a RigidBody on its own wakes only through the calls that say so below.
//
// cyclone::RigidBody: the dynamics core, after "Game Physics Engine Development"
// (Millington), on Eigen math types.
//
// Design note. The class keeps cyclone's split between characteristics (mass,
// inertia, damping), state (position, orientation, velocity, rotation) and
// derived data (world-space inverse inertia, transform). It differs from the
// original where the original was wrong or unsafe:
//  - every member has a documented default (the original left state undefined);
//  - every setter and integrate() validate their input and throw
//    std::invalid_argument naming the function and the value, leaving the body
//    exactly as it was;
//  - getPointInWorldSpace / getDirectionInWorldSpace convert body -> world;
//  - the sleep threshold belongs to the body (no mutable global), so two worlds
//    in one process never interfere;
//  - the sleep average is kept whether or not the body may sleep;
//  - an implicit gyroscopic step (GyroscopicStep), off by default, so that a spinning
//    asymmetric body can keep its angular momentum; its calls refuse bad input with
//    cyclone::InvalidArgument (a std::invalid_argument naming function and field);
//  - a second-order rotation step that keeps a torque-free body's angular momentum and
//    energy (RotationStep::MomentumConserving), off by default.
// Setters of characteristics or state keep derived data current, so a getter
// never returns stale data (calculateDerivedData() stays public for callers who
// change state through a subclass).
#pragma once

#include "cyclone/core.h"
#include "cyclone/error.h"
#include "cyclone/precision.h"

namespace cyclone {

/// Default threshold of the sleep average below which a body may sleep
/// (unit: (m/s)^2 + (rad/s)^2). 0.01 is an RMS speed of 0.1 m/s: a body sliding
/// at 0.5 m/s or spinning at 0.5 rad/s stays awake (cyclone's 0.3 sent it to sleep),
/// while a body at rest falls asleep about one second after it stops.
inline constexpr real kDefaultSleepEpsilon = 0.01;

/// The implicit step of Euler's torque-free equations I dw/dt + w x I w = 0 that
/// RigidBody::applyGyroscopicStep takes; without it (the seed) a torque-free body keeps
/// its world angular velocity, while an asymmetric body's angular momentum is what is
/// conserved (and, spun about its intermediate axis, it flips: the Dzhanibekov effect).
enum class GyroscopicStep {
    /// No gyroscopic term: the seed's scheme.
    None,
    /// Backward Euler, as Bullet's and Jolt's implicit gyroscopic term: one Newton step
    /// from w on I (w' - w) + h w' x I w' = 0. The exact solution never raises the energy
    /// or |L|, but loses both at first order: a box spun near its intermediate axis at
    /// 60 Hz loses about 30% of its energy in 10 s (docs/accuracy/README.md).
    BackwardEuler,
    /// The implicit midpoint rule: I (w' - w) + h m x I m = 0 with m = (w + w') / 2,
    /// solved by Newton's method to roundoff (2-4 iterations of a 3x3 solve at
    /// h |w| < 1). It conserves the kinetic energy and |L| exactly (both are quadratic
    /// invariants, which the midpoint rule keeps); with integrate's orientation update,
    /// the world angular momentum drifts at first order, 5 to 10 times less than with
    /// BackwardEuler in the spinning-box scenes of docs/accuracy/README.md.
    Midpoint,
};

/// How RigidBody::integrate advances the orientation and the angular velocity.
enum class RotationStep {
    /// The seed's, first order: the torque changes the angular velocity, which is then held
    /// through the step while the orientation turns by q += h/2 (0, w) q, normalised. A
    /// torque-free body keeps its world angular velocity, which is right only for a body
    /// of isotropic inertia.
    Seed,
    /// Second order in the step for the rotation: half of the torque's impulse on the
    /// world angular momentum L, the torque-free motion over the whole step
    /// (applyTorqueFreeRotation), then the other half. Without torque the world angular
    /// momentum and the kinetic energy are kept to rounding error whatever the step; the
    /// torque is that of the step's start, so a torque that changes with the pose is
    /// followed at first order. The linear motion is the seed's.
    MomentumConserving,
};

namespace detail {
struct StateFields;
}  // namespace detail

/// A rigid body: position and orientation with their first derivatives, mass and
/// inertia, damping, accumulated force and torque, and sleep state.
///
/// Units are SI throughout: m, kg, s, rad, N, N m. Vectors are in world space unless
/// a name says otherwise.
///
/// What wakes a body: setAwake(true), setCanSleep(false) and the force and torque calls
/// (addForce, addForceAtPoint, addForceAtBodyPoint, addTorque). Setting the position,
/// orientation, velocity or rotation, or adding velocity or rotation, leaves the sleep
/// state alone (a World's setters wake the body themselves).
class RigidBody {
public:
    friend struct detail::StateFields;  ///< Saves and restores the state (World::saveState).
    /// A unit body at rest: mass 1 kg, inertia identity (kg m^2), at the origin,
    /// identity orientation, no damping (1), no constant acceleration, awake, allowed to
    /// sleep, sleep threshold kDefaultSleepEpsilon, sleep average twice that threshold.
    RigidBody();

    // --- Integration and simulation ---------------------------------------------------

    /// Recomputes the world transform and world inverse inertia from the state.
    /// Setters already do this; call it after changing protected state in a subclass.
    void calculateDerivedData();

    /// Advances the body by `duration` seconds (>= 0, finite) with the first-order,
    /// semi-implicit Newton-Euler scheme: the gyroscopic step if one is set
    /// (setGyroscopicStep), velocities from forces, damping, then positions from the
    /// new velocities (the orientation turns by the Cayley rotation of duration times
    /// the angular velocity: q += dt/2 (0, w) q, normalised; or as setRotationStep says,
    /// see RotationStep); clears the accumulators and updates the
    /// sleep average. Puts the body to sleep when the average drops below the sleep
    /// threshold and the body may sleep. A sleeping body and `duration == 0` change
    /// nothing. Throws std::invalid_argument on a negative or non-finite duration.
    void integrate(real duration);

    /// As integrate(duration), but the body is put to sleep only if `mayFallAsleep` is
    /// true. A world that sleeps whole islands at once passes false and decides itself.
    void integrate(real duration, bool mayFallAsleep);

    /// Sets the gyroscopic step integrate() begins with (default GyroscopicStep::None,
    /// the seed's scheme). Throws InvalidArgument on a value outside the enum.
    void setGyroscopicStep(GyroscopicStep step);
    /// The gyroscopic step integrate() begins with.
    GyroscopicStep getGyroscopicStep() const { return gyroscopicStep; }

    /// Sets how integrate() advances the orientation and the angular velocity (default
    /// RotationStep::Seed). Throws InvalidArgument on a value outside the enum.
    void setRotationStep(RotationStep step);
    /// How integrate() advances the orientation and the angular velocity.
    RotationStep getRotationStep() const { return rotationStep; }

    /// Moves the body as a torque-free rigid body for `duration` seconds (finite, >= 0):
    /// the implicit midpoint rule on the body-frame angular momentum L_b,
    /// L_b' - L_b = h (L_b + L_b')/2 x W, with W = I^-1 (L_b + L_b')/2 the midpoint angular
    /// velocity, solved by Newton's method to roundoff. That step is the rotation of L_b by
    /// the Cayley map of -h W; the orientation turns by the opposite rotation (the Cayley
    /// map of h W in body space), so the world angular momentum R L_b does not change and
    /// the kinetic energy L_b . I^-1 L_b / 2, a quadratic invariant that the midpoint rule
    /// keeps, does not either. Second order; a step with h |w| beyond about 1, where
    /// Newton's method may not converge, is split into equal parts. The position and the
    /// linear velocity are untouched; the angular velocity becomes R' I^-1 R'^T L. A
    /// sleeping body and a zero duration change nothing. Throws InvalidArgument on a
    /// negative or non-finite duration, leaving the body unchanged.
    void applyTorqueFreeRotation(real duration);

    /// Replaces the angular velocity by that of one implicit `step` of Euler's
    /// torque-free equations over `duration` seconds (finite, >= 0), computed in body
    /// space where the inertia is constant (see GyroscopicStep). Torque and damping are
    /// not applied here. A body with isotropic inertia (w x I w = 0), a sleeping body, a
    /// zero duration and GyroscopicStep::None change nothing, at no cost. The kinetic
    /// energy never grows: should the solution found raise it (roundoff, or an
    /// unconverged step at h |w| of order one or more), w' is scaled back to the energy
    /// before. Throws InvalidArgument on a negative or non-finite duration or a value
    /// outside the enum, leaving the body unchanged.
    void applyGyroscopicStep(GyroscopicStep step, real duration);

    /// True when the body-space inertia is a multiple of the identity (a sphere, a cube),
    /// within a relative 1e-12: the gyroscopic term w x I w is then zero.
    bool hasIsotropicInertia() const;

    // --- Mass and inertia ---------------------------------------------------------------

    /// Sets the mass (kg, finite, > 0).
    void setMass(const real mass);
    /// The mass (kg); infinity for a body of infinite mass.
    real getMass() const;
    /// Sets the inverse mass (1/kg, finite, >= 0; 0 makes the body immovable).
    void setInverseMass(const real inverseMass);
    /// The inverse mass (1/kg).
    real getInverseMass() const;
    /// True exactly when the inverse mass is > 0.
    bool hasFiniteMass() const;

    /// Sets the body-space inertia tensor (kg m^2; finite, symmetric, positive definite).
    void setInertiaTensor(const Matrix3 &inertiaTensor);
    /// Writes the body-space inertia tensor (kg m^2) into `inertiaTensor`.
    void getInertiaTensor(Matrix3 *inertiaTensor) const;
    /// The body-space inertia tensor (kg m^2).
    Matrix3 getInertiaTensor() const;
    /// Writes the world-space inertia tensor (kg m^2) into `inertiaTensor`.
    void getInertiaTensorWorld(Matrix3 *inertiaTensor) const;
    /// The world-space inertia tensor (kg m^2).
    Matrix3 getInertiaTensorWorld() const;
    /// Sets the body-space inverse inertia tensor (1/(kg m^2); finite, symmetric,
    /// positive definite).
    void setInverseInertiaTensor(const Matrix3 &inverseInertiaTensor);
    /// Writes the body-space inverse inertia tensor into `inverseInertiaTensor`.
    void getInverseInertiaTensor(Matrix3 *inverseInertiaTensor) const;
    /// The body-space inverse inertia tensor (1/(kg m^2)).
    Matrix3 getInverseInertiaTensor() const;
    /// Writes the world-space inverse inertia tensor into `inverseInertiaTensor`.
    void getInverseInertiaTensorWorld(Matrix3 *inverseInertiaTensor) const;
    /// The world-space inverse inertia tensor (1/(kg m^2)).
    Matrix3 getInverseInertiaTensorWorld() const;

    // --- Damping ------------------------------------------------------------------------

    /// Sets both dampings: the fraction of linear / angular velocity kept after one
    /// second (each in [0, 1]; 1 means no damping).
    void setDamping(const real linearDamping, const real angularDamping);
    /// Sets the fraction of linear velocity kept after one second, in [0, 1].
    void setLinearDamping(const real linearDamping);
    /// The fraction of linear velocity kept after one second.
    real getLinearDamping() const;
    /// Sets the fraction of angular velocity kept after one second, in [0, 1].
    void setAngularDamping(const real angularDamping);
    /// The fraction of angular velocity kept after one second.
    real getAngularDamping() const;
    /// The fractions of linear and angular velocity that damping keeps over `duration`
    /// seconds (finite, >= 0): linearDamping^duration and angularDamping^duration, the
    /// factors integrate(duration) applies. Kept from one call (or integrate) to the next
    /// while the duration and the damping stay the same.
    void getDampingFactors(real duration, real *linear, real *angular) const;

    // --- Position and orientation -------------------------------------------------------

    /// Sets the world-space position of the centre of mass (m, finite).
    void setPosition(const Vector3 &position);
    /// Sets the position by component (m, finite).
    void setPosition(const real x, const real y, const real z);
    /// Writes the position (m) into `position`.
    void getPosition(Vector3 *position) const;
    /// The position (m).
    Vector3 getPosition() const;

    /// Sets the orientation (finite components). It is normalised; (0,0,0,0) means
    /// identity.
    void setOrientation(const Quaternion &orientation);
    /// Sets the orientation by component: r (w), i (x), j (y), k (z); normalised,
    /// (0,0,0,0) means identity.
    void setOrientation(const real r, const real i, const real j, const real k);
    /// Writes the orientation into `orientation`.
    void getOrientation(Quaternion *orientation) const;
    /// The orientation (unit quaternion).
    Quaternion getOrientation() const;
    /// Writes the rotation matrix (body -> world directions) into `matrix`.
    void getOrientation(Matrix3 *matrix) const;
    /// Writes the rotation matrix (body -> world directions), row-major, into `matrix`.
    void getOrientation(real matrix[9]) const;
    /// Writes the body -> world transform into `transform`.
    void getTransform(Matrix4 *transform) const;
    /// Writes the body -> world transform, row-major 4x4 (last row 0 0 0 1).
    void getTransform(real matrix[16]) const;
    /// Writes the body -> world transform column-major (the transpose of
    /// getTransform(real[16])), ready for OpenGL.
    void getGLTransform(float matrix[16]) const;
    /// The body -> world transform.
    Matrix4 getTransform() const;

    /// Converts a point from world space to body space.
    Vector3 getPointInLocalSpace(const Vector3 &point) const;
    /// Converts a point from body space to world space.
    Vector3 getPointInWorldSpace(const Vector3 &point) const;
    /// Converts a direction from world space to body space (no translation).
    Vector3 getDirectionInLocalSpace(const Vector3 &direction) const;
    /// Converts a direction from body space to world space (no translation).
    Vector3 getDirectionInWorldSpace(const Vector3 &direction) const;

    // --- Velocity and rotation ----------------------------------------------------------

    /// Sets the world-space linear velocity (m/s, finite).
    void setVelocity(const Vector3 &velocity);
    /// Sets the linear velocity by component (m/s, finite).
    void setVelocity(const real x, const real y, const real z);
    /// Writes the linear velocity (m/s) into `velocity`.
    void getVelocity(Vector3 *velocity) const;
    /// The linear velocity (m/s).
    Vector3 getVelocity() const;
    /// Adds `deltaVelocity` (m/s, finite) to the linear velocity. Does not wake the body.
    void addVelocity(const Vector3 &deltaVelocity);

    /// Sets the world-space angular velocity (rad/s, finite).
    void setRotation(const Vector3 &rotation);
    /// Sets the angular velocity by component (rad/s, finite).
    void setRotation(const real x, const real y, const real z);
    /// Writes the angular velocity (rad/s) into `rotation`.
    void getRotation(Vector3 *rotation) const;
    /// The angular velocity (rad/s).
    Vector3 getRotation() const;
    /// Adds `deltaRotation` (rad/s, finite) to the angular velocity. Does not wake the body.
    void addRotation(const Vector3 &deltaRotation);

    // --- Sleep --------------------------------------------------------------------------

    /// True if the body is awake and integrated.
    bool getAwake() const { return isAwake; }
    /// Wakes the body (sleep average set to twice the sleep threshold, so it stays
    /// awake about a second) or puts it to sleep (velocity and rotation zeroed).
    void setAwake(const bool awake = true);
    /// True if the body may fall asleep.
    bool getCanSleep() const { return canSleep; }
    /// Allows or forbids sleep; forbidding it wakes the body.
    void setCanSleep(const bool canSleep = true);
    /// The recency-weighted sleep average, (m/s)^2 + (rad/s)^2.
    real getSleepAverage() const { return motion; }
    /// Sets the sleep threshold of the sleep average ((m/s)^2 + (rad/s)^2, finite, > 0).
    void setSleepEpsilon(const real sleepEpsilon);
    /// The sleep threshold of the sleep average.
    real getSleepEpsilon() const { return sleepEpsilon; }
    /// Sets the cap of the sleep average, as a multiple of the sleep threshold, in a
    /// step where the body moves (v.v + w.w at or above the threshold); finite, in
    /// [1, 10]. A body that stops then sleeps at most log2(cap) s later. Default 10, the
    /// seed's clamp (the average is capped at 10 times the threshold in every step).
    void setMovingSleepAverageCap(const real cap);
    /// The cap of the sleep average while the body moves, a multiple of the threshold.
    real getMovingSleepAverageCap() const { return movingMotionCap; }

    // --- Dynamic quantities -------------------------------------------------------------

    /// Writes the linear acceleration of the last integration step (m/s^2).
    void getLastFrameAcceleration(Vector3 *linearAcceleration) const;
    /// The linear acceleration of the last integration step (m/s^2).
    Vector3 getLastFrameAcceleration() const;

    // --- Forces, torques and constant acceleration --------------------------------------

    /// Clears the accumulated force and torque (integrate() does it after each step).
    void clearAccumulators();
    /// Adds a world-space force (N, finite) at the centre of mass. Wakes a sleeping body
    /// as setAwake(true) does.
    void addForce(const Vector3 &force);
    /// Adds a world-space force (N) at a world-space point (m): a force and a torque.
    /// Wakes a sleeping body.
    void addForceAtPoint(const Vector3 &force, const Vector3 &point);
    /// Adds a world-space force (N) at a body-space point (m). Wakes a sleeping body.
    void addForceAtBodyPoint(const Vector3 &force, const Vector3 &point);
    /// Adds a world-space torque (N m, finite). Wakes a sleeping body.
    void addTorque(const Vector3 &torque);
    /// The accumulated force (N) for the next step.
    Vector3 getAccumulatedForce() const { return forceAccum; }
    /// The accumulated torque (N m) for the next step.
    Vector3 getAccumulatedTorque() const { return torqueAccum; }

    /// Sets the constant acceleration (m/s^2, finite), e.g. gravity.
    void setAcceleration(const Vector3 &acceleration);
    /// Sets the constant acceleration by component (m/s^2, finite).
    void setAcceleration(const real x, const real y, const real z);
    /// Writes the constant acceleration (m/s^2) into `acceleration`.
    void getAcceleration(Vector3 *acceleration) const;
    /// The constant acceleration (m/s^2).
    Vector3 getAcceleration() const;

protected:
    // Characteristics.
    real inverseMass;                 ///< 1/kg; 0 for an immovable body.
    Matrix3 inverseInertiaTensor;     ///< Body space, 1/(kg m^2).
    real linearDamping;               ///< Fraction of velocity kept after 1 s, [0, 1].
    real angularDamping;              ///< Fraction of rotation kept after 1 s, [0, 1].

    // State.
    Vector3 position;                 ///< World-space centre of mass, m.
    Quaternion orientation;           ///< Body -> world rotation, unit length.
    Vector3 velocity;                 ///< World-space linear velocity, m/s.
    Vector3 rotation;                 ///< World-space angular velocity, rad/s.

    // Derived data.
    Matrix3 inverseInertiaTensorWorld;  ///< World space, 1/(kg m^2).
    real motion;                        ///< Recency-weighted mean of v.v + w.w.
    real sleepEpsilon;                  ///< Sleep threshold of `motion`.
    real movingMotionCap;               ///< Cap of `motion` while moving, x sleepEpsilon, [1, 10].
    bool isAwake;                       ///< Integrated only when true.
    bool canSleep;                      ///< False keeps the body awake.
    GyroscopicStep gyroscopicStep;      ///< What integrate() applies first.
    RotationStep rotationStep;          ///< How integrate() turns the body.
    Matrix4 transformMatrix;            ///< Body -> world transform.

    // Accumulators.
    Vector3 forceAccum;               ///< N, world space, cleared each step.
    Vector3 torqueAccum;              ///< N m, world space, cleared each step.
    Vector3 acceleration;             ///< Constant acceleration, m/s^2 (gravity).
    Vector3 lastFrameAcceleration;    ///< Linear acceleration of the last step, m/s^2.

private:
    /// integrate()'s factors for one duration and damping: std::pow is costly, and a
    /// body is usually integrated with the same duration step after step.
    struct StepFactors {
        real duration = -1;        ///< s; -1 (no valid duration): not computed yet.
        real linearDamping = -1;
        real angularDamping = -1;
        real linear = 1;           ///< linearDamping^duration.
        real angular = 1;          ///< angularDamping^duration.
        real motionBias = 1;       ///< 0.5^duration: weight of the old sleep average.
    };
    mutable StepFactors lastStepFactors;  ///< A cache: not part of the body's state.

    /// The factors for `duration` and the current damping (recomputed when they changed).
    const StepFactors &stepFactors(real duration) const;
};

// Defined here, inline: a World's step reads them for every contact point.
inline Vector3 RigidBody::getPosition() const { return position; }
inline Quaternion RigidBody::getOrientation() const { return orientation; }
inline Matrix4 RigidBody::getTransform() const { return transformMatrix; }
inline Vector3 RigidBody::getPointInWorldSpace(const Vector3 &point) const { return transformMatrix * point; }

}  // namespace cyclone
