/// \file
/// What the user fills in: settings of a world, a body and a spring, with defaults, units
/// and valid ranges, and the handles of bodies and springs. The World validates every
/// field and refuses bad ones with InvalidArgument.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "cyclone/body.h"
#include "cyclone/core.h"
#include "cyclone/world/locked_axes.h"
#include "cyclone/world/shape.h"

namespace cyclone {

/// Integration scheme of a world's dynamic bodies (scene files: the name in quotes).
/// docs/accuracy/README.md shows each one's error against its cost.
enum class Integrator {
    /// "newton-euler": the seed's first-order semi-implicit Newton-Euler. Without torque
    /// the world angular velocity stays constant (wrong for an asymmetric body, whose
    /// angular momentum is what is conserved); spring forces are explicit, evaluated at
    /// the start of each sub-step of h = dt / substeps (symplectic Euler: stable while
    /// omega h < 2, beyond which a spring gains energy and explodes), except that a
    /// spring of SpringForce::Automatic whose omega h exceeds explicitSpringLimit gets
    /// the backward-Euler force (so does every spring under the integrators below but
    /// NewtonEulerImplicit, which makes them all backward Euler).
    NewtonEuler,
    /// "newton-euler-gyroscopic": the seed plus the implicit gyroscopic term
    /// (GyroscopicStep::Midpoint over the whole step, before the first sub-step's solve),
    /// so that a spinning asymmetric body keeps its kinetic energy and its angular
    /// momentum to first order in dt (and flips about its intermediate axis, which the
    /// seed's never does). Costs 2-4 3x3 solves per step and awake body of anisotropic
    /// inertia; nothing for spheres and cubes.
    NewtonEulerGyroscopic,
    /// "newton-euler-implicit": the gyroscopic term as above, and backward-Euler springs:
    /// each spring's force is solved each sub-step for the velocity it produces (4 passes
    /// of a 3x3 solve per spring), so a spring never gains energy whatever its omega dt. The
    /// price is numerical damping: a fraction u^2 / (1 + u^2) of the oscillation energy is
    /// lost per sub-step, u = omega h (1% at u = 0.1, so an undamped 150 rad/s spring at
    /// 1500 Hz keeps 1e-13 of its energy after 2 s). For stiff springs that should hold,
    /// not ring.
    NewtonEulerImplicit,
    /// "momentum-conserving": second order in the step for the rotation
    /// (RotationStep::MomentumConserving in every sub-step: half the torque's impulse,
    /// the torque-free motion by the implicit midpoint rule on the body-frame angular
    /// momentum with the matching rotation of the orientation, the other half). A
    /// torque-free body keeps its world angular momentum and kinetic energy to rounding
    /// error whatever the step. The linear motion, contacts and springs are as with
    /// "newton-euler". Costs 3-5 3x3 solves per sub-step and awake body of anisotropic
    /// inertia.
    MomentumConserving,
};

/// The solver's algorithm switches and tuning, there to compare algorithms in benchmarks
/// and tests. Leave alone: the defaults are what the tests and benchmarks measure, and
/// turning one off makes stacks, landings or sleep worse (docs/solver.md says by how much).
struct DebugSettings {
    /// Sub-steps of a step in which every awake body rests (touches something, each of its
    /// contacts was solved last step and one at least carried a normal impulse, and it
    /// moves less than 1 mm in the step), in [0, WorldSettings::substeps]: that step takes
    /// restingIterations velocity passes in all, restingIterations / restingSubsteps per
    /// sub-step (rounded up), and costs a carrier pass, a penetration pass and an
    /// integration per sub-step less. Only without joints, springs or
    /// moving kinematic bodies, and while |gravity| (dt / restingSubsteps)^2 <=
    /// speculativeDistance. 0 or substeps: every step takes WorldSettings::substeps.
    int restingSubsteps = 1;
    /// Velocity passes of a resting step in all (see restingSubsteps), in [1, 10000]; a
    /// resting step takes at most the passes of a full step, velocityIterations * substeps.
    /// In a resting step the warm start carries the load and the carrier pass holds a stack
    /// up, so it needs fewer passes than a step in which something lands (docs/solver.md,
    /// "Resting steps").
    int restingIterations = 8;
    /// Speculative contacts from the bodies' speeds (WorldSettings::speculativeDistance): on, a pair that can meet
    /// within the step gets a contact that lets it close the gap and no more; off, only
    /// shapes that overlap or lie within speculativeDistance get contacts, so a landing
    /// body sinks up to v dt into the surface before the contact acts (for comparison;
    /// docs/accuracy/README.md measures both).
    bool speculativeContacts = true;
    /// The landing correction: after the step's integration, the pairs in which a body
    /// moved fast this step (more than half the tolerance below) are tested again at
    /// the poses the step ends with, and the points found deeper than a tolerance (5 mm,
    /// or a tenth of the smaller body's bounding radius when less) are pushed apart by
    /// position only, velocities unchanged, so that a body landing fast on a pile that is
    /// itself landing is not left sunk in it. Only the fast bodies are moved, and the
    /// bodies of a pair the step began deeper in than 1.6 tolerances (sunk under a pile's
    /// load). Bodies held together by joints move as one, all by the same translation, so
    /// that no joint opens (a group tied to the world or to a body that may not move stays
    /// still). A step in which neither is found does nothing more than compare each awake
    /// body's poses and each contact point's depth (docs/solver.md, "Landing
    /// correction").
    bool landingCorrection = true;
    /// A touching pair whose bodies moved less than this relative to each other since its
    /// last narrowphase keeps its manifold (depths refreshed from the anchors), and a
    /// manifold keeps its solver Jacobians while neither body moved more than this since
    /// they were made; m (translation plus rotation times the bounding radius), >= 0;
    /// 0 tests every pair and makes every Jacobian every step (docs/solver.md, "How the
    /// passes are made fast").
    real manifoldReuseTolerance = 0.0005;
    /// Whether impulses of the last step seed the solver (warm starting).
    bool warmStarting = true;
    /// The carrier pass: after the velocity passes of each sub-step, one more pass solves
    /// each body against the bodies that carry it as immovable ones, with a few sweeps per
    /// contact, keeping the impulses of the velocity passes; the last penetration pass does
    /// the same. Carriers are static and sleeping bodies and a body lower in the contact
    /// graph (counted from static or sleeping bodies) that the other rests on within 60
    /// degrees of gravity.
    /// Stacks then hold at any mass ratio and do not lean; off, every pass is plain
    /// Gauss-Seidel.
    bool carrierPass = true;
    /// Held bodies: a step leaves out of the solve each awake body that could sleep
    /// (sleep average below its threshold), rests on warm contacts as in a resting step,
    /// shares pairs only with such bodies, static or sleeping ones, and is not reached by
    /// a hit (a contact closing faster than 0.5 m/s, through the bodies that touch it); its
    /// velocity is zeroed and the bodies it touches are solved against it as immovable.
    /// Its island still sleeps as a whole. Only with sleep on and no joints or springs in
    /// the step. Off, every awake body is solved (docs/contacts_and_sleep.md, "Held bodies").
    bool holding = true;
    /// Unchanged pairs: a pair that found no contact at its last test, both bodies then
    /// without velocity, is not tested again while neither body's pose or velocities
    /// change (bit for bit) and nothing falls: the test would give the same answer. A
    /// settled pile's held bodies keep most of its pairs so. Off, every pair the
    /// broadphase lists is tested.
    bool unchangedPairs = true;
};

/// Settings of a World. Every field has a documented default; World validates them.
struct WorldSettings {
    /// Constant acceleration given to every dynamic body, m/s^2.
    Vector3 gravity = Vector3(0, -9.81, 0);
    /// Contact solver velocity iterations per sub-step, >= 1.
    int velocityIterations = 3;
    /// Penetration-recovery passes per sub-step (pseudo-velocity passes), >= 0.
    int positionIterations = 1;
    /// Sub-steps per step, >= 1: each repeats solve and integrate with dt / substeps.
    int substeps = 4;
    /// Whether bodies may fall asleep.
    bool sleep = true;
    /// Threshold of the sleep average (v.v + w.w) below which an island may sleep,
    /// (m/s)^2 + (rad/s)^2, > 0. A body of bounding radius R under 0.25 m gets this times
    /// (R / 0.25 m)^2, so that it must move as many of its sizes per second to stay awake.
    real sleepEpsilon = kDefaultSleepEpsilon;
    /// Longest time a body stays awake after it stops moving (its v.v + w.w drops below
    /// sleepEpsilon), s, in [0, log2(10) = 3.32]: while it moves, its sleep average is
    /// capped at 2^sleepDelay x sleepEpsilon (RigidBody::setMovingSleepAverageCap; 3.32 is the
    /// seed's clamp). A body woken at rest still stays awake about a second.
    real sleepDelay = 0.4;
    /// Integration scheme.
    Integrator integrator = Integrator::NewtonEuler;
    /// Springs of SpringForce::Automatic whose omega h exceeds this get the backward-Euler
    /// force (as with NewtonEulerImplicit) instead of the explicit one; dimensionless,
    /// > 0 (infinity keeps every spring explicit). omega^2 is a bound on the largest
    /// k / mass the spring's bodies feel along their springs (k times the inverse mass at
    /// the attachment point along the spring, twice that when the other end moves too,
    /// summed over a body's springs), h = dt / substeps. An explicit spring is stable
    /// while omega h < 2 but overshoots its starting stretch by 1 / sqrt(1 - (omega h / 2)^2):
    /// at 0.8, by at most 9%, while springs below it keep their energy.
    real explicitSpringLimit = 0.8;
    /// Penetration the solver leaves alone so that resting contacts persist, m, >= 0.
    /// Shapes apart by up to this also count as touching (box-box, the sphere pairs and
    /// a plane against a solid shape), so that shapes placed to touch, which rounding
    /// often leaves a hair apart, are in contact from the first step.
    real penetrationSlop = 0.0002;
    /// Fraction of the penetration beyond the slop removed per step, in (0, 1].
    real penetrationRecovery = 0.1;
    /// Approach speed below which restitution is ignored, m/s, >= 0.
    real restitutionThreshold = 1.0;
    /// Contact points up to this far apart are kept, so a tilting face keeps its
    /// support without a contact appearing suddenly, m, >= 0. Bodies that move also get
    /// speculative contacts with what they can reach within the step at their speeds
    /// (whatever this distance), so that a landing body stops at the surface in the step
    /// of the impact (meshes too, triangle by triangle).
    real speculativeDistance = 0.02;
    /// Most pairs of overlapping broadphase boxes a step keeps, in [1, 2^31 - 1]; beyond
    /// it the step drops the rest and says so (StepStats::errors, PairBudgetExceeded).
    /// Each pair kept while touching costs about 4.9 KB, up to 9.4 KB in a pile at one
    /// point, whose manifolds the passes cannot group (docs/hostile_input.md, "Bytes per
    /// pair and per contact"), so the default, 65,536 (as Jolt's samples' body pairs),
    /// bounds them near 0.6 GB; 24 GB would hold about 2.5 million.
    int maxPairs = 65536;
    /// Threads that run a step, the calling thread included, in [1, 64]. The contact
    /// solver shares its work among them; the results are the same whatever the count
    /// (docs/solver.md, "Threads"). 1 starts no thread.
    int threads = 1;
    /// Algorithm switches and tuning: leave alone (see DebugSettings).
    DebugSettings debug;
};

/// A collision mask holding every layer.
inline constexpr std::uint32_t kAllLayers = 0xffffffffu;

/// How a body moves.
enum class Motion {
    /// Never moves: infinite mass, not integrated (scene files: "static").
    Static,
    /// Infinite mass, moved only by the velocity and angular velocity the game sets
    /// (World::setVelocity, setRotation, moveKinematic); gravity, contacts and springs do
    /// not move it, and it pushes and carries the dynamic bodies it touches. It never
    /// sleeps while it moves (scene files: "kinematic").
    Kinematic,
    /// Moved by gravity, forces, springs and contacts (scene files: "dynamic").
    Dynamic,
};

/// Surface properties of a body.
struct Material {
    /// Coulomb friction coefficient, >= 0. A pair uses the geometric mean of its two.
    real friction = 0.6;
    /// Restitution in [0, 1]. A pair uses the larger of its two.
    real restitution = 0;
    /// Resistance to rolling, m, >= 0: the torque that opposes rolling at a point or line
    /// contact is at most this times the normal force. A pair uses the larger of its two.
    /// The default, 2 mm, stops a ball of radius r rolling at v in about
    /// v r (1 + I / (m r^2)) / (0.002 g) seconds (a 0.25 m ball at 1 m/s: 18 s) and keeps
    /// it still on slopes up to atan(0.002 / r) (0.46 degrees for r = 0.25 m).
    real rollingFriction = 0.002;
    /// Resistance to spinning about the contact normal at a point contact, m, >= 0: the
    /// opposing torque is at most this times the normal force (contacts of two points or
    /// more resist spinning through their friction's twist). A pair uses the larger. The
    /// default, 5 mm, stops a solid ball of radius r spinning in place at w in
    /// w 0.4 r^2 / (0.005 g) seconds (r = 0.25 m at 5 rad/s: 2.5 s).
    real spinningFriction = 0.005;
};

/// Largest magnitude of a coordinate or a size the World and the scene runner accept, m;
/// a body that flies beyond it is isolated (StepStats::isolatedBodies). Why 1e12: there
/// the spacing of doubles is 2^-13 m = 1.2e-4 m, below the default penetration slop
/// (2e-4 m) and far below the speculative distance and the broadphase margin (0.02 m), so
/// contacts hold as at the origin; at 1e14 m (spacing 0.016 m) a ball and a crate fall
/// through a static floor (docs/hostile_input.md, "Coordinate range").
inline constexpr real kMaxCoordinate = 1e12;

/// Longest step World::step takes, s (FixedStepper's stepSeconds has the same bound).
/// Why 1 s: a stack of five unit boxes with sleep off stays on for 2,000 s at dt = 1 and
/// 2 s (creeping sideways 4-5 cm per 1,000 s; at 0.25 s and below it does not creep), and
/// its top box slides off at 5 s (after 500 s) and 10 s (after 170 s): a body that touches
/// something when the step begins gets no speculative contact for the fall the step
/// brings, so a long step drops it through what it slides onto (docs/hostile_input.md,
/// "Long steps").
/// A longer span is taken as several steps (FixedStepper), as Jolt has the caller split a
/// long update into collision steps.
inline constexpr real kMaxStep = 1;

/// Shortest step World::step takes, s (FixedStepper's stepSeconds has the same bound).
/// Why 1e-6 s: the step divides by its sub-step h = dt / substeps (velocities from
/// position errors, speculative reach), and below about 1e-308 s that quotient is no
/// longer a double (dt = 5e-324 made eleven ragdoll bodies non-finite in the first step).
/// A microsecond is a thousand times shorter than any rate a game or a robot steps at
/// and leaves twelve orders of magnitude of margin (docs/hostile_input.md).
inline constexpr real kMinStep = 1e-6;

/// Smallest mass of a dynamic body, kg; also the smallest principal moment of inertia
/// over the squared bounding radius R (the farthest point of the shape from its origin).
/// Why: a contact's effective inverse mass along a row is at most
/// k = sum over its two bodies of 1/m + R^2 / I_min <= 4e100, and the solver inverts
/// 3 x 3 blocks of such rows (friction and twist) by cofactors, whose determinant is a sum
/// of six products of three k: 6 (4e100)^3 = 4e302 stays below the largest double
/// (1.8e308) with room for rounding. Below the range, 1 / m or its products overflow and
/// the solve turns NaN.
inline constexpr real kMinMass = 1e-100;
/// Largest mass of a dynamic body, kg; also the largest principal moment of inertia over
/// R^2. Why: the blocks' determinants shrink as (1/m)^3, and below 1e-300 they leave the
/// normal doubles (2.2e-308), so that friction would silently vanish.
inline constexpr real kMaxMass = 1e100;

/// Settings of a body to add to a World.
struct BodySettings {
    /// Unique within the world when not empty; used in reports and scene files.
    std::string name;
    /// Collision shape, in the body's frame.
    Shape shape;
    /// How the body moves. Kinematic bodies ignore `mass`, `inertia`, the damping and
    /// `canSleep`, and start with `velocity` and `rotation`.
    Motion motion = Motion::Dynamic;
    /// Mass of a dynamic body, kg, in [kMinMass, kMaxMass] = [1e-100, 1e100].
    real mass = 1;
    /// Body-space inertia tensor (about the centre of mass, in the shape frame's axes),
    /// kg m^2, symmetric positive definite, each principal moment over R^2 (R: the shape's
    /// farthest point from its origin, m) in [kMinMass, kMaxMass]; empty means computed
    /// from the shape and the mass (then checked the same way: a unit cube's moments are
    /// m/6 and R^2 = 3/4, so its mass must be at least 4.5e-100 kg).
    std::optional<Matrix3> inertia;
    /// World-space position of the centre of mass (the shape's origin; for a compound,
    /// the origin of the frame its children are placed in, and the centre of mass lies
    /// where their masses put it), m, finite, each
    /// coordinate within 1e12 m.
    Vector3 position = Vector3::Zero();
    /// Orientation; normalised on add, (0,0,0,0) means identity.
    Quaternion orientation = Quaternion::Identity();
    /// World-space linear velocity of a dynamic or kinematic body, m/s, finite.
    Vector3 velocity = Vector3::Zero();
    /// World-space angular velocity of a dynamic or kinematic body, rad/s, finite.
    Vector3 rotation = Vector3::Zero();
    /// Fraction of linear velocity kept after one second, [0, 1]; 1 means none.
    real linearDamping = 1;
    /// Fraction of angular velocity kept after one second, [0, 1]; 1 means none.
    real angularDamping = 1;
    /// Friction and restitution.
    Material material;
    /// False keeps this body awake always (World::setCanSleep changes it).
    bool canSleep = true;
    /// Initial awake state of a dynamic body: false adds it asleep, unmoved until
    /// something wakes it (see World for what does).
    bool awake = true;
    /// Continuous collision detection for this body (fast, thin things).
    bool ccd = false;
    /// Collision layer, in [0, 31].
    int layer = 0;
    /// The layers this body collides with, bit k for layer k. Two bodies touch only when
    /// each one's mask holds the other's layer. Every layer by default. A sensor sees a
    /// body by the same rule: each one's mask must hold the other's layer.
    std::uint32_t collidesWith = kAllLayers;
    /// A sensor reports the bodies that overlap it (WorldEvents::sensorBegins and
    /// sensorEnds) but pushes nothing and is pushed by nothing: its pairs never reach the
    /// contact solver. It sees every body but other sensors (static, sleeping and
    /// kinematic ones included) whose layer its `collidesWith` holds, whose own
    /// `collidesWith` holds the sensor's layer, and that no World::setPairCollision rule
    /// keeps from it. Any shape on a static body; any but a
    /// plane or a mesh on a kinematic or dynamic one (a dynamic sensor falls like any
    /// body, through the others). A mesh sensor sees what crosses its triangles.
    bool sensor = false;
    /// Multiplies the world's gravity for this body (dynamic bodies): any finite number;
    /// 0 floats, -1 falls up (World::setGravityScale changes it).
    real gravityScale = 1;
    /// World axes a dynamic body may not move along or turn about (see LockedAxes); its
    /// velocity's locked components are dropped when it is added. Ignored for static and
    /// kinematic bodies.
    LockedAxes lockedAxes;
    /// Velocity of the body's surface along its contacts, body space, m/s, finite: a
    /// conveyor belt's; the body itself moves as it otherwise would. Only its part in each
    /// contact's plane acts, through friction.
    Vector3 surfaceVelocity = Vector3::Zero();
    /// A one-way body (a platform): it collides only with bodies on the side this
    /// direction (body space, finite, not zero; normalised) points to; a body met from the
    /// other side, or already overlapping it, passes through until they are apart
    /// (contacts/pre_solve.h has the rule). Empty: an ordinary body.
    std::optional<Vector3> oneWay;
    /// The game's own number for the body (an index, a handle, a pointer's bits): returned
    /// with its events and query hits, never read by the World.
    std::uint64_t userData = 0;
};

/// Handle of a body in a World. Stale handles (of removed bodies) are refused. A
/// default-constructed BodyId names no body.
struct BodyId {
    /// Slot of the body in its World; reused after the body is removed.
    std::uint32_t index = UINT32_MAX;
    /// Incremented each time the slot is reused, so that an old handle stays stale.
    std::uint32_t generation = 0;
    /// True when both name the same body (same slot and generation).
    bool operator==(const BodyId &other) const { return index == other.index && generation == other.generation; }
    /// True when they name different bodies.
    bool operator!=(const BodyId &other) const { return !(*this == other); }
    /// Orders handles by slot, then generation (for std::map, std::set and sorting; the
    /// order says nothing about when the bodies were added).
    bool operator<(const BodyId &other) const {
        return index != other.index ? index < other.index : generation < other.generation;
    }
};

/// How a spring's force is integrated (with an integrator other than NewtonEulerImplicit,
/// whose springs are all backward Euler).
enum class SpringForce {
    /// Explicit (evaluated at the start of each sub-step) while the spring's omega h is
    /// within WorldSettings::explicitSpringLimit, backward Euler beyond: never explodes.
    Automatic,
    /// Always explicit, whatever omega h: stable only while omega h < 2.
    Explicit,
};

/// A damped spring between two bodies, or between a body and a fixed world point;
/// a force generator on the cyclone model (Hooke's law plus damping along the spring).
struct SpringSettings {
    /// First body.
    BodyId a;
    /// Attachment on `a`, in a's body space, m.
    Vector3 aPoint = Vector3::Zero();
    /// Second body; empty anchors the spring at the world point `bPoint`.
    std::optional<BodyId> b;
    /// Attachment on `b` in b's body space, or the world anchor when `b` is empty, m.
    Vector3 bPoint = Vector3::Zero();
    /// Spring constant, N/m, > 0.
    real stiffness = 100;
    /// Damping along the spring, N s/m, >= 0.
    real damping = 0;
    /// Rest length, m, >= 0.
    real restLength = 1;
    /// How the force is integrated.
    SpringForce force = SpringForce::Automatic;
};

/// Handle of a spring in a World. Stale handles (of removed springs) are refused.
struct SpringId {
    /// Slot of the spring in its World; reused after the spring is removed.
    std::uint32_t index = UINT32_MAX;
    /// Incremented each time the slot is reused, so that an old handle stays stale.
    std::uint32_t generation = 0;
    /// True when both name the same spring.
    bool operator==(const SpringId &other) const { return index == other.index && generation == other.generation; }
    /// True when they name different springs.
    bool operator!=(const SpringId &other) const { return !(*this == other); }
    /// Orders handles by slot, then generation (for std::map, std::set and sorting; the
    /// order says nothing about when the springs were added).
    bool operator<(const SpringId &other) const {
        return index != other.index ? index < other.index : generation < other.generation;
    }
};

}  // namespace cyclone

// Hashes of the handles, for std::unordered_map and std::unordered_set.
namespace std {
/// Hash of a BodyId: its slot and generation.
template <>
struct hash<cyclone::BodyId> {
    /// The hash of `id`.
    size_t operator()(const cyclone::BodyId &id) const noexcept {
        return hash<uint64_t>()(uint64_t{id.generation} << 32 | id.index);
    }
};
/// Hash of a SpringId: its slot and generation.
template <>
struct hash<cyclone::SpringId> {
    /// The hash of `id`.
    size_t operator()(const cyclone::SpringId &id) const noexcept {
        return hash<uint64_t>()(uint64_t{id.generation} << 32 | id.index);
    }
};
}  // namespace std
