#include "cyclone/body.h"

#include "cyclone/detail/validation.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <string>

namespace cyclone {
namespace {

using detail::refuse;
using detail::requireFinite;
using detail::requireNonNegative;
using detail::requirePositive;
using detail::requireSymmetricPositiveDefinite;
using detail::requireUnit;
using detail::show;

Quaternion normalisedOrientation(const char *function, const Quaternion &q) {
    requireFinite(function, "orientation", q);
    // stableNorm, not norm: the squared norm overflows for components near 1e155 and
    // underflows near 1e-155, which would turn a valid rotation into zero or identity.
    const real norm = q.coeffs().stableNorm();
    if (norm == 0) return Quaternion::Identity();
    return Quaternion(q.coeffs() / norm);
}

// The inverse of a symmetric positive definite 3 x 3 matrix M through its equilibrated
// form: with D = diag(1 / sqrt(M_ii)), D M D has a unit diagonal, and M^-1 = D (D M D)^-1 D.
// The plain cofactor inverse forms products of three entries, which leave the double range
// for entries beyond about 5.6e102 (the inverse came out zero) or below 1.8e-103, or for
// diagonals as far apart as diag(1e-300, 1, 1e300).
Matrix3 scaledInverse(const Matrix3 &m) {
    const Vector3 diagonal = m.diagonal();
    if (!(diagonal.minCoeff() > 0) || !diagonal.allFinite()) return m.inverse();
    const Vector3 d = diagonal.cwiseSqrt().cwiseInverse();
    const Matrix3 equilibrated = d.asDiagonal() * m * d.asDiagonal();
    return d.asDiagonal() * equilibrated.inverse() * d.asDiagonal();
}

// The matrix of v x (cross product on the left).
Matrix3 skew(const Vector3 &v) {
    Matrix3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

}  // namespace

RigidBody::RigidBody()
    : inverseMass(1),
      inverseInertiaTensor(Matrix3::Identity()),
      linearDamping(1),
      angularDamping(1),
      position(Vector3::Zero()),
      orientation(Quaternion::Identity()),
      velocity(Vector3::Zero()),
      rotation(Vector3::Zero()),
      inverseInertiaTensorWorld(Matrix3::Identity()),
      motion(2 * kDefaultSleepEpsilon),
      sleepEpsilon(kDefaultSleepEpsilon),
      movingMotionCap(10),
      isAwake(true),
      canSleep(true),
      gyroscopicStep(GyroscopicStep::None),
      rotationStep(RotationStep::Seed),
      transformMatrix(Matrix4::Identity()),
      forceAccum(Vector3::Zero()),
      torqueAccum(Vector3::Zero()),
      acceleration(Vector3::Zero()),
      lastFrameAcceleration(Vector3::Zero()) {}

void RigidBody::calculateDerivedData() {
    transformMatrix.linear() = orientation.toRotationMatrix();
    transformMatrix.translation() = position;
    // c I turns into itself: R (c I) R^T = c I, exactly, without the rounding of the products.
    const Matrix3 &t = inverseInertiaTensor;
    const bool isotropic = t(0, 1) == 0 && t(0, 2) == 0 && t(1, 0) == 0 && t(1, 2) == 0 && t(2, 0) == 0 &&
                           t(2, 1) == 0 && t(0, 0) == t(1, 1) && t(0, 0) == t(2, 2);
    if (isotropic) {
        inverseInertiaTensorWorld = t;
        return;
    }
    const Matrix3 &r = transformMatrix.linear();
    inverseInertiaTensorWorld = r * inverseInertiaTensor * r.transpose();
}

void RigidBody::integrate(real duration) { integrate(duration, true); }

void RigidBody::integrate(real duration, bool mayFallAsleep) {
    requireNonNegative("RigidBody::integrate", "duration", duration);
    if (!isAwake || duration == 0) return;

    applyGyroscopicStep(gyroscopicStep, duration);
    lastFrameAcceleration = acceleration + forceAccum * inverseMass;
    const Vector3 angularAcceleration = inverseInertiaTensorWorld * torqueAccum;

    const StepFactors &factors = stepFactors(duration);
    if (rotationStep == RotationStep::MomentumConserving) {
        // Strang splitting: half of the torque's impulse on L, the torque-free motion,
        // the other half (on L in the new pose: its inverse inertia, not the old one).
        velocity += lastFrameAcceleration * duration;
        velocity *= factors.linear;
        position += velocity * duration;
        const Vector3 halfImpulse = 0.5 * duration * factors.angular * torqueAccum;
        rotation = rotation * factors.angular + inverseInertiaTensorWorld * halfImpulse;
        applyTorqueFreeRotation(duration);
        rotation += inverseInertiaTensorWorld * halfImpulse;
    } else {
        velocity += lastFrameAcceleration * duration;
        rotation += angularAcceleration * duration;
        velocity *= factors.linear;
        rotation *= factors.angular;

        position += velocity * duration;
        // q += 1/2 dt (0, w) q, then normalised: the seed's first-order orientation update.
        const Quaternion spin(0, rotation.x() * duration, rotation.y() * duration, rotation.z() * duration);
        orientation.coeffs() += 0.5 * (spin * orientation).coeffs();
        orientation.normalize();
    }

    calculateDerivedData();
    clearAccumulators();

    const real currentMotion = velocity.squaredNorm() + rotation.squaredNorm();
    const real bias = factors.motionBias;
    motion = bias * motion + (1 - bias) * currentMotion;
    // The cap bounds the average's memory of fast motion: once the body stops, the
    // average halves each second from at most the cap down to the threshold.
    const real cap = currentMotion >= sleepEpsilon ? movingMotionCap : real(10);
    if (mayFallAsleep && canSleep && motion < sleepEpsilon) {
        setAwake(false);
    } else if (motion > cap * sleepEpsilon) {
        motion = cap * sleepEpsilon;
    }
}

void RigidBody::getDampingFactors(real duration, real *linear, real *angular) const {
    requireNonNegative("RigidBody::getDampingFactors", "duration", duration);
    const StepFactors &factors = stepFactors(duration);
    *linear = factors.linear;
    *angular = factors.angular;
}

const RigidBody::StepFactors &RigidBody::stepFactors(real duration) const {
    StepFactors &f = lastStepFactors;
    if (f.duration != duration || f.linearDamping != linearDamping || f.angularDamping != angularDamping) {
        f.duration = duration;
        f.linearDamping = linearDamping;
        f.angularDamping = angularDamping;
        f.linear = std::pow(linearDamping, duration);
        f.angular = std::pow(angularDamping, duration);
        f.motionBias = std::pow(real(0.5), duration);
    }
    return f;
}

bool RigidBody::hasIsotropicInertia() const {
    const real mean = inverseInertiaTensor.trace() / 3;
    return (inverseInertiaTensor - mean * Matrix3::Identity()).cwiseAbs().maxCoeff() <= 1e-12 * mean;
}

namespace {

bool knownStep(GyroscopicStep step) {
    return step == GyroscopicStep::None || step == GyroscopicStep::BackwardEuler || step == GyroscopicStep::Midpoint;
}

// One Newton step on backward Euler from w (Bullet's btRigidBody::
// computeGyroscopicImpulseImplicit_Body): the residual f(w') = I (w' - w) + h w' x I w'
// is h w x I w at w' = w, and its Jacobian there is I + h ([w]x I - [I w]x).
Vector3 backwardEulerStep(const Matrix3 &inertia, const Vector3 &w, real h) {
    const Vector3 momentum = inertia * w;
    const Matrix3 jacobian = inertia + h * (skew(w) * inertia - skew(momentum));
    const Eigen::FullPivLU<Matrix3> lu(jacobian);
    if (!lu.isInvertible()) return w;
    return w - lu.solve(h * w.cross(momentum));
}

// Newton's method on the midpoint rule f(x) = I (x - w) + h m x I m, m = (x + w) / 2,
// whose Jacobian is I + h/2 ([m]x I - [I m]x). Quadratic convergence from x = w: at
// h |w| = 0.1 the correction falls as 1e-3, 1e-6, 1e-12.
Vector3 midpointStep(const Matrix3 &inertia, const Vector3 &w, real h) {
    constexpr int kMaxIterations = 10;
    Vector3 x = w;
    for (int i = 0; i < kMaxIterations; ++i) {
        const Vector3 m = 0.5 * (x + w);
        const Vector3 momentum = inertia * m;
        const Vector3 residual = inertia * (x - w) + h * m.cross(momentum);
        const Matrix3 jacobian = inertia + 0.5 * h * (skew(m) * inertia - skew(momentum));
        const Eigen::FullPivLU<Matrix3> lu(jacobian);
        if (!lu.isInvertible()) break;
        const Vector3 correction = lu.solve(residual);
        x -= correction;
        if (!(correction.norm() > 1e-14 * x.norm())) break;
    }
    return x;
}

// The implicit midpoint rule on Euler's equations in body space, dL/dt = L x I^-1 L, for
// the midpoint x = (L + L') / 2: g(x) = 2 (x - L) - h x x (A x) = 0 with A = I^-1, whose
// Jacobian is 2 - h ([x]x A - [A x]x). Newton's method from x = L converges quadratically
// while h |A x| is below about 1. Returns false (x unusable) when it does not converge.
bool torqueFreeMidpoint(const Matrix3 &inverseInertia, const Vector3 &momentum, real h, Vector3 *midpoint) {
    constexpr int kMaxIterations = 12;
    Vector3 x = momentum;
    for (int i = 0; i < kMaxIterations; ++i) {
        const Vector3 w = inverseInertia * x;
        const Vector3 residual = 2 * (x - momentum) - h * x.cross(w);
        const Matrix3 jacobian = 2 * Matrix3::Identity() - h * (skew(x) * inverseInertia - skew(w));
        const Eigen::FullPivLU<Matrix3> lu(jacobian);
        if (!lu.isInvertible()) return false;
        const Vector3 correction = lu.solve(residual);
        x -= correction;
        if (!x.allFinite()) return false;
        if (!(correction.norm() > 1e-14 * x.norm())) {
            *midpoint = x;
            return true;
        }
    }
    return false;
}

// The rotation whose Cayley map is [v]x: by 2 atan(|v| / 2) about v.
Quaternion cayley(const Vector3 &v) {
    Quaternion q(1, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z());
    q.normalize();
    return q;
}

}  // namespace

void RigidBody::setRotationStep(RotationStep step) {
    if (step != RotationStep::Seed && step != RotationStep::MomentumConserving)
        refuse("RigidBody::setRotationStep", "step",
               "must be Seed or MomentumConserving, got " + std::to_string(static_cast<int>(step)));
    rotationStep = step;
}

void RigidBody::applyTorqueFreeRotation(real duration) {
    requireNonNegative("RigidBody::applyTorqueFreeRotation", "duration", duration);
    if (!isAwake || duration == 0) return;

    const Matrix3 toWorld = orientation.toRotationMatrix();
    const Matrix3 inertia = scaledInverse(inverseInertiaTensor);
    const Vector3 bodyMomentum = inertia * (toWorld.transpose() * rotation);
    const Vector3 worldMomentum = toWorld * bodyMomentum;
    // A body of isotropic inertia turns about a fixed axis: the midpoint is L itself.
    const bool isotropic = hasIsotropicInertia();
    if (!worldMomentum.allFinite()) return;
    // Split the step while Newton's method fails (h |w| well beyond 1); at the last split
    // each part's rotation is kept whatever it is, still a rotation, so L is kept all the same.
    constexpr int kMaxParts = 1 << 12;
    Quaternion turn = Quaternion::Identity();
    for (int parts = 1;; parts *= 2) {
        const bool last = parts >= kMaxParts;
        const real h = duration / parts;
        Vector3 momentum = bodyMomentum;
        turn = Quaternion::Identity();
        bool converged = true;
        for (int part = 0; part < parts; ++part) {
            Vector3 midpoint = momentum;
            if (!isotropic && !torqueFreeMidpoint(inverseInertiaTensor, momentum, h, &midpoint)) {
                converged = false;
                if (!last) break;
            }
            const Quaternion partTurn = cayley(h * (inverseInertiaTensor * midpoint));
            turn = turn * partTurn;
            // L_b' = 2 x - L_b is this rotation of L_b, taken back (up to roundoff).
            momentum = partTurn.conjugate() * momentum;
        }
        if (converged || last) break;
    }
    orientation = orientation * turn;
    orientation.normalize();
    calculateDerivedData();
    const Matrix3 &newToWorld = transformMatrix.linear();
    const Vector3 w = newToWorld * (inverseInertiaTensor * (newToWorld.transpose() * worldMomentum));
    if (w.allFinite()) rotation = w;
}

void RigidBody::setGyroscopicStep(GyroscopicStep step) {
    if (!knownStep(step))
        refuse("RigidBody::setGyroscopicStep", "step",
                              "must be None, BackwardEuler or Midpoint, got " + std::to_string(static_cast<int>(step)));
    gyroscopicStep = step;
}

void RigidBody::applyGyroscopicStep(GyroscopicStep step, real duration) {
    static const char *function = "RigidBody::applyGyroscopicStep";
    if (!knownStep(step))
        refuse(function, "step",
               "must be None, BackwardEuler or Midpoint, got " + std::to_string(static_cast<int>(step)));
    requireNonNegative(function, "duration", duration);
    if (step == GyroscopicStep::None || !isAwake || duration == 0 || hasIsotropicInertia()) return;

    const Matrix3 toWorld = orientation.toRotationMatrix();
    const Vector3 w = toWorld.transpose() * rotation;
    const Matrix3 inertia = scaledInverse(inverseInertiaTensor);
    Vector3 next = step == GyroscopicStep::Midpoint ? midpointStep(inertia, w, duration)
                                                    : backwardEulerStep(inertia, w, duration);
    // Backward Euler's solution satisfies w'.I w' = w'.I w <= sqrt(w'.I w') sqrt(w.I w);
    // the midpoint's keeps w.I w. An approximate solution may not: scale it back.
    const real before = w.dot(inertia * w);
    const real after = next.dot(inertia * next);
    if (after > before) next *= std::sqrt(before / after);
    if (!next.allFinite()) return;
    rotation = toWorld * next;
}

void RigidBody::setMass(const real mass) {
    requirePositive("RigidBody::setMass", "mass", mass);
    // Below about 5.6e-309 kg the inverse overflows, and the next force would be NaN.
    if (!std::isfinite(1 / mass)) refuse("RigidBody::setMass", "mass", "is too small to invert, got " + show(mass));
    inverseMass = 1 / mass;
}

real RigidBody::getMass() const {
    if (inverseMass == 0) return std::numeric_limits<real>::infinity();
    return 1 / inverseMass;
}

void RigidBody::setInverseMass(const real newInverseMass) {
    requireNonNegative("RigidBody::setInverseMass", "inverseMass", newInverseMass);
    inverseMass = newInverseMass;
}

real RigidBody::getInverseMass() const { return inverseMass; }

bool RigidBody::hasFiniteMass() const { return inverseMass > 0; }

void RigidBody::setInertiaTensor(const Matrix3 &inertiaTensor) {
    requireSymmetricPositiveDefinite("RigidBody::setInertiaTensor", "inertiaTensor", inertiaTensor);
    const Matrix3 inverse = scaledInverse(inertiaTensor);
    if (!inverse.allFinite())
        refuse("RigidBody::setInertiaTensor", "inertiaTensor",
               "has no finite inverse in double precision, got " + show(inertiaTensor));
    inverseInertiaTensor = 0.5 * (inverse + inverse.transpose());
    calculateDerivedData();
}

void RigidBody::getInertiaTensor(Matrix3 *inertiaTensor) const { *inertiaTensor = getInertiaTensor(); }

Matrix3 RigidBody::getInertiaTensor() const { return scaledInverse(inverseInertiaTensor); }

void RigidBody::getInertiaTensorWorld(Matrix3 *inertiaTensor) const { *inertiaTensor = getInertiaTensorWorld(); }

Matrix3 RigidBody::getInertiaTensorWorld() const { return scaledInverse(inverseInertiaTensorWorld); }

void RigidBody::setInverseInertiaTensor(const Matrix3 &inverseInertiaTensor_) {
    requireSymmetricPositiveDefinite("RigidBody::setInverseInertiaTensor", "inverseInertiaTensor", inverseInertiaTensor_);
    inverseInertiaTensor = inverseInertiaTensor_;
    calculateDerivedData();
}

void RigidBody::getInverseInertiaTensor(Matrix3 *inverseInertiaTensor_) const {
    *inverseInertiaTensor_ = inverseInertiaTensor;
}

Matrix3 RigidBody::getInverseInertiaTensor() const { return inverseInertiaTensor; }

void RigidBody::getInverseInertiaTensorWorld(Matrix3 *inverseInertiaTensor_) const {
    *inverseInertiaTensor_ = inverseInertiaTensorWorld;
}

Matrix3 RigidBody::getInverseInertiaTensorWorld() const { return inverseInertiaTensorWorld; }

void RigidBody::setDamping(const real linear, const real angular) {
    requireUnit("RigidBody::setDamping", "linearDamping", linear);
    requireUnit("RigidBody::setDamping", "angularDamping", angular);
    linearDamping = linear;
    angularDamping = angular;
}

void RigidBody::setLinearDamping(const real linear) {
    requireUnit("RigidBody::setLinearDamping", "linearDamping", linear);
    linearDamping = linear;
}

real RigidBody::getLinearDamping() const { return linearDamping; }

void RigidBody::setAngularDamping(const real angular) {
    requireUnit("RigidBody::setAngularDamping", "angularDamping", angular);
    angularDamping = angular;
}

real RigidBody::getAngularDamping() const { return angularDamping; }

void RigidBody::setPosition(const Vector3 &newPosition) {
    requireFinite("RigidBody::setPosition", "position", newPosition);
    position = newPosition;
    // The rotation and world inertia depend on the orientation only: they are current.
    transformMatrix.translation() = position;
}

void RigidBody::setPosition(const real x, const real y, const real z) { setPosition(Vector3(x, y, z)); }

void RigidBody::getPosition(Vector3 *out) const { *out = position; }

void RigidBody::setOrientation(const Quaternion &newOrientation) {
    orientation = normalisedOrientation("RigidBody::setOrientation", newOrientation);
    calculateDerivedData();
}

void RigidBody::setOrientation(const real r, const real i, const real j, const real k) {
    setOrientation(Quaternion(r, i, j, k));
}

void RigidBody::getOrientation(Quaternion *out) const { *out = orientation; }

void RigidBody::getOrientation(Matrix3 *matrix) const { *matrix = transformMatrix.linear(); }

void RigidBody::getOrientation(real matrix[9]) const {
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) matrix[row * 3 + col] = transformMatrix.linear()(row, col);
}

void RigidBody::getTransform(Matrix4 *transform) const { *transform = transformMatrix; }

void RigidBody::getTransform(real matrix[16]) const {
    const auto &m = transformMatrix.matrix();
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) matrix[row * 4 + col] = m(row, col);
}

