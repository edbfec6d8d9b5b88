// RigidBody input validation: every refused input throws std::invalid_argument whose
// message names the function, the field and the value, and leaves the body bit for bit
// as it was.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "body_test_support.h"
#include "cyclone/body.h"

namespace cyclone_test {
namespace {

const real nan = std::numeric_limits<real>::quiet_NaN();
const real inf = std::numeric_limits<real>::infinity();
const real tiny = std::numeric_limits<real>::denorm_min();

Matrix3 rows(real a, real b, real c, real d, real e, real f, real g, real h, real i) {
    Matrix3 m;
    m << a, b, c, d, e, f, g, h, i;
    return m;
}

// Matrices that are not a valid inertia tensor (nor its inverse), with a number that
// appears in each one's message.
struct BadTensor {
    std::string name;
    Matrix3 matrix;
    std::string shown;
};

std::vector<BadTensor> badTensors() {
    return {
        {"NaN", rows(2, 0, 0, 0, nan, 0, 0, 0, 2), "nan"},
        {"Infinite", rows(inf, 0, 0, 0, 2, 0, 0, 0, 2), "inf"},
        {"MinusInfinite", rows(2, 0, 0, 0, 2, 0, 0, 0, -inf), "-inf"},
        {"NotSymmetric", rows(1, 0.375, 0, 0, 1, 0, 0, 0, 1), "0.375"},
        {"SlightlyNotSymmetric", rows(2, 0, 0, 1e-6, 2, 0, 0, 0, 2), "1e-06"},
        // The second row is twice the first: rank 2.
        {"Singular", rows(1.75, 3.5, 0, 3.5, 7, 0, 0, 0, 1), "1.75"},
        {"SingularDiagonal", rows(1.25, 0, 0, 0, 0, 0, 0, 0, 1.25), "1.25"},
        {"Zero", Matrix3::Zero(), "0"},
        {"NegativeDefinite", rows(-2.25, 0, 0, 0, -2.25, 0, 0, 0, -2.25), "-2.25"},
        {"IndefiniteDiagonal", rows(1.5, 0, 0, 0, -0.75, 0, 0, 0, 2), "-0.75"},
        // Positive diagonal, yet the eigenvalues of the 2x2 block are 4 and -1.
        {"IndefiniteWithPositiveDiagonal", rows(1.5, 2.5, 0, 2.5, 1.5, 0, 0, 0, 1), "2.5"},
    };
}

struct Refusal {
    std::string name;
    std::function<void(RigidBody &)> call;
    std::string function;  // as in the message: "RigidBody::<function>:"
    std::string field;
    std::string value;     // how the refused value appears in the message
    bool asleep = false;   // refuse on a sleeping body (calls that would wake it)
};

std::ostream &operator<<(std::ostream &out, const Refusal &r) { return out << r.name; }

std::vector<Refusal> refusals() {
    std::vector<Refusal> all;
    auto add = [&all](std::string name, std::function<void(RigidBody &)> call, std::string function,
                      std::string field, std::string value, bool asleep = false) {
        all.push_back({std::move(name), std::move(call), std::move(function), std::move(field), std::move(value),
                       asleep});
    };

    // Mass: finite and > 0.
    add("SetMassNaN", [](RigidBody &b) { b.setMass(nan); }, "setMass", "mass", "nan");
    add("SetMassInfinite", [](RigidBody &b) { b.setMass(inf); }, "setMass", "mass", "inf");
    add("SetMassMinusInfinite", [](RigidBody &b) { b.setMass(-inf); }, "setMass", "mass", "-inf");
    add("SetMassZero", [](RigidBody &b) { b.setMass(0); }, "setMass", "mass", "got 0");
    add("SetMassMinusZero", [](RigidBody &b) { b.setMass(-0.0); }, "setMass", "mass", "-0");
    add("SetMassNegative", [](RigidBody &b) { b.setMass(-2.5); }, "setMass", "mass", "-2.5");
    // Positive, but 1 / mass overflows to infinity.
    add("SetMassTooSmallToInvert", [](RigidBody &b) { b.setMass(tiny); }, "setMass", "mass", "e-324");

    // Inverse mass: finite and >= 0.
    add("SetInverseMassNaN", [](RigidBody &b) { b.setInverseMass(nan); }, "setInverseMass", "inverseMass", "nan");
    add("SetInverseMassInfinite", [](RigidBody &b) { b.setInverseMass(inf); }, "setInverseMass", "inverseMass",
        "inf");
    add("SetInverseMassNegative", [](RigidBody &b) { b.setInverseMass(-0.5); }, "setInverseMass", "inverseMass",
        "-0.5");
    add("SetInverseMassSmallestNegative", [](RigidBody &b) { b.setInverseMass(-tiny); }, "setInverseMass",
        "inverseMass", "e-324");

    // Inertia tensors and their inverses.
    for (const BadTensor &t : badTensors()) {
        const Matrix3 m = t.matrix;
        add("SetInertiaTensor" + t.name, [m](RigidBody &b) { b.setInertiaTensor(m); }, "setInertiaTensor",
            "inertiaTensor", t.shown);
        add("SetInverseInertiaTensor" + t.name, [m](RigidBody &b) { b.setInverseInertiaTensor(m); },
            "setInverseInertiaTensor", "inverseInertiaTensor", t.shown);
    }
    // Positive definite, but its inverse overflows to infinity.
    add("SetInertiaTensorTooSmallToInvert",
        [](RigidBody &b) { b.setInertiaTensor(rows(1, 0, 0, 0, 1, 0, 0, 0, tiny)); }, "setInertiaTensor",
        "inertiaTensor", "e-324");

    // Damping: in [0, 1]; setDamping changes neither value if one is refused.
    add("SetDampingLinearNegative", [](RigidBody &b) { b.setDamping(-0.125, 0.5); }, "setDamping", "linearDamping",
        "-0.125");
    add("SetDampingLinearAboveOne", [](RigidBody &b) { b.setDamping(1.5, 0.5); }, "setDamping", "linearDamping",
        "1.5");
    add("SetDampingLinearNaN", [](RigidBody &b) { b.setDamping(nan, 0.5); }, "setDamping", "linearDamping", "nan");
    add("SetDampingLinearInfinite", [](RigidBody &b) { b.setDamping(inf, 0.5); }, "setDamping", "linearDamping",
        "inf");
    add("SetDampingAngularNegative", [](RigidBody &b) { b.setDamping(0.5, -0.125); }, "setDamping",
        "angularDamping", "-0.125");
    add("SetDampingAngularAboveOne", [](RigidBody &b) { b.setDamping(0.5, 1.5); }, "setDamping", "angularDamping",
        "1.5");
    add("SetDampingAngularNaN", [](RigidBody &b) { b.setDamping(0.5, nan); }, "setDamping", "angularDamping",
        "nan");
    add("SetDampingAngularMinusInfinite", [](RigidBody &b) { b.setDamping(0.5, -inf); }, "setDamping",
        "angularDamping", "-inf");
    add("SetLinearDampingNegative", [](RigidBody &b) { b.setLinearDamping(-0.125); }, "setLinearDamping",
        "linearDamping", "-0.125");
    add("SetLinearDampingJustAboveOne", [](RigidBody &b) { b.setLinearDamping(1.0000000000000002); },
        "setLinearDamping", "linearDamping", "1.0000000000000002");
    add("SetLinearDampingNaN", [](RigidBody &b) { b.setLinearDamping(nan); }, "setLinearDamping", "linearDamping",
        "nan");
    add("SetLinearDampingInfinite", [](RigidBody &b) { b.setLinearDamping(inf); }, "setLinearDamping",
        "linearDamping", "inf");
    add("SetAngularDampingNegative", [](RigidBody &b) { b.setAngularDamping(-0.125); }, "setAngularDamping",
        "angularDamping", "-0.125");
    add("SetAngularDampingAboveOne", [](RigidBody &b) { b.setAngularDamping(1.5); }, "setAngularDamping",
        "angularDamping", "1.5");
    add("SetAngularDampingNaN", [](RigidBody &b) { b.setAngularDamping(nan); }, "setAngularDamping",
        "angularDamping", "nan");
    add("SetAngularDampingMinusInfinite", [](RigidBody &b) { b.setAngularDamping(-inf); }, "setAngularDamping",
        "angularDamping", "-inf");

    // Position and orientation.
    add("SetPositionNaN", [](RigidBody &b) { b.setPosition(Vector3(nan, 0, 0)); }, "setPosition", "position",
        "[nan, 0, 0]");
    add("SetPositionInfinite", [](RigidBody &b) { b.setPosition(Vector3(0, inf, 0)); }, "setPosition",
        "position", "[0, inf, 0]");
    add("SetPositionComponentsNaN", [](RigidBody &b) { b.setPosition(1, nan, 3); }, "setPosition", "position",
        "[1, nan, 3]");
    add("SetPositionComponentsMinusInfinite", [](RigidBody &b) { b.setPosition(1, 2, -inf); }, "setPosition",
        "position", "[1, 2, -inf]");
    add("SetOrientationNaN", [](RigidBody &b) { b.setOrientation(Quaternion(nan, 0, 0, 0)); }, "setOrientation",
        "orientation", "[nan, 0, 0, 0]");
    add("SetOrientationInfinite", [](RigidBody &b) { b.setOrientation(Quaternion(1, inf, 0, 0)); },
        "setOrientation", "orientation", "[1, inf, 0, 0]");
    add("SetOrientationComponentsNaN", [](RigidBody &b) { b.setOrientation(1, 0, 0, nan); }, "setOrientation",
        "orientation", "[1, 0, 0, nan]");
    add("SetOrientationComponentsMinusInfinite", [](RigidBody &b) { b.setOrientation(1, 0, -inf, 0); },
        "setOrientation", "orientation", "[1, 0, -inf, 0]");

    // Velocity, rotation and constant acceleration.
    add("SetVelocityNaN", [](RigidBody &b) { b.setVelocity(Vector3(0, 0, nan)); }, "setVelocity", "velocity",
        "[0, 0, nan]");
    add("SetVelocityComponentsInfinite", [](RigidBody &b) { b.setVelocity(inf, 0, 0); }, "setVelocity",
        "velocity", "[inf, 0, 0]");
    add("AddVelocityNaN", [](RigidBody &b) { b.addVelocity(Vector3(nan, 1, 1)); }, "addVelocity", "deltaVelocity",
        "[nan, 1, 1]");
    add("AddVelocityMinusInfinite", [](RigidBody &b) { b.addVelocity(Vector3(1, -inf, 1)); }, "addVelocity",
        "deltaVelocity", "[1, -inf, 1]");
    add("SetRotationNaN", [](RigidBody &b) { b.setRotation(Vector3(0, nan, 0)); }, "setRotation", "rotation",
        "[0, nan, 0]");
    add("SetRotationComponentsInfinite", [](RigidBody &b) { b.setRotation(0, 0, inf); }, "setRotation",
        "rotation", "[0, 0, inf]");
    add("AddRotationNaN", [](RigidBody &b) { b.addRotation(Vector3(1, 1, nan)); }, "addRotation", "deltaRotation",
        "[1, 1, nan]");
    add("AddRotationInfinite", [](RigidBody &b) { b.addRotation(Vector3(inf, 1, 1)); }, "addRotation",
        "deltaRotation", "[inf, 1, 1]");
    add("SetAccelerationNaN", [](RigidBody &b) { b.setAcceleration(Vector3(nan, nan, nan)); }, "setAcceleration",
        "acceleration", "[nan, nan, nan]");
    add("SetAccelerationComponentsMinusInfinite", [](RigidBody &b) { b.setAcceleration(0, -inf, 0); },
        "setAcceleration", "acceleration", "[0, -inf, 0]");

    // Forces and torques; on a sleeping body a refused call must not wake it either.
    for (const bool asleep : {false, true}) {
        const std::string suffix = asleep ? "Asleep" : "";
        add("AddForceNaN" + suffix, [](RigidBody &b) { b.addForce(Vector3(0, nan, 0)); }, "addForce", "force",
            "[0, nan, 0]", asleep);
        add("AddForceInfinite" + suffix, [](RigidBody &b) { b.addForce(Vector3(inf, 0, 0)); }, "addForce", "force",
            "[inf, 0, 0]", asleep);
        add("AddForceAtPointForceNaN" + suffix,
            [](RigidBody &b) { b.addForceAtPoint(Vector3(nan, 0, 0), Vector3(1, 2, 3)); }, "addForceAtPoint",
            "force", "[nan, 0, 0]", asleep);
        add("AddForceAtPointPointInfinite" + suffix,
            [](RigidBody &b) { b.addForceAtPoint(Vector3(1, 0, 0), Vector3(1, -inf, 3)); }, "addForceAtPoint",
            "point", "[1, -inf, 3]", asleep);
        add("AddForceAtBodyPointForceInfinite" + suffix,
            [](RigidBody &b) { b.addForceAtBodyPoint(Vector3(0, 0, inf), Vector3(1, 2, 3)); },
            "addForceAtBodyPoint", "force", "[0, 0, inf]", asleep);
        add("AddForceAtBodyPointPointNaN" + suffix,
            [](RigidBody &b) { b.addForceAtBodyPoint(Vector3(1, 0, 0), Vector3(nan, 2, 3)); },
            "addForceAtBodyPoint", "point", "[nan, 2, 3]", asleep);
        add("AddTorqueNaN" + suffix, [](RigidBody &b) { b.addTorque(Vector3(0, 0, nan)); }, "addTorque", "torque",
            "[0, 0, nan]", asleep);
        add("AddTorqueMinusInfinite" + suffix, [](RigidBody &b) { b.addTorque(Vector3(-inf, 0, 0)); }, "addTorque",
            "torque", "[-inf, 0, 0]", asleep);
    }

    // Sleep threshold: finite and > 0.
    add("SetSleepEpsilonZero", [](RigidBody &b) { b.setSleepEpsilon(0); }, "setSleepEpsilon", "sleepEpsilon",
        "got 0");
    add("SetSleepEpsilonNegative", [](RigidBody &b) { b.setSleepEpsilon(-0.25); }, "setSleepEpsilon",
        "sleepEpsilon", "-0.25");
    add("SetSleepEpsilonNaN", [](RigidBody &b) { b.setSleepEpsilon(nan); }, "setSleepEpsilon", "sleepEpsilon",
        "nan");
    add("SetSleepEpsilonInfinite", [](RigidBody &b) { b.setSleepEpsilon(inf); }, "setSleepEpsilon",
        "sleepEpsilon", "inf");

    // Duration: finite and >= 0, checked even when the body sleeps.
    for (const bool asleep : {false, true}) {
        const std::string suffix = asleep ? "Asleep" : "";
        add("IntegrateNegative" + suffix, [](RigidBody &b) { b.integrate(-0.125); }, "integrate", "duration",
            "-0.125", asleep);
        add("IntegrateNaN" + suffix, [](RigidBody &b) { b.integrate(nan); }, "integrate", "duration", "nan",
            asleep);
    }
    add("IntegrateSmallestNegative", [](RigidBody &b) { b.integrate(-tiny); }, "integrate", "duration", "e-324");
    add("IntegrateInfinite", [](RigidBody &b) { b.integrate(inf); }, "integrate", "duration", "inf");
    add("IntegrateMinusInfinite", [](RigidBody &b) { b.integrate(-inf); }, "integrate", "duration", "-inf");
    add("IntegrateNoSleepNegative", [](RigidBody &b) { b.integrate(-1, false); }, "integrate", "duration", "-1");
    add("IntegrateNoSleepNaN", [](RigidBody &b) { b.integrate(nan, false); }, "integrate", "duration", "nan");
    add("IntegrateNoSleepInfinite", [](RigidBody &b) { b.integrate(inf, false); }, "integrate", "duration", "inf");
    const auto dampingFactors = [](real duration) {
        return [duration](RigidBody &b) {
            real linear = 0, angular = 0;
            b.getDampingFactors(duration, &linear, &angular);
        };
    };
    add("DampingFactorsNegative", dampingFactors(-0.125), "getDampingFactors", "duration", "-0.125");
    add("DampingFactorsNaN", dampingFactors(nan), "getDampingFactors", "duration", "nan");
    return all;
}

class RigidBodyRefusal : public ::testing::TestWithParam<Refusal> {};

TEST_P(RigidBodyRefusal, ThrowsNamesTheValueAndChangesNothing) {
    const Refusal &r = GetParam();
    RigidBody body = busyBody();
    if (r.asleep) body.setAwake(false);
    const Snapshot before(body);
    try {
        r.call(body);
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument &e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("RigidBody::" + r.function + ":"), std::string::npos) << message;
        EXPECT_NE(message.find(r.field), std::string::npos) << message;
        EXPECT_NE(message.find(r.value), std::string::npos) << message;
    } catch (const std::exception &e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
    EXPECT_TRUE(identical(before, Snapshot(body)));
}

INSTANTIATE_TEST_SUITE_P(Inputs, RigidBodyRefusal, ::testing::ValuesIn(refusals()),
                         [](const ::testing::TestParamInfo<Refusal> &info) { return info.param.name; });

TEST(RigidBodyRefusalCoverage, NamesAreUnique) {
    // gtest would report duplicates only at run time; make it a plain failure.
    const std::vector<Refusal> all = refusals();
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j) EXPECT_NE(all[i].name, all[j].name);
}

// --- Accepted edge values ----------------------------------------------------------------

TEST(RigidBodyAccepted, EdgesOfTheValidRanges) {
    RigidBody body;
    body.setInverseMass(0);
    body.setInverseMass(-0.0);  // compares equal to 0: an immovable body
    EXPECT_FALSE(body.hasFiniteMass());
    body.setMass(1e-300);  // absurdly light, but its inverse is still finite
    EXPECT_DOUBLE_EQ(body.getInverseMass(), 1e300);
    EXPECT_TRUE(body.hasFiniteMass());
    body.setInertiaTensor(rows(1e-300, 0, 0, 0, 1, 0, 0, 0, 1e300));
    EXPECT_TRUE(body.getInverseInertiaTensor().allFinite());
    body.setDamping(0, 1);
    body.setDamping(1, 0);
    body.integrate(0);
    body.integrate(tiny);
    body.setSleepEpsilon(tiny);
    EXPECT_EQ(body.getSleepEpsilon(), tiny);
}

TEST(RigidBodyAccepted, RoundingLevelAsymmetryOfAComputedTensor) {
    // R D R^T in floating point is symmetric only to rounding; it must be accepted.
    const Matrix3 r = Eigen::AngleAxis<real>(0.9, Vector3(2, -1, 3).normalized()).toRotationMatrix();
    const Matrix3 tensor = r * Vector3(2, 4, 8).asDiagonal() * r.transpose();
    RigidBody body;
    body.setInertiaTensor(tensor);
    EXPECT_TRUE(near(body.getInertiaTensor(), tensor, 1e-12));
    body.setInverseInertiaTensor(tensor);
    EXPECT_TRUE(near(body.getInverseInertiaTensor(), tensor, 1e-12));
}

TEST(RigidBodyAccepted, NonFiniteDataNeverEntersThroughARefusedSetter) {
    // After a refusal the body still integrates to finite values.
    RigidBody body = busyBody();
    EXPECT_THROW(body.setVelocity(nan, 0, 0), std::invalid_argument);
    EXPECT_THROW(body.addForce(Vector3(inf, 0, 0)), std::invalid_argument);
    body.integrate(0.1);
    EXPECT_TRUE(body.getPosition().allFinite());
    EXPECT_TRUE(body.getVelocity().allFinite());
    EXPECT_TRUE(body.getOrientation().coeffs().allFinite());
}

}  // namespace
}  // namespace cyclone_test
