// The scenes in Bullet 3, set up to match cyclone's as far as the two models allow.
//
// Matched to the scene's WorldSettings and BodySettings:
//  - one internal step per frame: stepSimulation(dt, 0) takes exactly one step of dt;
//  - btSequentialImpulseConstraintSolver with m_numIterations = cyclone's velocity passes
//    per frame (substeps x velocityIterations); Bullet takes no sub-steps;
//  - friction and restitution: Bullet multiplies the two bodies' coefficients, cyclone
//    takes the geometric mean of the frictions and the larger restitution, so Bullet's
//    global combine callbacks are set to do the same (0.6 and 0.6 give 0.6, not 0.36);
//  - restitution threshold: m_restitutionVelocityThreshold = restitutionThreshold;
//  - sleep off: DISABLE_DEACTIVATION on every dynamic body; sleep on: sleeping
//    thresholds of sqrt(sleepEpsilon) for both |v| and |w| (cyclone's threshold is on
//    v.v + w.w), Bullet's default deactivation time (gDeactivationTime, 2 s); a body that
//    starts asleep starts ISLAND_SLEEPING;
//  - damping: cyclone keeps a fraction d of the velocity per second, Bullet keeps
//    (1 - damping)^t, so Bullet's damping is 1 - d;
//  - inertia: the scene's tensor (its diagonal) when given, else Bullet's own
//    calculateLocalInertia of the shape.
// Left at Bullet's defaults (and printed by bulletSettingsNote): btDbvtBroadphase,
// btDefaultCollisionConfiguration, collision margins (0.04 m; a sphere's and a capsule's
// margin is their radius; a convex hull is inflated by its margin), split impulse and
// its penetration threshold, erp/erp2, warm starting factor, contact breaking threshold,
// implicit gyroscopic forces. A ground plane is a btStaticPlaneShape. Identical shape
// descriptions share one btCollisionShape, as a Bullet user would write it.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "alloc_counter.h"
#include "engine.h"

namespace cyclone::bench {
namespace {

btVector3 toBullet(const Vector3 &v) {
    return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z()));
}

btQuaternion toBullet(const Quaternion &q) {
    Quaternion unit = q;
    if (unit.coeffs().squaredNorm() == 0) unit = Quaternion::Identity();
    unit.normalize();
    return btQuaternion(static_cast<btScalar>(unit.x()), static_cast<btScalar>(unit.y()),
                        static_cast<btScalar>(unit.z()), static_cast<btScalar>(unit.w()));
}

btScalar geometricMeanFriction(const btCollisionObject *a, const btCollisionObject *b) {
    return std::sqrt(a->getFriction() * b->getFriction());
}

btScalar largerRestitution(const btCollisionObject *a, const btCollisionObject *b) {
    return std::max(a->getRestitution(), b->getRestitution());
}

void configureSolver(btContactSolverInfo &info, const WorldSettings &settings) {
    info.m_numIterations = settings.substeps * settings.velocityIterations;
    info.m_restitutionVelocityThreshold = static_cast<btScalar>(settings.restitutionThreshold);
}

// Every field of the shape's type, as numbers: equal keys mean the same shape.
std::vector<double> shapeKey(const Shape &shape) {
    std::vector<double> key{static_cast<double>(shape.type)};
    switch (shape.type) {
    case ShapeType::Box: key.insert(key.end(), shape.halfExtents.data(), shape.halfExtents.data() + 3); break;
    case ShapeType::Sphere: key.push_back(shape.radius); break;
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
        key.push_back(shape.radius);
        key.push_back(shape.length);
        break;
    case ShapeType::Plane:
        key.insert(key.end(), shape.normal.data(), shape.normal.data() + 3);
        key.push_back(shape.offset);
        break;
    case ShapeType::Convex:
    case ShapeType::Mesh:
        for (const Vector3 &v : shape.vertices) key.insert(key.end(), v.data(), v.data() + 3);
        for (const auto &t : shape.triangles) key.insert(key.end(), t.begin(), t.end());
        break;
    case ShapeType::Compound:
    case ShapeType::Heightfield: break;  // refused by shapeFor
    }
    return key;
}

