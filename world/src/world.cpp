// The World's public calls: validation, bodies and springs, and the wake rules.
#include <cmath>
#include <sstream>

#include "ccd.h"
#include "validation.h"
#include "world_impl.h"

namespace cyclone {

using detail::Tree;

namespace {

real boundingRadius(const Shape &shape, const detail::CollisionShape &compiled) {
    switch (shape.type) {
        case ShapeType::Box: return shape.halfExtents.norm();
        case ShapeType::Sphere: return shape.radius;
        case ShapeType::Capsule: return shape.radius + shape.length / 2;
        case ShapeType::Cylinder: return std::hypot(shape.radius, shape.length / 2);
        case ShapeType::Convex:
        case ShapeType::Mesh: {
            real r = 0;
            for (const Vector3 &v : compiled.vertices()) r = std::max(r, v.norm());
            return r;
        }
        case ShapeType::Plane: break;
    }
    return 0;
}

void validateSettings(const char *function, const WorldSettings &s) {
    using namespace detail;
    requireFinite(function, "gravity", s.gravity);
    if (s.velocityIterations < 1 || s.velocityIterations > 10000)
        refuse(function, "velocityIterations", "must be in [1, 10000], got " + std::to_string(s.velocityIterations));
    if (s.positionIterations < 0 || s.positionIterations > 10000)
        refuse(function, "positionIterations", "must be in [0, 10000], got " + std::to_string(s.positionIterations));
    if (s.substeps < 1 || s.substeps > 1000)
        refuse(function, "substeps", "must be in [1, 1000], got " + std::to_string(s.substeps));
    requirePositive(function, "sleepEpsilon", s.sleepEpsilon);
    requireNonNegative(function, "penetrationSlop", s.penetrationSlop);
    if (!(s.penetrationRecovery > 0 && s.penetrationRecovery <= 1))
        refuse(function, "penetrationRecovery", "must be in (0, 1], got " + show(s.penetrationRecovery));
    requireNonNegative(function, "restitutionThreshold", s.restitutionThreshold);
    requireNonNegative(function, "contactHertz", s.contactHertz);
    requireNonNegative(function, "contactDampingRatio", s.contactDampingRatio);
    requirePositive(function, "maxPushVelocity", s.maxPushVelocity);
    requireNonNegative(function, "speculativeDistance", s.speculativeDistance);
    requireNonNegative(function, "manifoldReuseTolerance", s.manifoldReuseTolerance);
    if (s.threads < 1 || s.threads > 64)
        refuse(function, "threads", "must be in [1, 64], got " + std::to_string(s.threads));
    if (s.integrator != Integrator::NewtonEuler && s.integrator != Integrator::NewtonEulerGyroscopic &&
        s.integrator != Integrator::NewtonEulerImplicit && s.integrator != Integrator::MomentumConserving)
        refuse(function, "integrator",
               "must be an Integrator value, got " + std::to_string(static_cast<int>(s.integrator)));
    if (!(s.explicitSpringLimit > 0))
        refuse(function, "explicitSpringLimit", "must be > 0, got " + show(s.explicitSpringLimit));
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
    if (!s.orientation.coeffs().allFinite()) refuse(function, "orientation", "must be finite");
    requireUnit(function, "linearDamping", s.linearDamping);
    requireUnit(function, "angularDamping", s.angularDamping);
    requireNonNegative(function, "material.friction", s.material.friction);
    requireUnit(function, "material.restitution", s.material.restitution);

    RigidBody body;
    body.setSleepEpsilon(world.sleepEpsilon);
    body.setPosition(s.position);
    body.setOrientation(s.orientation);
    body.setDamping(s.linearDamping, s.angularDamping);
    if (s.isStatic) {
        body.setInverseMass(0);
        body.setAwake(false);
        return body;
    }
    requirePositive(function, "mass", s.mass);
    const Matrix3 inertia = s.inertia ? *s.inertia : Matrix3(shape.unitInertia() * s.mass);
    try {
        body.setInertiaTensor(inertia);
    } catch (const std::invalid_argument &) {
        std::ostringstream shown;
        shown << "[" << inertia.row(0) << "; " << inertia.row(1) << "; " << inertia.row(2) << "]";
        refuse(function, "inertia", "must be finite, symmetric and positive definite, got " + shown.str());
    }
    body.setMass(s.mass);
    body.setVelocity(s.velocity);
    body.setRotation(s.rotation);
    body.setAcceleration(world.gravity);
    body.setRotationStep(rotationStep(world));
    body.setCanSleep(s.canSleep);
    if (!s.awake) body.setAwake(false);
    return body;
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
    impl_->settings = settings;
    for (std::uint32_t index : impl_->order) {
        BodyRecord &r = impl_->bodies[index];
        r.body.setSleepEpsilon(settings.sleepEpsilon);
        if (r.isStatic) continue;
        r.body.setAcceleration(settings.gravity);
        r.body.setRotationStep(rotationStep(settings));
        impl_->wake(index);
    }
}

// --- Bodies ---------------------------------------------------------------------------

BodyId World::addBody(const BodySettings &settings) {
    static const char *function = "World::addBody";
    Impl &w = *impl_;
    if (!settings.name.empty() && w.names.count(settings.name))
        detail::refuse(function, "name", "must be unique, \"" + settings.name + "\" is already taken");
    const bool staticOnly = settings.shape.type == ShapeType::Plane || settings.shape.type == ShapeType::Mesh;
    if (staticOnly && !settings.isStatic)
        detail::refuse(function, "shape.type",
                       std::string("\"") + shapeTypeName(settings.shape.type) + "\" is for static bodies only");
    std::shared_ptr<const detail::CollisionShape> shape;
    try {
        shape = detail::compileShape(settings.shape);
    } catch (const InvalidArgument &e) {
        throw InvalidArgument(function, e.field(), e.problem());
    }
    if (!(boundingRadius(settings.shape, *shape) <= detail::kMaxCoordinate))
        detail::refuse(function, "shape", "must fit within 1e30 m of its origin");
    RigidBody body = makeBody(function, settings, *shape, w.settings);

    // Nothing below throws on user input: the world changes only from here on.
    std::uint32_t index;
    if (!w.freeBodies.empty()) {
        index = w.freeBodies.back();
        w.freeBodies.pop_back();
    } else {
        index = static_cast<std::uint32_t>(w.bodies.size());
        w.bodies.emplace_back();
    }
    BodyRecord &r = w.bodies[index];
    r.body = body;
    r.shape = shape;
    r.name = settings.name;
    r.material = settings.material;
    r.alive = true;
    r.isStatic = settings.isStatic;
    r.isPlane = settings.shape.type == ShapeType::Plane;
    r.ccd = settings.ccd;
    r.core = settings.ccd && !settings.isStatic ? detail::makeCore(detail::sweptShape(*shape)) : nullptr;
    r.quarantined = false;
    r.simulated = false;
    r.tree = Tree::None;
    r.sleepingIsland = -1;
    r.island = -1;
    r.solverIndex = 0;
    r.awakeSlot = -1;
    r.rank = w.nextRank++;
    r.boundingRadius = boundingRadius(settings.shape, *shape);
    w.order.push_back(index);
    if (!r.name.empty()) w.names.emplace(r.name, index);

    if (r.isPlane) {
        w.planes.push_back(index);
        r.object.reset();
    } else {
        r.object = std::make_unique<detail::BodyObject>(shape->geometry(), r.body.getTransform());
        r.object->setUserData(reinterpret_cast<void *>(static_cast<std::uintptr_t>(index)));
        r.object->place(r.body.getTransform(), detail::kBroadphaseMargin);
        if (r.isStatic) {
            w.setTree(index, Tree::Static);
        } else if (r.body.getAwake()) {
            w.setTree(index, Tree::Awake);
            w.updateAwakeList(index);
        } else {
            const std::uint32_t self = index;
            w.sleepIsland(&self, 1, false);
        }
    }
    return w.idOf(index);
}

void World::removeBody(BodyId id) {
    Impl &w = *impl_;
    BodyRecord &r = w.record(id, "World::removeBody");
    const std::uint32_t index = id.index;
    // Bodies touching the removed one lose their support: wake them (and their islands).
    for (std::uint32_t p : r.pairs) {
        const detail::PairState &pair = w.pairs[p];
        const std::uint32_t other = pair.a == index ? pair.b : pair.a;
        if (pair.touching() && !w.bodies[other].isStatic) w.wake(other);
    }
    w.removePairsOf(index);
    for (SpringRecord &s : w.springs) {
        if (!s.alive) continue;
        const bool onA = s.settings.a == id;
        const bool onB = s.settings.b && *s.settings.b == id;
        if (!onA && !onB) continue;
        const BodyId other = onA ? s.settings.b.value_or(BodyId()) : s.settings.a;
        if (contains(other) && !w.bodies[other.index].isStatic) w.wake(other.index);
        s.alive = false;
        ++s.generation;
        w.freeSprings.push_back(static_cast<std::uint32_t>(&s - w.springs.data()));
    }
    if (r.sleepingIsland >= 0) {
        // The rest of its sleeping island wakes: it may have rested on this body.
        const std::vector<std::uint32_t> members = w.sleepingIslands[r.sleepingIsland];
        for (std::uint32_t m : members)
            if (m != index) w.wake(m);
    }
    if (r.isPlane) w.planes.erase(std::find(w.planes.begin(), w.planes.end(), index));
    w.setTree(index, Tree::None);
    if (r.sleepingIsland >= 0) {
        w.freeSleepingIslands.push_back(r.sleepingIsland);
        w.sleepingIslands[r.sleepingIsland].clear();
    }
    if (!r.name.empty()) w.names.erase(r.name);
    w.order.erase(std::find(w.order.begin(), w.order.end(), index));
    r.object.reset();
    r.shape.reset();
    r.core.reset();
    r.alive = false;
    w.updateAwakeList(index);
    if (r.quarantined) --w.quarantinedBodies;
    ++r.generation;
    w.freeBodies.push_back(index);
    for (std::uint32_t m : w.order) w.bodies[m].island = -1;
}

bool World::contains(BodyId id) const {
    return id.index < impl_->bodies.size() && impl_->bodies[id.index].alive &&
           impl_->bodies[id.index].generation == id.generation;
}

std::vector<BodyId> World::bodies() const {
    std::vector<BodyId> out;
    out.reserve(impl_->order.size());
    for (std::uint32_t index : impl_->order) out.push_back(impl_->idOf(index));
    return out;
}

void World::bodies(std::vector<BodyId> &out) const {
    out.clear();
    for (std::uint32_t index : impl_->order) out.push_back(impl_->idOf(index));
}

std::size_t World::bodyCount() const { return impl_->order.size(); }

std::optional<BodyId> World::findBody(const std::string &name) const {
    const auto found = impl_->names.find(name);
    if (found == impl_->names.end()) return std::nullopt;
    return impl_->idOf(found->second);
}

const RigidBody &World::body(BodyId id) const { return impl_->record(id, "World::body").body; }
const std::string &World::name(BodyId id) const { return impl_->record(id, "World::name").name; }
const Shape &World::shape(BodyId id) const { return impl_->record(id, "World::shape").shape->shape(); }
bool World::isStatic(BodyId id) const { return impl_->record(id, "World::isStatic").isStatic; }
const Material &World::material(BodyId id) const { return impl_->record(id, "World::material").material; }

// --- Changing bodies --------------------------------------------------------------------

void World::setPosition(BodyId id, const Vector3 &position) {
    static const char *function = "World::setPosition";
    Impl &w = *impl_;
    BodyRecord &r = w.record(id, function);
    detail::requirePlace(function, "position", position);
    if (r.isPlane) detail::refuse(function, "id", "names a plane; planes are placed by their offset");
    r.body.setPosition(position);
    w.refreshCollisionObject(id.index);
}

void World::setOrientation(BodyId id, const Quaternion &orientation) {
    static const char *function = "World::setOrientation";
    Impl &w = *impl_;
    BodyRecord &r = w.record(id, function);
    if (!orientation.coeffs().allFinite()) detail::refuse(function, "orientation", "must be finite");
    if (r.isPlane) detail::refuse(function, "id", "names a plane; planes are placed by their normal");
    r.body.setOrientation(orientation);
    w.refreshCollisionObject(id.index);
}

void World::setVelocity(BodyId id, const Vector3 &velocity) {
    static const char *function = "World::setVelocity";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "velocity", velocity);
    impl_->wake(id.index);
    r.body.setVelocity(velocity);
}

void World::setRotation(BodyId id, const Vector3 &rotation) {
    static const char *function = "World::setRotation";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "rotation", rotation);
    impl_->wake(id.index);
    r.body.setRotation(rotation);
}

