// The World's public calls: validation, bodies and springs, stepping, events.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "collision/round_side.h"
#include "collision/time_of_impact.h"
#include "world/mass_range.h"
#include "world/free_slots.h"
#include "world/validation.h"
#include "world/world_impl.h"

namespace cyclone {

using detail::Tree;

namespace {

// m v.v + w.(I w), never negative, and infinite only when the energy is: m v.v as
// (sqrt(m) |v|)^2, w.(I w) as |D^-1/2 L^-1 P w|^2 from the LDLT of the inverse inertia (the
// tensor itself, inverted back, is lost for masses beyond about 1e100 kg).
real twiceKineticEnergy(const RigidBody &body) {
    const real linear = std::sqrt(body.getMass()) * body.getVelocity().stableNorm();
    const Eigen::LDLT<Matrix3> ldlt(body.getInverseInertiaTensorWorld());
    const Vector3 y = ldlt.matrixL().solve(ldlt.transpositionsP() * body.getRotation());
    real twice = linear * linear;
    for (int i = 0; i < 3; ++i) {
        const real d = std::abs(ldlt.vectorD()[i]);
        const real term = d > 0 ? y[i] / std::sqrt(d) : (y[i] == 0 ? 0 : std::numeric_limits<real>::infinity());
        twice += term * term;
    }
    return twice;
}

// The seed's clamp, 10 times the threshold, halves to the threshold in log2(10) s.
constexpr real kMaxSleepDelay = 3.321928094887362;

// A body whose average is capped at 2^delay thresholds sleeps `delay` seconds after it stops.
real movingMotionCap(real sleepDelay) { return std::min(real(10), std::exp2(sleepDelay)); }

void validateSettings(const char *function, const WorldSettings &s) {
    using namespace detail;
    requireFinite(function, "gravity", s.gravity);
    if (s.velocityIterations < 1 || s.velocityIterations > 10000)
        refuse(function, "velocityIterations", "must be in [1, 10000], got " + std::to_string(s.velocityIterations));
    if (s.positionIterations < 0 || s.positionIterations > 10000)
        refuse(function, "positionIterations", "must be in [0, 10000], got " + std::to_string(s.positionIterations));
    if (s.substeps < 1 || s.substeps > 1000)
        refuse(function, "substeps", "must be in [1, 1000], got " + std::to_string(s.substeps));
    if (s.debug.restingSubsteps < 0 || s.debug.restingSubsteps > s.substeps)
        refuse(function, "restingSubsteps",
               "must be in [0, substeps = " + std::to_string(s.substeps) + "], got " + std::to_string(s.debug.restingSubsteps));
    if (s.debug.restingIterations < 1 || s.debug.restingIterations > 10000)
        refuse(function, "restingIterations", "must be in [1, 10000], got " + std::to_string(s.debug.restingIterations));
    requirePositive(function, "sleepEpsilon", s.sleepEpsilon);
    if (!(s.sleepDelay >= 0 && s.sleepDelay <= kMaxSleepDelay))
        refuse(function, "sleepDelay", "must be in [0, log2(10) = 3.32], got " + show(s.sleepDelay));
    requireNonNegative(function, "penetrationSlop", s.penetrationSlop);
    if (!(s.penetrationRecovery > 0 && s.penetrationRecovery <= 1))
        refuse(function, "penetrationRecovery", "must be in (0, 1], got " + show(s.penetrationRecovery));
    requireNonNegative(function, "restitutionThreshold", s.restitutionThreshold);
    requireNonNegative(function, "speculativeDistance", s.speculativeDistance);
    requireNonNegative(function, "manifoldReuseTolerance", s.debug.manifoldReuseTolerance);
    const int integrator = static_cast<int>(s.integrator);
    if (s.maxPairs < 1) refuse(function, "maxPairs", "must be >= 1, got " + std::to_string(s.maxPairs));
    if (s.threads < 1 || s.threads > 64)
        refuse(function, "threads", "must be in [1, 64], got " + std::to_string(s.threads));
    if (s.integrator != Integrator::NewtonEuler && s.integrator != Integrator::NewtonEulerGyroscopic &&
        s.integrator != Integrator::NewtonEulerImplicit && s.integrator != Integrator::MomentumConserving)
        refuse(function, "integrator", "is not an Integrator, got " + std::to_string(integrator));
    if (!(s.explicitSpringLimit > 0))
        refuse(function, "explicitSpringLimit", "must be > 0, got " + show(s.explicitSpringLimit));
}

// Bodies whose bounding radius is below this have their sleep threshold scaled with their
// size, m: a 0.25 m ball and anything larger keep WorldSettings::sleepEpsilon.
constexpr real kSleepScaleRadius = 0.25;

// A body's sleep threshold (RigidBody::setSleepEpsilon), (m/s)^2 + (rad/s)^2: the world's
// `epsilon`, times (R / kSleepScaleRadius)^2 below that radius, so that a small body must
// move as many of its own sizes per second as a 0.25 m ball to stay awake (a 5 cm box
// sliding at 5 cm/s, under the world threshold's 0.1 m/s, stays awake). A plane (bounding
// radius 0) keeps the world's.
real sleepEpsilonFor(real epsilon, real boundingRadius) {
    if (!(boundingRadius > 0 && boundingRadius < kSleepScaleRadius)) return epsilon;
    const real scale = boundingRadius / kSleepScaleRadius;
    return epsilon * scale * scale;
}

RotationStep rotationStep(const WorldSettings &s) {
    return s.integrator == Integrator::MomentumConserving ? RotationStep::MomentumConserving : RotationStep::Seed;
}

// Builds the RigidBody of a settings struct; throws (nothing else changed) on bad input.
RigidBody makeBody(const char *function, const BodySettings &s, const detail::CollisionShape &shape,
                   const WorldSettings &world) {
    using namespace detail;
    requirePlace(function, "position", s.position);
    requireFinite(function, "velocity", s.velocity);
    requireFinite(function, "rotation", s.rotation);
    requireFinite(function, "orientation", s.orientation);
    requireUnit(function, "linearDamping", s.linearDamping);
    requireUnit(function, "angularDamping", s.angularDamping);
    requireNonNegative(function, "material.friction", s.material.friction);
    requireUnit(function, "material.restitution", s.material.restitution);
    requireNonNegative(function, "material.rollingFriction", s.material.rollingFriction);
    requireNonNegative(function, "material.spinningFriction", s.material.spinningFriction);

    RigidBody body;
    body.setSleepEpsilon(sleepEpsilonFor(world.sleepEpsilon, shape.boundingRadius()));
    body.setAwake(true);  // the sleep average starts at twice this body's threshold
    body.setMovingSleepAverageCap(movingMotionCap(world.sleepDelay));
    body.setPosition(s.position);
    body.setOrientation(s.orientation);
    const Motion motion = s.motion;
    if (motion != Motion::Dynamic) {
        // Infinite mass, no damping: a kinematic body keeps the velocities it is given.
        body.setInverseMass(0);
        body.setAwake(false);
        if (motion == Motion::Kinematic) {
            body.setVelocity(s.velocity);
            body.setRotation(s.rotation);
        }
        return body;
    }
    body.setDamping(s.linearDamping, s.angularDamping);
    const Matrix3 inertia = s.inertia ? *s.inertia : withMomentFloor(shape.unitInertia() * s.mass);
    requireSolvableMass(function, s.mass, inertia, shape.boundingRadius());
    if (s.inertia && shape.volume() > 0) requireInertiaNearShape(function, inertia, shape.unitInertia() * s.mass);
    try {
        body.setInertiaTensor(inertia);
    } catch (const std::invalid_argument &) {
        std::ostringstream shown;
        shown << "[" << inertia.row(0) << "; " << inertia.row(1) << "; " << inertia.row(2) << "]";
        refuse(function, "inertia", "must be finite, symmetric and positive definite, got " + shown.str());
    }
    body.setMass(s.mass);
    body.setVelocity(freeLinear(s.lockedAxes, s.velocity));
    body.setRotation(freeAngular(s.lockedAxes, s.rotation));
    requireGravityScale(function, "gravityScale", s.gravityScale, world.gravity);
    body.setAcceleration(world.gravity * s.gravityScale);
    body.setRotationStep(rotationStep(world));
    body.setCanSleep(s.canSleep);
    if (!s.awake) body.setAwake(false);
    return body;
}

// How a body of `settings` moves; refuses (nothing changed) a taken name, a static body
// set kinematic, or a plane or mesh that is not static.
Motion checkedMotion(const char *function, const BodySettings &settings,
                     const std::unordered_map<std::string, std::uint32_t> &names) {
    if (!settings.name.empty() && names.count(settings.name))
        detail::refuse(function, "name", "must be unique, \"" + settings.name + "\" is already taken");
    const Motion motion = settings.motion;
    const bool staticOnly = settings.shape.type == ShapeType::Plane || settings.shape.type == ShapeType::Mesh ||
                            settings.shape.type == ShapeType::Heightfield;
    if (staticOnly && motion != Motion::Static)
        detail::refuse(function, "shape.type",
                       std::string("\"") + shapeTypeName(settings.shape.type) + "\" is for static bodies only");
    return motion;
}

// The compiled `shape`; refuses (nothing changed) one that is not valid or reaches beyond
// 1e12 m from its origin.
std::shared_ptr<const detail::CollisionShape> checkedShape(const char *function, const Shape &shape) {
    std::shared_ptr<const detail::CollisionShape> compiled;
    try {
        compiled = detail::compileShape(shape);
    } catch (const InvalidArgument &e) {
        throw InvalidArgument(function, e.field(), e.problem());
    }
    if (!(compiled->boundingRadius() <= detail::kMaxCoordinate))
        detail::refuse(function, "shape", "must fit within 1e12 m of its origin, got a shape reaching " +
                                              detail::show(compiled->boundingRadius()) + " m from it");
    return compiled;
}

// Refuses (nothing changed) a layer outside [0, 31], a non-finite surface velocity or a
// one-way direction that is not finite and non-zero.
void checkFilterAndRules(const char *function, const BodySettings &settings) {
    if (settings.layer < 0 || settings.layer > 31)
        detail::refuse(function, "layer", "must be in [0, 31], got " + std::to_string(settings.layer));
    detail::requireFinite(function, "surfaceVelocity", settings.surfaceVelocity);
    if (settings.oneWay && (!settings.oneWay->allFinite() || settings.oneWay->isZero(0)))
        detail::refuse(function, "oneWay", "must be finite and not zero, got " + detail::show(*settings.oneWay));
}

// Fills the record `r` of a new body of `settings` moving as `motion`, out of every tree.
void fillRecord(detail::BodyRecord &r, const BodySettings &settings, Motion motion, const RigidBody &body,
                const std::shared_ptr<const detail::CollisionShape> &shape) {
    r.body = body;
    r.shape = shape;
    r.name = settings.name;
    r.material = settings.material;
    r.alive = true;
    r.immovable = motion != Motion::Dynamic;
    r.kinematic = motion == Motion::Kinematic;
    r.moving = false;
    r.isPlane = settings.shape.type == ShapeType::Plane;
    r.ccd = settings.ccd && motion == Motion::Dynamic && !settings.sensor;
    r.core = r.ccd ? detail::makeCore(detail::sweptShape(*shape)) : nullptr;
    r.isolated = false;
    r.simulated = false;
    r.tree = Tree::None;
    r.sleepingIsland = -1;
    r.island = -1;
    r.solverIndex = 0;
    r.awakeSlot = -1;
    r.boundingRadius = shape->boundingRadius();
    r.layer = settings.layer;
    r.collidesWith = settings.collidesWith;
    r.gravityScale = motion == Motion::Dynamic ? settings.gravityScale : 1;
    r.locked = motion == Motion::Dynamic ? settings.lockedAxes : LockedAxes();
    r.surfaceVelocity = settings.surfaceVelocity;
    r.userData = settings.userData;
    r.oneWay = settings.oneWay ? Vector3(settings.oneWay->normalized()) : Vector3(Vector3::Zero());
    r.sensor = settings.sensor;
}

// Counts the new body `index` in the store's tallies, its order and its names.
void countBody(detail::BodyStore &bodies, std::uint32_t index) {
    detail::BodyRecord &r = bodies[index];
    r.rank = bodies.nextRank++;
    bodies.lockedCount += r.locked.any();
    bodies.ruledCount += !r.surfaceVelocity.isZero(0) || !r.oneWay.isZero(0);
    if (r.layer != 0 || r.collidesWith != kAllLayers) ++bodies.filteredCount;
    bodies.sensorCount += r.sensor;
    bodies.roundCount += detail::mayBeRound(*r.shape);
    bodies.order.push_back(index);
    if (!r.name.empty()) bodies.names.emplace(r.name, index);
}

// Puts the new body `index` where collision detection finds it: the planes, or the
// broadphase tree of its motion (awake, asleep in an island of its own, or static).
void enterCollision(detail::WorldState &w, std::uint32_t index) {
    detail::BodyRecord &r = w.bodies[index];
    if (r.isPlane) {
        w.bodies.planes.push_back(index);
        r.object.reset();
        return;
    }
    r.object = std::make_unique<detail::BodyObject>(r.shape->geometry(), r.body.getTransform());
    r.object->setUserData(reinterpret_cast<void *>(static_cast<std::uintptr_t>(index)));
    r.object->place(r.body.getTransform(), detail::kBroadphaseMargin);
    if (r.kinematic) {
        w.bodies.kinematic.push_back(index);
        w.setTree(index, Tree::Static);  // until its first step in motion (KinematicBodies)
    } else if (r.immovable) {
        w.setTree(index, Tree::Static);
    } else if (r.body.getAwake()) {
        w.setTree(index, Tree::Awake);
        w.bodies.updateAwakeList(index);
    } else {
        const std::uint32_t self = index;
        w.sleepIsland(&self, 1, false);
    }
}

}  // namespace

// --- Construction ---------------------------------------------------------------------

World::World(const WorldSettings &settings) {
    validateSettings("World::World", settings);
    impl_ = std::make_unique<Impl>(settings);
}

World::~World() = default;
World::World(World &&) noexcept = default;
World &World::operator=(World &&) noexcept = default;

const WorldSettings &World::settings() const { return impl_->settings; }

void World::setSettings(const WorldSettings &settings) {
    validateSettings("World::setSettings", settings);
    for (std::uint32_t index : impl_->bodies.order) {
        const detail::BodyRecord &r = impl_->bodies[index];
        if (!r.immovable) detail::requireGravityScale("World::setSettings", "gravity", r.gravityScale, settings.gravity);
    }
    impl_->settings = settings;
    for (std::uint32_t index : impl_->bodies.order) {
        detail::BodyRecord &r = impl_->bodies[index];
        r.seen.renew(r.body, impl_->stepCount + 1);  // a test's answer may change with the settings
        r.body.setSleepEpsilon(sleepEpsilonFor(settings.sleepEpsilon, r.boundingRadius));
        r.body.setMovingSleepAverageCap(movingMotionCap(settings.sleepDelay));
        if (r.immovable) continue;
        r.body.setAcceleration(settings.gravity * r.gravityScale);
        r.body.setRotationStep(rotationStep(settings));
        impl_->wake(index);
    }
}

// --- Bodies ---------------------------------------------------------------------------

BodyId World::addBody(const BodySettings &settings) {
    static const char *function = "World::addBody";
    Impl &w = *impl_;
    const Motion motion = checkedMotion(function, settings, w.bodies.names);
    const std::optional<std::uint32_t> known = w.shapes.find(settings.shape);
    const std::shared_ptr<const detail::CollisionShape> shape =
        known ? w.shapes[*known] : checkedShape(function, settings.shape);
    checkFilterAndRules(function, settings);
    RigidBody body = makeBody(function, settings, *shape, w.settings);
    if (shape->isCompound()) body.setPosition(body.getPosition() + detail::frameToCentre(body, *shape));
    if (settings.shape.type != ShapeType::Plane)
        detail::requireReach(function, "position", body.getPosition(), shape->boundingRadius());

    // Nothing below throws on user input: the world changes only from here on.
    const std::uint32_t index = detail::takeSlot(w.bodies.records, w.bodies.free);
    detail::BodyRecord &r = w.bodies[index];
    fillRecord(r, settings, motion, body, shape);
    r.seen.renew(r.body, w.stepCount + 1);
    r.shapeIndex = known ? *known : w.shapes.add(shape);
    countBody(w.bodies, index);
    enterCollision(w, index);
    w.sensors.added(w.bodies, index);
    return w.bodies.idOf(index);
}

void World::removeBody(BodyId id) {
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.record(id, "World::removeBody");
    if (w.characters.owns(id))
        detail::refuse("World::removeBody", "id", "names a character's capsule; removeCharacter removes it");
    const std::uint32_t index = id.index;
    // Bodies touching the removed one lose their support: wake them (and their islands).
    for (std::uint32_t p : r.pairs) {
        const detail::PairState &pair = w.contacts.pairs[p];
        const std::uint32_t other = pair.a == index ? pair.b : pair.a;
        if (pair.touching() && !w.bodies[other].immovable) w.wake(other);
    }
    w.contacts.removePairsOf(w.bodies, index);
    w.joints.removeJointsOf(w.bodies, detail::BodyTransitions(w), id);
    w.leaveFilters(index);
    for (detail::SpringRecord &s : w.springs) {
        if (!s.alive) continue;
        const bool onA = s.settings.a == id;
        const bool onB = s.settings.b && *s.settings.b == id;
        if (!onA && !onB) continue;
        const BodyId other = onA ? s.settings.b.value_or(BodyId()) : s.settings.a;
        if (contains(other) && !w.bodies[other.index].immovable) w.wake(other.index);
        s.alive = false;
        ++s.generation;
        w.springs.free.push_back(static_cast<std::uint32_t>(&s - w.springs.records.data()));
    }
    if (r.sleepingIsland >= 0) {
        // The rest of its sleeping island wakes: it may have rested on this body.
        const std::vector<std::uint32_t> members = w.islands.sleeping[r.sleepingIsland];
        for (std::uint32_t m : members)
            if (m != index) w.wake(m);
    }
    if (r.kinematic) w.bodies.kinematic.erase(std::find(w.bodies.kinematic.begin(), w.bodies.kinematic.end(), index));
    r.kinematic = false;
    r.moving = false;
    if (r.layer != 0 || r.collidesWith != kAllLayers) --w.bodies.filteredCount;
    w.bodies.roundCount -= detail::mayBeRound(*r.shape);
    r.layer = 0;
    r.collidesWith = kAllLayers;
    w.bodies.lockedCount -= r.locked.any();
    r.locked = LockedAxes();
    w.bodies.ruledCount -= !r.surfaceVelocity.isZero(0) || !r.oneWay.isZero(0);
    r.surfaceVelocity = Vector3::Zero();
    r.oneWay = Vector3::Zero();
    if (r.isPlane) w.bodies.planes.erase(std::find(w.bodies.planes.begin(), w.bodies.planes.end(), index));
    w.setTree(index, Tree::None);
    if (r.sleepingIsland >= 0) {
        w.islands.freeSleeping.push_back(r.sleepingIsland);
        w.islands.sleeping[r.sleepingIsland].clear();
    }
    if (!r.name.empty()) w.bodies.names.erase(r.name);
    w.bodies.order.erase(std::find(w.bodies.order.begin(), w.bodies.order.end(), index));
    r.object.reset();
    r.shape.reset();
    r.core.reset();
    r.alive = false;
    r.held = false;
    w.bodies.updateAwakeList(index);
    if (r.isolated) --w.bodies.isolatedCount;
    ++r.generation;
    w.bodies.free.push_back(index);
    for (std::uint32_t m : w.bodies.order) w.bodies[m].island = -1;
}

bool World::contains(BodyId id) const {
    return impl_->bodies.contains(id);
}

std::vector<BodyId> World::bodies() const {
    std::vector<BodyId> out;
    out.reserve(impl_->bodies.order.size());
    for (std::uint32_t index : impl_->bodies.order) out.push_back(impl_->bodies.idOf(index));
    return out;
}

void World::bodies(std::vector<BodyId> &out) const {
    out.clear();
    for (std::uint32_t index : impl_->bodies.order) out.push_back(impl_->bodies.idOf(index));
}

std::size_t World::bodyCount() const { return impl_->bodies.order.size(); }

std::optional<BodyId> World::findBody(const std::string &name) const {
    const auto found = impl_->bodies.names.find(name);
    if (found == impl_->bodies.names.end()) return std::nullopt;
    return impl_->bodies.idOf(found->second);
}

const RigidBody &World::body(BodyId id) const { return impl_->bodies.record(id, "World::body").body; }
const std::string &World::name(BodyId id) const { return impl_->bodies.record(id, "World::name").name; }
const Shape &World::shape(BodyId id) const { return impl_->bodies.record(id, "World::shape").shape->shape(); }
Motion World::motion(BodyId id) const {
    const detail::BodyRecord &r = impl_->bodies.record(id, "World::motion");
    return r.kinematic ? Motion::Kinematic : r.immovable ? Motion::Static : Motion::Dynamic;
}
const Material &World::material(BodyId id) const { return impl_->bodies.record(id, "World::material").material; }

// --- Changing bodies --------------------------------------------------------------------

void World::setPosition(BodyId id, const Vector3 &position) {
    static const char *function = "World::setPosition";
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.changeableRecord(id, function);
    detail::requirePlace(function, "position", position);
    if (r.isPlane) detail::refuse(function, "id", "names a plane; planes are placed by their offset");
    detail::requireReach(function, "position", position, r.boundingRadius);
    r.body.setPosition(position);
    w.refreshCollisionObject(id.index);
}

void World::setOrientation(BodyId id, const Quaternion &orientation) {
    static const char *function = "World::setOrientation";
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.changeableRecord(id, function);
    detail::requireFinite(function, "orientation", orientation);
    if (r.isPlane) detail::refuse(function, "id", "names a plane; planes are placed by their normal");
    r.body.setOrientation(orientation);
    w.refreshCollisionObject(id.index);
}

void World::setVelocity(BodyId id, const Vector3 &velocity) {
    static const char *function = "World::setVelocity";
    detail::BodyRecord &r = impl_->bodies.movableRecord(id, function);
    detail::requireFinite(function, "velocity", velocity);
    impl_->wake(id.index);
    r.body.setVelocity(velocity);
    r.seen.look(r.body, impl_->stepCount + 1);
    if (r.kinematic && detail::movesAt(velocity, r.body.getRotation()))
        detail::KinematicBodies::startMoving(impl_->bodies, impl_->contacts.pairs, detail::BodyTransitions(*impl_), id.index);
}

void World::setRotation(BodyId id, const Vector3 &rotation) {
    static const char *function = "World::setRotation";
    detail::BodyRecord &r = impl_->bodies.movableRecord(id, function);
    detail::requireFinite(function, "rotation", rotation);
    impl_->wake(id.index);
    r.body.setRotation(rotation);
    r.seen.look(r.body, impl_->stepCount + 1);
    if (r.kinematic && detail::movesAt(r.body.getVelocity(), rotation))
        detail::KinematicBodies::startMoving(impl_->bodies, impl_->contacts.pairs, detail::BodyTransitions(*impl_), id.index);
}

void World::moveKinematic(BodyId id, const Vector3 &targetPosition, const Quaternion &targetOrientation, real dt) {
    static const char *function = "World::moveKinematic";
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.record(id, function);
    if (!r.kinematic)
        detail::refuse(function, "id", std::string("names a ") + (r.immovable ? "static" : "dynamic") +
                                           " body; only kinematic bodies are moved to a pose");
    detail::requirePlace(function, "targetPosition", targetPosition);
    if (!targetOrientation.coeffs().allFinite()) detail::refuse(function, "targetOrientation", "must be finite");
    if (!std::isfinite(dt) || !(dt > 0)) detail::refuse(function, "dt", "must be finite and > 0, got " + detail::show(dt));
    const Quaternion target = targetOrientation.coeffs().isZero(0) ? Quaternion::Identity() : targetOrientation.normalized();
    const Vector3 velocity = (targetPosition - r.body.getPosition()) / dt;
    // The shorter turn from the current orientation to the target, as an angular velocity.
    Quaternion turn = target * r.body.getOrientation().conjugate();
    if (turn.w() < 0) turn.coeffs() = -turn.coeffs();
    const Eigen::AngleAxis<real> axisAngle(turn);
    const Vector3 rotation = axisAngle.angle() > 0 ? Vector3(axisAngle.axis() * (axisAngle.angle() / dt)) : Vector3::Zero();
    if (!velocity.allFinite() || !rotation.allFinite())
        detail::refuse(function, "dt", "gives a non-finite velocity, got " + detail::show(dt));
    r.body.setVelocity(velocity);
    r.body.setRotation(rotation);
    r.seen.look(r.body, w.stepCount + 1);
    if (detail::movesAt(velocity, rotation))
        detail::KinematicBodies::startMoving(w.bodies, w.contacts.pairs, detail::BodyTransitions(w), id.index);
}

void World::applyImpulse(BodyId id, const Vector3 &impulse) {
    static const char *function = "World::applyImpulse";
    detail::BodyRecord &r = impl_->bodies.dynamicRecord(id, function);
    detail::requireFinite(function, "impulse", impulse);
    const Vector3 dv = impulse * r.body.getInverseMass();
    if (!dv.allFinite() || !(r.body.getVelocity() + dv).allFinite())
        detail::refuse(function, "impulse", "would make the velocity non-finite, got " + detail::show(impulse));
    impl_->wake(id.index);
    r.body.addVelocity(dv);
}

void World::applyImpulse(BodyId id, const Vector3 &impulse, const Vector3 &point) {
    static const char *function = "World::applyImpulse";
    detail::BodyRecord &r = impl_->bodies.dynamicRecord(id, function);
    detail::requireFinite(function, "impulse", impulse);
    detail::requireFinite(function, "point", point);
    const Vector3 dv = impulse * r.body.getInverseMass();
    const Vector3 dw = r.body.getInverseInertiaTensorWorld() * (point - r.body.getPosition()).cross(impulse);
    if (!(r.body.getVelocity() + dv).allFinite() || !(r.body.getRotation() + dw).allFinite())
        detail::refuse(function, "impulse", "would make the velocity non-finite, got " + detail::show(impulse) +
                                                " at " + detail::show(point));
    impl_->wake(id.index);
    r.body.addVelocity(dv);
    r.body.addRotation(dw);
}

void World::addForce(BodyId id, const Vector3 &force) {
    static const char *function = "World::addForce";
    detail::BodyRecord &r = impl_->bodies.dynamicRecord(id, function);
    detail::requireFinite(function, "force", force);
    impl_->wake(id.index);
    r.body.addForce(force);
}

void World::addForceAtPoint(BodyId id, const Vector3 &force, const Vector3 &point) {
    static const char *function = "World::addForceAtPoint";
    detail::BodyRecord &r = impl_->bodies.dynamicRecord(id, function);
    detail::requireFinite(function, "force", force);
    detail::requireFinite(function, "point", point);
    impl_->wake(id.index);
    r.body.addForceAtPoint(force, point);
}

void World::addTorque(BodyId id, const Vector3 &torque) {
    static const char *function = "World::addTorque";
    detail::BodyRecord &r = impl_->bodies.dynamicRecord(id, function);
    detail::requireFinite(function, "torque", torque);
    impl_->wake(id.index);
    r.body.addTorque(torque);
}

void World::setAwake(BodyId id, bool awake) {
    static const char *function = "World::setAwake";
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.dynamicRecord(id, function);
    if (awake) {
        w.wake(id.index);
        return;
    }
    if (!r.body.getAwake()) return;
    if (r.island >= 0) {
        w.sleepIsland(w.islands.members(r.island), w.islands.size(r.island));
    } else {
        const std::uint32_t self = id.index;
        w.sleepIsland(&self, 1);
    }
}

void World::setCanSleep(BodyId id, bool canSleep) {
    detail::BodyRecord &r = impl_->bodies.dynamicRecord(id, "World::setCanSleep");
    if (!canSleep) impl_->wake(id.index);
    r.body.setCanSleep(canSleep);
}

void World::setCollisionFilter(BodyId id, int layer, std::uint32_t collidesWith) {
    static const char *function = "World::setCollisionFilter";
    Impl &w = *impl_;
    detail::BodyRecord &r = w.bodies.record(id, function);
    if (layer < 0 || layer > 31) detail::refuse(function, "layer", "must be in [0, 31], got " + std::to_string(layer));
    const bool wasFiltered = r.layer != 0 || r.collidesWith != kAllLayers;
    r.layer = layer;
    r.collidesWith = collidesWith;
    w.bodies.filteredCount += (r.layer != 0 || r.collidesWith != kAllLayers) - wasFiltered;
    // Pairs the filter now forbids go; a body that lost a support, or may meet new ones,
    // must be simulated to find out.
    for (std::size_t k = r.pairs.size(); k-- > 0;) {
        const std::uint32_t p = r.pairs[k];
        const detail::PairState &pair = w.contacts.pairs[p];
        const std::uint32_t other = pair.a == id.index ? pair.b : pair.a;
        if (w.bodies.collide(pair.a, pair.b)) continue;
        if (pair.touching() && !w.bodies[other].immovable) w.wake(other);
        w.contacts.removePair(w.bodies, p);
    }
    w.filterChanged(id.index);
    if (!r.immovable) w.wake(id.index);
}

void World::setMaterial(BodyId id, const Material &material) {
    static const char *function = "World::setMaterial";
    detail::BodyRecord &r = impl_->bodies.record(id, function);
    detail::requireNonNegative(function, "friction", material.friction);
    detail::requireUnit(function, "restitution", material.restitution);
    detail::requireNonNegative(function, "rollingFriction", material.rollingFriction);
    detail::requireNonNegative(function, "spinningFriction", material.spinningFriction);
    r.material = material;
}

// --- Springs ----------------------------------------------------------------------------

SpringId World::addSpring(const SpringSettings &s) {
    static const char *function = "World::addSpring";
    Impl &w = *impl_;
    w.bodies.record(s.a, function);
    if (s.b) w.bodies.record(*s.b, function);
    detail::requirePlace(function, "aPoint", s.aPoint);
    detail::requirePlace(function, "bPoint", s.bPoint);
    detail::requirePositive(function, "stiffness", s.stiffness);
    detail::requireNonNegative(function, "damping", s.damping);
    detail::requireNonNegative(function, "restLength", s.restLength);
    if (s.b && *s.b == s.a) detail::refuse(function, "b", "must differ from a");
    if (s.force != SpringForce::Automatic && s.force != SpringForce::Explicit)
        detail::refuse(function, "force",
                       "must be Automatic or Explicit, got " + std::to_string(static_cast<int>(s.force)));
    const std::uint32_t index = detail::takeSlot(w.springs.records, w.springs.free);
    detail::SpringRecord &r = w.springs.records[index];
    r.settings = s;
    r.alive = true;
    r.implicitForce.setZero();
    if (!w.bodies[s.a.index].immovable) w.wake(s.a.index);
    if (s.b && !w.bodies[s.b->index].immovable) w.wake(s.b->index);
    return {index, r.generation};
}

void World::removeSpring(SpringId id) {
    Impl &w = *impl_;
    if (id.index >= w.springs.records.size() || !w.springs.records[id.index].alive || w.springs.records[id.index].generation != id.generation)
        detail::refuse("World::removeSpring", "id", "does not name a spring of this world");
    detail::SpringRecord &r = w.springs.records[id.index];
    const BodyId a = r.settings.a;
    const std::optional<BodyId> b = r.settings.b;
    detail::freeSlot(w.springs.records, w.springs.free, id.index);
    if (contains(a) && !w.bodies[a.index].immovable) w.wake(a.index);
    if (b && contains(*b) && !w.bodies[b->index].immovable) w.wake(b->index);
}

// --- Stepping ---------------------------------------------------------------------------

void World::step(real dt) {
    if (!(dt >= kMinStep && dt <= kMaxStep))
        detail::refuse("World::step", "dt",
                       "must be finite and in [1e-06, 1] s (kMinStep, kMaxStep; take a longer span as several "
                       "steps), got " + detail::show(dt));
    impl_->step(dt);
}

const StepStats &World::stats() const { return impl_->stats; }

const WorldEvents &World::events() const { return impl_->events.events; }

real World::kineticEnergy() const {
    real twice = 0;
    for (std::uint32_t index : impl_->bodies.order) {
        const detail::BodyRecord &r = impl_->bodies[index];
        if (!r.immovable) twice += twiceKineticEnergy(r.body);
    }
    return twice / 2;
}

}  // namespace cyclone