class BulletEngine final : public Engine {
public:
    explicit BulletEngine(const Scene &scene) {
        // Before Bullet allocates anything, so that all its memory is counted.
        btAlignedAllocSetCustom(countedMalloc, countedFree);
        gCalculateCombinedFrictionCallback = geometricMeanFriction;
        gCalculateCombinedRestitutionCallback = largerRestitution;

        configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
        dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
        broadphase_ = std::make_unique<btDbvtBroadphase>();
        solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
        world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                           configuration_.get());
        world_->setGravity(toBullet(scene.world.gravity));
        configureSolver(world_->getSolverInfo(), scene.world);

        bodies_.reserve(scene.bodies.size());
        for (const BodySettings &settings : scene.bodies) addBody(settings, scene.world);
    }

    ~BulletEngine() override {
        for (auto &body : bodies_) world_->removeRigidBody(body.get());
        world_.reset();
        bodies_.clear();
        shapes_.clear();
        meshes_.clear();
    }

    void step(real dt) override {
        world_->stepSimulation(static_cast<btScalar>(dt), 0);
        deepest_ = 0;
        contacts_ = 0;
        for (int i = 0, n = dispatcher_->getNumManifolds(); i < n; ++i) {
            const btPersistentManifold *manifold = dispatcher_->getManifoldByIndexInternal(i);
            contacts_ += manifold->getNumContacts();
            for (int j = 0; j < manifold->getNumContacts(); ++j)
                deepest_ = std::max(deepest_, -static_cast<real>(manifold->getContactPoint(j).getDistance()));
        }
    }

    Vector3 position(int index) const override {
        const btVector3 &p = bodies_[static_cast<std::size_t>(index)]->getWorldTransform().getOrigin();
        return Vector3(p.x(), p.y(), p.z());
    }

    real deepestPenetration() const override { return deepest_; }
    int contacts() const override { return contacts_; }

private:
    btCollisionShape *shapeFor(const Shape &shape) {
        std::vector<double> key = shapeKey(shape);
        auto found = shapeIndex_.find(key);
        if (found != shapeIndex_.end()) return shapes_[found->second].get();

        std::unique_ptr<btCollisionShape> made;
        switch (shape.type) {
        case ShapeType::Box: made = std::make_unique<btBoxShape>(toBullet(shape.halfExtents)); break;
        case ShapeType::Sphere: made = std::make_unique<btSphereShape>(static_cast<btScalar>(shape.radius)); break;
        case ShapeType::Capsule:
            made = std::make_unique<btCapsuleShapeZ>(static_cast<btScalar>(shape.radius),
                                                     static_cast<btScalar>(shape.length));
            break;
        case ShapeType::Cylinder:
            made = std::make_unique<btCylinderShapeZ>(toBullet(Vector3(shape.radius, shape.radius, shape.length / 2)));
            break;
        case ShapeType::Convex: {
            auto hull = std::make_unique<btConvexHullShape>();
            for (const Vector3 &v : shape.vertices) hull->addPoint(toBullet(v), false);
            hull->recalcLocalAabb();
            made = std::move(hull);
            break;
        }
        case ShapeType::Plane: {
            const Vector3 normal = shape.normal.normalized();
            made = std::make_unique<btStaticPlaneShape>(toBullet(normal), static_cast<btScalar>(shape.offset));
            break;
        }
        case ShapeType::Mesh: {
            auto mesh = std::make_unique<btTriangleMesh>();
            for (const auto &t : shape.triangles) {
                mesh->addTriangle(toBullet(shape.vertices[static_cast<std::size_t>(t[0])]),
                                  toBullet(shape.vertices[static_cast<std::size_t>(t[1])]),
                                  toBullet(shape.vertices[static_cast<std::size_t>(t[2])]));
            }
            made = std::make_unique<btBvhTriangleMeshShape>(mesh.get(), true);
            meshes_.push_back(std::move(mesh));
            break;
        }
        case ShapeType::Compound: throw std::invalid_argument("the Bullet engine is not given compound shapes");
        case ShapeType::Heightfield: throw std::invalid_argument("the Bullet engine is not given heightfields");
        }
        shapeIndex_.emplace(std::move(key), shapes_.size());
        shapes_.push_back(std::move(made));
        return shapes_.back().get();
    }

    void addBody(const BodySettings &settings, const WorldSettings &world) {
        btCollisionShape *shape = shapeFor(settings.shape);
        const btScalar mass = settings.motion == Motion::Static ? btScalar(0) : static_cast<btScalar>(settings.mass);
        btVector3 inertia(0, 0, 0);
        if (settings.motion != Motion::Static) {
            if (settings.inertia) {
                inertia = toBullet(settings.inertia->diagonal());
            } else {
                shape->calculateLocalInertia(mass, inertia);
            }
        }
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
        info.m_startWorldTransform = btTransform(toBullet(settings.orientation), toBullet(settings.position));
        info.m_friction = static_cast<btScalar>(settings.material.friction);
        info.m_restitution = static_cast<btScalar>(settings.material.restitution);
        info.m_linearDamping = static_cast<btScalar>(1 - settings.linearDamping);
        info.m_angularDamping = static_cast<btScalar>(1 - settings.angularDamping);
        const btScalar threshold = static_cast<btScalar>(std::sqrt(world.sleepEpsilon));
        info.m_linearSleepingThreshold = threshold;
        info.m_angularSleepingThreshold = threshold;

        auto body = std::make_unique<btRigidBody>(info);
        if (settings.motion != Motion::Static) {
            body->setLinearVelocity(toBullet(settings.velocity));
            body->setAngularVelocity(toBullet(settings.rotation));
            if (settings.ccd) {
                btVector3 centre;
                btScalar radius;
                shape->getBoundingSphere(centre, radius);
                body->setCcdMotionThreshold(radius);
                body->setCcdSweptSphereRadius(radius / 2);
            }
        }
        world_->addRigidBody(body.get());
        if (settings.motion != Motion::Static) {
            if (!world.sleep || !settings.canSleep) {
                body->forceActivationState(DISABLE_DEACTIVATION);
            } else if (!settings.awake) {
                body->forceActivationState(ISLAND_SLEEPING);
            }
        }
        bodies_.push_back(std::move(body));
    }

    std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btDbvtBroadphase> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<btDiscreteDynamicsWorld> world_;
    std::vector<std::unique_ptr<btTriangleMesh>> meshes_;
    std::vector<std::unique_ptr<btCollisionShape>> shapes_;
    std::map<std::vector<double>, std::size_t> shapeIndex_;
    std::vector<std::unique_ptr<btRigidBody>> bodies_;
    real deepest_ = 0;
    int contacts_ = 0;
};

}  // namespace