void World::applyImpulse(BodyId id, const Vector3 &impulse) {
    static const char *function = "World::applyImpulse";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "impulse", impulse);
    impl_->wake(id.index);
    r.body.addVelocity(impulse * r.body.getInverseMass());
}

void World::applyImpulse(BodyId id, const Vector3 &impulse, const Vector3 &point) {
    static const char *function = "World::applyImpulse";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "impulse", impulse);
    detail::requireFinite(function, "point", point);
    const Vector3 dv = impulse * r.body.getInverseMass();
    const Vector3 dw = r.body.getInverseInertiaTensorWorld() * (point - r.body.getPosition()).cross(impulse);
    if (!dv.allFinite() || !dw.allFinite()) detail::refuse(function, "impulse", "gives a non-finite velocity");
    impl_->wake(id.index);
    r.body.addVelocity(dv);
    r.body.addRotation(dw);
}

void World::addForce(BodyId id, const Vector3 &force) {
    static const char *function = "World::addForce";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "force", force);
    impl_->wake(id.index);
    r.body.addForce(force);
}

void World::addForceAtPoint(BodyId id, const Vector3 &force, const Vector3 &point) {
    static const char *function = "World::addForceAtPoint";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "force", force);
    detail::requireFinite(function, "point", point);
    impl_->wake(id.index);
    r.body.addForceAtPoint(force, point);
}