void RigidBody::getGLTransform(float matrix[16]) const {
    const auto &m = transformMatrix.matrix();
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) matrix[col * 4 + row] = static_cast<float>(m(row, col));
}

Vector3 RigidBody::getPointInLocalSpace(const Vector3 &point) const {
    return transformMatrix.linear().transpose() * (point - transformMatrix.translation());
}

Vector3 RigidBody::getDirectionInLocalSpace(const Vector3 &direction) const {
    return transformMatrix.linear().transpose() * direction;
}

Vector3 RigidBody::getDirectionInWorldSpace(const Vector3 &direction) const {
    return transformMatrix.linear() * direction;
}

void RigidBody::setVelocity(const Vector3 &newVelocity) {
    requireFinite("RigidBody::setVelocity", "velocity", newVelocity);
    velocity = newVelocity;
}

void RigidBody::setVelocity(const real x, const real y, const real z) { setVelocity(Vector3(x, y, z)); }

void RigidBody::getVelocity(Vector3 *out) const { *out = velocity; }

Vector3 RigidBody::getVelocity() const { return velocity; }

void RigidBody::addVelocity(const Vector3 &deltaVelocity) {
    requireFinite("RigidBody::addVelocity", "deltaVelocity", deltaVelocity);
    velocity += deltaVelocity;
}