std::unique_ptr<Engine> makeBulletEngine(const Scene &scene) { return std::make_unique<BulletEngine>(scene); }

std::string bulletSettingsNote() {
    btContactSolverInfo info;
    WorldSettings settings;
    settings.substeps = 1;
    settings.velocityIterations = kVelocityPassesPerFrame;
    configureSolver(info, settings);
    std::ostringstream out;
    out << "- Bullet " << btGetVersion() / 100 << "." << btGetVersion() % 100 << ", "
        << (sizeof(btScalar) == 8 ? "double" : "single") << " precision, btDiscreteDynamicsWorld + btDbvtBroadphase"
        << " + btSequentialImpulseConstraintSolver; stepSimulation(dt, 0): one step of dt per frame\n"
        << "- numIterations " << info.m_numIterations << "; split impulse " << (info.m_splitImpulse ? "on" : "off")
        << " (default), penetration threshold " << info.m_splitImpulsePenetrationThreshold << " m, turn erp "
        << info.m_splitImpulseTurnErp << "; erp " << info.m_erp << ", erp2 " << info.m_erp2 << "; linear slop "
        << info.m_linearSlop << "; warm starting factor " << info.m_warmstartingFactor
        << "; restitution velocity threshold " << info.m_restitutionVelocityThreshold << " m/s (cyclone's)\n"
        << "- friction combined as sqrt(f1 f2), restitution as max(e1, e2) (cyclone's rules, via Bullet's combine "
           "callbacks); default collision margins (0.04 m), contact breaking threshold "
        << gContactBreakingThreshold << " m\n"
        << "- sleep off: DISABLE_DEACTIVATION; sleep on: thresholds sqrt(sleepEpsilon) = "
        << std::sqrt(kDefaultSleepEpsilon) << " m/s and rad/s, deactivation time " << gDeactivationTime << " s\n";
    return out.str();
}

}  // namespace cyclone::bench