void World::addTorque(BodyId id, const Vector3 &torque) {
    static const char *function = "World::addTorque";
    BodyRecord &r = impl_->dynamicRecord(id, function);
    detail::requireFinite(function, "torque", torque);
    impl_->wake(id.index);
    r.body.addTorque(torque);
}

void World::setAwake(BodyId id, bool awake) {
    static const char *function = "World::setAwake";
    Impl &w = *impl_;
    BodyRecord &r = w.dynamicRecord(id, function);
    if (awake) {
        w.wake(id.index);
        return;
    }
    if (!r.body.getAwake()) return;
    if (r.island >= 0) {
        const int start = w.islandStart[r.island];
        const int end = w.islandStart[r.island + 1];
        w.sleepIsland(w.islandBodies.data() + start, end - start);
    } else {
        const std::uint32_t self = id.index;
        w.sleepIsland(&self, 1);
    }
}

void World::setCanSleep(BodyId id, bool canSleep) {
    BodyRecord &r = impl_->dynamicRecord(id, "World::setCanSleep");
    if (!canSleep) impl_->wake(id.index);
    r.body.setCanSleep(canSleep);
}

void World::setMaterial(BodyId id, const Material &material) {
    static const char *function = "World::setMaterial";
    BodyRecord &r = impl_->record(id, function);
    detail::requireNonNegative(function, "friction", material.friction);
    detail::requireUnit(function, "restitution", material.restitution);
    r.material = material;
}

