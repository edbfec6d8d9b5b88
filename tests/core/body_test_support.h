// Shared helpers of the RigidBody tests: approximate comparison of Eigen objects, a
// snapshot of everything a body shows through its getters (to prove a refused call
// changed nothing), and a body whose every field differs from the defaults.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cyclone/body.h"

namespace cyclone_test {

using cyclone::Matrix3;
using cyclone::Quaternion;
using cyclone::real;
using cyclone::RigidBody;
using cyclone::Vector3;

/// Pi and sqrt(1/2), the cosine of a quarter turn's half angle.
inline constexpr real kPi = 3.14159265358979323846;
inline const real kHalfSqrt2 = std::sqrt(0.5);

/// The diagonal matrix diag(a, b, c).
inline Matrix3 diag(real a, real b, real c) { return Vector3(a, b, c).asDiagonal(); }

/// Rotational kinetic energy w . I w / 2, J.
inline real kineticEnergy(const RigidBody &body) {
    const Vector3 w = body.getRotation();
    return 0.5 * w.dot(body.getInertiaTensorWorld() * w);
}

/// World angular momentum I w, N m s.
inline Vector3 angularMomentum(const RigidBody &body) { return body.getInertiaTensorWorld() * body.getRotation(); }

/// Coefficient-wise |actual - expected| <= tolerance, with both matrices in the message.
template <typename A, typename B>
::testing::AssertionResult near(const A &actual, const B &expected, real tolerance = 1e-12) {
    if (actual.rows() != expected.rows() || actual.cols() != expected.cols())
        return ::testing::AssertionFailure() << "shapes differ";
    for (Eigen::Index r = 0; r < actual.rows(); ++r)
        for (Eigen::Index c = 0; c < actual.cols(); ++c)
            if (!(std::abs(actual(r, c) - expected(r, c)) <= tolerance)) {
                std::ostringstream out;
                out.precision(17);
                out << "coefficient (" << r << ", " << c << ") differs by more than " << tolerance
                    << "\nactual:\n" << actual << "\nexpected:\n" << expected;
                return ::testing::AssertionFailure() << out.str();
            }
    return ::testing::AssertionSuccess();
}

/// The same for quaternions, coefficient by coefficient (w, x, y, z).
inline ::testing::AssertionResult near(const Quaternion &actual, const Quaternion &expected,
                                       real tolerance = 1e-12) {
    const Eigen::Matrix<real, 4, 1> a(actual.w(), actual.x(), actual.y(), actual.z());
    const Eigen::Matrix<real, 4, 1> e(expected.w(), expected.x(), expected.y(), expected.z());
    return near(a, e, tolerance);
}

/// Every value a body shows through its public getters, both overloads of each, named.
class Snapshot {
public:
    explicit Snapshot(const RigidBody &body) {
        add("getMass", body.getMass());
        add("getInverseMass", body.getInverseMass());
        add("hasFiniteMass", body.hasFiniteMass());

        Matrix3 m;
        body.getInertiaTensor(&m);
        add("getInertiaTensor(Matrix3*)", m);
        add("getInertiaTensor()", body.getInertiaTensor());
        body.getInertiaTensorWorld(&m);
        add("getInertiaTensorWorld(Matrix3*)", m);
        add("getInertiaTensorWorld()", body.getInertiaTensorWorld());
        body.getInverseInertiaTensor(&m);
        add("getInverseInertiaTensor(Matrix3*)", m);
        add("getInverseInertiaTensor()", body.getInverseInertiaTensor());
        body.getInverseInertiaTensorWorld(&m);
        add("getInverseInertiaTensorWorld(Matrix3*)", m);
        add("getInverseInertiaTensorWorld()", body.getInverseInertiaTensorWorld());

        add("getLinearDamping", body.getLinearDamping());
        add("getAngularDamping", body.getAngularDamping());

        Vector3 v;
        body.getPosition(&v);
        add("getPosition(Vector3*)", v);
        add("getPosition()", body.getPosition());

        Quaternion q;
        body.getOrientation(&q);
        add("getOrientation(Quaternion*)", q.coeffs());
        add("getOrientation()", body.getOrientation().coeffs());
        body.getOrientation(&m);
        add("getOrientation(Matrix3*)", m);
        real rows9[9];
        body.getOrientation(rows9);
        for (int i = 0; i < 9; ++i) add("getOrientation(real[9])[" + std::to_string(i) + "]", rows9[i]);

        cyclone::Matrix4 t;
        body.getTransform(&t);
        add("getTransform(Matrix4*)", t.matrix());
        add("getTransform()", body.getTransform().matrix());
        real rows16[16];
        body.getTransform(rows16);
        for (int i = 0; i < 16; ++i) add("getTransform(real[16])[" + std::to_string(i) + "]", rows16[i]);
        float gl[16];
        body.getGLTransform(gl);
        for (int i = 0; i < 16; ++i) add("getGLTransform[" + std::to_string(i) + "]", real(gl[i]));

        const Vector3 probe(0.3, -1.7, 2.9);
        add("getPointInLocalSpace", body.getPointInLocalSpace(probe));
        add("getPointInWorldSpace", body.getPointInWorldSpace(probe));
        add("getDirectionInLocalSpace", body.getDirectionInLocalSpace(probe));
        add("getDirectionInWorldSpace", body.getDirectionInWorldSpace(probe));

        body.getVelocity(&v);
        add("getVelocity(Vector3*)", v);
        add("getVelocity()", body.getVelocity());
        body.getRotation(&v);
        add("getRotation(Vector3*)", v);
        add("getRotation()", body.getRotation());

        add("getAwake", body.getAwake());
        add("getCanSleep", body.getCanSleep());
        add("getSleepAverage", body.getSleepAverage());
        add("getSleepEpsilon", body.getSleepEpsilon());

        body.getLastFrameAcceleration(&v);
        add("getLastFrameAcceleration(Vector3*)", v);
        add("getLastFrameAcceleration()", body.getLastFrameAcceleration());
        add("getAccumulatedForce", body.getAccumulatedForce());
        add("getAccumulatedTorque", body.getAccumulatedTorque());
        body.getAcceleration(&v);
        add("getAcceleration(Vector3*)", v);
        add("getAcceleration()", body.getAcceleration());
    }