void RigidBody::setRotation(const Vector3 &newRotation) {
    requireFinite("RigidBody::setRotation", "rotation", newRotation);
    rotation = newRotation;
}

void RigidBody::setRotation(const real x, const real y, const real z) { setRotation(Vector3(x, y, z)); }

void RigidBody::getRotation(Vector3 *out) const { *out = rotation; }

Vector3 RigidBody::getRotation() const { return rotation; }

void RigidBody::addRotation(const Vector3 &deltaRotation) {
    requireFinite("RigidBody::addRotation", "deltaRotation", deltaRotation);
    rotation += deltaRotation;
}

void RigidBody::setAwake(const bool awake) {
    if (awake) {
        isAwake = true;
        motion = 2 * sleepEpsilon;
    } else {
        isAwake = false;
        velocity.setZero();
        rotation.setZero();
    }
}

void RigidBody::setCanSleep(const bool newCanSleep) {
    canSleep = newCanSleep;
    if (!canSleep && !isAwake) setAwake(true);
}

void RigidBody::setSleepEpsilon(const real newSleepEpsilon) {
    requirePositive("RigidBody::setSleepEpsilon", "sleepEpsilon", newSleepEpsilon);
    sleepEpsilon = newSleepEpsilon;
}

void RigidBody::setMovingSleepAverageCap(const real cap) {
    if (!std::isfinite(cap) || !(cap >= 1 && cap <= 10))
        refuse("RigidBody::setMovingSleepAverageCap", "cap", "must be finite and in [1, 10], got " + show(cap));
    movingMotionCap = cap;
}