// --- Springs ----------------------------------------------------------------------------

SpringId World::addSpring(const SpringSettings &s) {
    static const char *function = "World::addSpring";
    Impl &w = *impl_;
    w.record(s.a, function);
    if (s.b) w.record(*s.b, function);
    detail::requireFinite(function, "aPoint", s.aPoint);
    detail::requireFinite(function, "bPoint", s.bPoint);
    detail::requirePositive(function, "stiffness", s.stiffness);
    detail::requireNonNegative(function, "damping", s.damping);
    detail::requireNonNegative(function, "restLength", s.restLength);
    if (s.b && *s.b == s.a) detail::refuse(function, "b", "must differ from a");
    if (s.force != SpringForce::Automatic && s.force != SpringForce::Explicit)
        detail::refuse(function, "force",
                       "must be Automatic or Explicit, got " + std::to_string(static_cast<int>(s.force)));
    std::uint32_t index;
    if (!w.freeSprings.empty()) {
        index = w.freeSprings.back();
        w.freeSprings.pop_back();
    } else {
        index = static_cast<std::uint32_t>(w.springs.size());
        w.springs.emplace_back();
    }
    SpringRecord &r = w.springs[index];
    r.settings = s;
    r.alive = true;
    r.implicitForce.setZero();
    if (!w.bodies[s.a.index].isStatic) w.wake(s.a.index);
    if (s.b && !w.bodies[s.b->index].isStatic) w.wake(s.b->index);
    return {index, r.generation};
}

void World::removeSpring(SpringId id) {
    Impl &w = *impl_;
    if (id.index >= w.springs.size() || !w.springs[id.index].alive || w.springs[id.index].generation != id.generation)
        detail::refuse("World::removeSpring", "id", "does not name a spring of this world");
    SpringRecord &r = w.springs[id.index];
    const BodyId a = r.settings.a;
    const std::optional<BodyId> b = r.settings.b;
    r.alive = false;
    ++r.generation;
    w.freeSprings.push_back(id.index);
    if (contains(a) && !w.bodies[a.index].isStatic) w.wake(a.index);
    if (b && contains(*b) && !w.bodies[b->index].isStatic) w.wake(b->index);
}

// --- Stepping ---------------------------------------------------------------------------

void World::step(real dt) {
    if (!std::isfinite(dt) || !(dt > 0)) detail::refuse("World::step", "dt", "must be finite and > 0, got " + detail::show(dt));
    impl_->step(dt);
}

const StepStats &World::stats() const { return impl_->stats; }