    /// Bit-for-bit equality (so -0 differs from 0), naming every value that differs.
    friend ::testing::AssertionResult identical(const Snapshot &before, const Snapshot &after) {
        std::ostringstream differences;
        differences.precision(17);
        for (std::size_t i = 0; i < before.values_.size(); ++i) {
            const real a = before.values_[i].second;
            const real b = after.values_[i].second;
            if (std::memcmp(&a, &b, sizeof(real)) != 0)
                differences << "\n  " << before.values_[i].first << ": " << a << " -> " << b;
        }
        if (differences.str().empty()) return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "the body changed:" << differences.str();
    }

private:
    void add(const std::string &name, real value) { values_.emplace_back(name, value); }
    void add(const std::string &name, bool value) { values_.emplace_back(name, value ? 1.0 : 0.0); }
    template <typename Derived>
    void add(const std::string &name, const Eigen::MatrixBase<Derived> &m) {
        for (Eigen::Index r = 0; r < m.rows(); ++r)
            for (Eigen::Index c = 0; c < m.cols(); ++c)
                add(name + "(" + std::to_string(r) + "," + std::to_string(c) + ")", real(m(r, c)));
    }

    std::vector<std::pair<std::string, real>> values_;
};

/// A body whose every field is away from its default: mass 2 kg, a full symmetric
/// inertia tensor, damping 0.9 / 0.8, translated and rotated, moving and spinning,
/// with a constant acceleration, a last-frame acceleration, accumulated force and
/// torque, and a sleep threshold of its own.
inline RigidBody busyBody() {
    RigidBody body;
    body.setMass(2);
    Matrix3 inertia;
    inertia << 3, 0.5, 0, 0.5, 4, 0.25, 0, 0.25, 5;
    body.setInertiaTensor(inertia);
    body.setDamping(0.9, 0.8);
    body.setSleepEpsilon(0.05);
    body.setCanSleep(false);
    body.setPosition(1, -2, 3);
    body.setOrientation(Quaternion(Eigen::AngleAxis<real>(0.7, Vector3(1, 2, 3).normalized())));
    body.setVelocity(0.5, 1.5, -2);
    body.setRotation(-0.25, 0.75, 1);
    body.setAcceleration(0, -9.81, 0);
    body.addForce(Vector3(4, 0, 0));
    body.integrate(0.125);  // leaves a last-frame acceleration behind
    body.addForceAtPoint(Vector3(1, 2, 3), Vector3(0, 0, 0));
    body.addTorque(Vector3(-1, 0.5, 2));
    return body;
}

}  // namespace cyclone_test