void RigidBody::getLastFrameAcceleration(Vector3 *linearAcceleration) const {
    *linearAcceleration = lastFrameAcceleration;
}

Vector3 RigidBody::getLastFrameAcceleration() const { return lastFrameAcceleration; }

void RigidBody::clearAccumulators() {
    forceAccum.setZero();
    torqueAccum.setZero();
}

void RigidBody::addForce(const Vector3 &force) {
    requireFinite("RigidBody::addForce", "force", force);
    forceAccum += force;
    if (!isAwake) setAwake(true);
}

void RigidBody::addForceAtPoint(const Vector3 &force, const Vector3 &point) {
    requireFinite("RigidBody::addForceAtPoint", "force", force);
    requireFinite("RigidBody::addForceAtPoint", "point", point);
    forceAccum += force;
    torqueAccum += (point - position).cross(force);
    if (!isAwake) setAwake(true);
}

void RigidBody::addForceAtBodyPoint(const Vector3 &force, const Vector3 &point) {
    requireFinite("RigidBody::addForceAtBodyPoint", "force", force);
    requireFinite("RigidBody::addForceAtBodyPoint", "point", point);
    addForceAtPoint(force, getPointInWorldSpace(point));
}

void RigidBody::addTorque(const Vector3 &torque) {
    requireFinite("RigidBody::addTorque", "torque", torque);
    torqueAccum += torque;
    if (!isAwake) setAwake(true);
}

void RigidBody::setAcceleration(const Vector3 &newAcceleration) {
    requireFinite("RigidBody::setAcceleration", "acceleration", newAcceleration);
    acceleration = newAcceleration;
}

void RigidBody::setAcceleration(const real x, const real y, const real z) {
    setAcceleration(Vector3(x, y, z));
}

void RigidBody::getAcceleration(Vector3 *out) const { *out = acceleration; }

Vector3 RigidBody::getAcceleration() const { return acceleration; }

}  // namespace cyclone