real World::kineticEnergy() const {
    real energy = 0;
    for (std::uint32_t index : impl_->order) {
        const BodyRecord &r = impl_->bodies[index];
        if (r.isStatic) continue;
        const Vector3 w = r.body.getRotation();
        energy += 0.5 * r.body.getMass() * r.body.getVelocity().squaredNorm() +
                  0.5 * w.dot(r.body.getInertiaTensorWorld() * w);
    }
    return energy;
}

// --- Impl: lookup, sleep and wake -------------------------------------------------------

BodyRecord &World::Impl::record(BodyId id, const char *function) {
    if (id.index >= bodies.size() || !bodies[id.index].alive || bodies[id.index].generation != id.generation)
        detail::refuse(function, "id", "does not name a body of this world (index " + std::to_string(id.index) +
                                            ", generation " + std::to_string(id.generation) + ")");
    return bodies[id.index];
}

BodyRecord &World::Impl::dynamicRecord(BodyId id, const char *function) {
    BodyRecord &r = record(id, function);
    if (r.isStatic) detail::refuse(function, "id", "names a static body, which never moves");
    return r;
}

const BodyRecord &World::Impl::record(BodyId id, const char *function) const {
    return const_cast<Impl *>(this)->record(id, function);
}

void World::Impl::setTree(std::uint32_t index, Tree tree) {
    BodyRecord &r = bodies[index];
    if (!r.object) {
        r.tree = Tree::None;
        return;
    }
    broadphase.place(r.object.get(), r.tree, tree);
    r.tree = tree;
}

void World::Impl::refreshCollisionObject(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    if (r.object && r.object->place(r.body.getTransform(), detail::kBroadphaseMargin))
        broadphase.refit(r.object.get(), r.tree);
    if (!r.isStatic) {
        wake(index);
        return;
    }
    // A moved static body wakes what touched it.
    for (std::uint32_t p : bodies[index].pairs) {
        const detail::PairState &pair = pairs[p];
        const std::uint32_t other = pair.a == index ? pair.b : pair.a;
        if (!bodies[other].isStatic) wake(other);
    }
}

void World::Impl::updateAwakeList(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    const bool listed = r.alive && !r.isStatic && !r.quarantined && r.body.getAwake();
    if (listed == (r.awakeSlot >= 0)) return;
    if (listed) {
        if (!awake.empty() && bodies[awake.back()].rank > r.rank) awakeSorted = false;
        r.awakeSlot = static_cast<int>(awake.size());
        awake.push_back(index);
        return;
    }
    const std::uint32_t last = awake.back();
    awake[r.awakeSlot] = last;
    bodies[last].awakeSlot = r.awakeSlot;
    awake.pop_back();
    r.awakeSlot = -1;
    if (last != index) awakeSorted = false;
}

void World::Impl::wake(std::uint32_t index) {
    BodyRecord &r = bodies[index];
    if (r.isStatic || r.quarantined) return;
    if (r.sleepingIsland < 0) {
        if (!r.body.getAwake()) {
            r.body.setAwake(true);
            eventSink->wokeUp.push_back(idOf(index));
        }
        updateAwakeList(index);
        return;
    }
    const int island = r.sleepingIsland;
    for (std::uint32_t m : sleepingIslands[island]) {
        BodyRecord &member = bodies[m];
        member.sleepingIsland = -1;
        member.body.setAwake(true);
        eventSink->wokeUp.push_back(idOf(m));
        member.object->place(member.body.getTransform(), detail::kBroadphaseMargin);
        setTree(m, Tree::Awake);
        updateAwakeList(m);
    }
    sleepingIslands[island].clear();
    freeSleepingIslands.push_back(island);
}

void World::Impl::sleepIsland(const std::uint32_t *members, int count, bool report) {
    int island;
    if (!freeSleepingIslands.empty()) {
        island = freeSleepingIslands.back();
        freeSleepingIslands.pop_back();
    } else {
        island = static_cast<int>(sleepingIslands.size());
        sleepingIslands.emplace_back();
    }
    std::vector<std::uint32_t> &list = sleepingIslands[island];
    list.clear();
    for (int i = 0; i < count; ++i) {
        BodyRecord &r = bodies[members[i]];
        if (!r.alive || r.isStatic || r.sleepingIsland >= 0) continue;
        list.push_back(members[i]);
        r.body.setAwake(false);
        r.sleepingIsland = island;
        r.island = -1;
        setTree(members[i], Tree::Asleep);
        updateAwakeList(members[i]);
        if (report) eventSink->fellAsleep.push_back(idOf(members[i]));
    }
    if (list.empty()) freeSleepingIslands.push_back(island);
}

}  // namespace cyclone
