// RigidBody characteristics and state: defaults, setters and both overloads of every
// getter, the matrices it hands out, space conversions and force accumulation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "body_test_support.h"
#include "cyclone/body.h"

namespace cyclone_test {
namespace {


// +90 degrees about z: body x -> world y, body y -> world -x.
Quaternion quarterTurnZ() { return Quaternion(kHalfSqrt2, 0, 0, kHalfSqrt2); }

// +120 degrees about (1,1,1): body x -> world y, y -> z, z -> x, so that
// R = [0 0 1; 1 0 0; 0 1 0] with exact entries.
Quaternion axisCycle() { return Quaternion(0.5, 0.5, 0.5, 0.5); }


TEST(RigidBodyDefaults, UnitBodyAtRestAtTheOrigin) {
    const RigidBody body;
    EXPECT_EQ(body.getInverseMass(), 1);
    EXPECT_EQ(body.getMass(), 1);
    EXPECT_TRUE(body.hasFiniteMass());
    EXPECT_EQ(body.getInertiaTensor(), Matrix3::Identity());
    EXPECT_EQ(body.getInverseInertiaTensor(), Matrix3::Identity());
    EXPECT_EQ(body.getInertiaTensorWorld(), Matrix3::Identity());
    EXPECT_EQ(body.getInverseInertiaTensorWorld(), Matrix3::Identity());
    EXPECT_EQ(body.getLinearDamping(), 1);
    EXPECT_EQ(body.getAngularDamping(), 1);
    EXPECT_EQ(body.getPosition(), Vector3::Zero());
    const Quaternion q = body.getOrientation();
    EXPECT_EQ(q.w(), 1);
    EXPECT_EQ(q.vec(), Vector3::Zero());
    EXPECT_EQ(body.getTransform().matrix(), Eigen::Matrix4d::Identity());
    EXPECT_EQ(body.getVelocity(), Vector3::Zero());
    EXPECT_EQ(body.getRotation(), Vector3::Zero());
    EXPECT_EQ(body.getAcceleration(), Vector3::Zero());
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3::Zero());
    EXPECT_EQ(body.getAccumulatedForce(), Vector3::Zero());
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3::Zero());
}

TEST(RigidBodyDefaults, AwakeMaySleepAndMotionTwiceTheThreshold) {
    const RigidBody body;
    EXPECT_TRUE(body.getAwake());
    EXPECT_TRUE(body.getCanSleep());
    EXPECT_EQ(body.getSleepEpsilon(), cyclone::kDefaultSleepEpsilon);
    EXPECT_EQ(cyclone::kDefaultSleepEpsilon, 0.01);
    EXPECT_DOUBLE_EQ(body.getSleepAverage(), 2 * 0.01);
}

TEST(RigidBodyDefaults, DefaultBodiesAreIdentical) {
    EXPECT_TRUE(identical(Snapshot(RigidBody()), Snapshot(RigidBody())));
}

TEST(RigidBodySnapshot, SeesAChangeInAnyState) {
    // The refusal tests rely on Snapshot noticing changes; check that it does.
    const RigidBody reference = busyBody();
    const Snapshot before(reference);
    auto changed = [&](void (*change)(RigidBody &)) {
        RigidBody body = reference;
        change(body);
        return !identical(before, Snapshot(body));
    };
    EXPECT_TRUE(changed([](RigidBody &b) { b.setMass(2.5); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setInertiaTensor(diag(3, 4, 6)); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setLinearDamping(0.5); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setAngularDamping(0.5); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setPosition(1, -2, 3.5); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setOrientation(1, 0, 0, 0); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setVelocity(0, 0, 0); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setRotation(0, 0, 0); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setAcceleration(0, 0, 0); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.clearAccumulators(); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setSleepEpsilon(0.5); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setCanSleep(true); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.setAwake(true); }));
    EXPECT_TRUE(changed([](RigidBody &b) { b.integrate(0.01); }));
}

// --- Mass --------------------------------------------------------------------------------

TEST(RigidBodyMass, SetMassStoresItsInverse) {
    RigidBody body;
    body.setMass(4);  // 1 / 4 kg = 0.25 1/kg
    EXPECT_EQ(body.getMass(), 4);
    EXPECT_EQ(body.getInverseMass(), 0.25);
    EXPECT_TRUE(body.hasFiniteMass());
}

TEST(RigidBodyMass, SetInverseMassGivesTheMass) {
    RigidBody body;
    body.setInverseMass(0.5);  // 1 / 0.5 = 2 kg
    EXPECT_EQ(body.getInverseMass(), 0.5);
    EXPECT_EQ(body.getMass(), 2);
    EXPECT_TRUE(body.hasFiniteMass());
}

TEST(RigidBodyMass, ZeroInverseMassIsInfiniteMass) {
    RigidBody body;
    body.setInverseMass(0);
    EXPECT_EQ(body.getInverseMass(), 0);
    EXPECT_EQ(body.getMass(), std::numeric_limits<real>::infinity());
    EXPECT_FALSE(body.hasFiniteMass());
}

TEST(RigidBodyMass, HasFiniteMassExactlyWhenInverseMassIsPositive) {
    RigidBody body;
    body.setInverseMass(1e-300);  // a mass of 1e300 kg is huge but finite
    EXPECT_TRUE(body.hasFiniteMass());
    EXPECT_DOUBLE_EQ(body.getMass(), 1e300);
    body.setInverseMass(0);
    EXPECT_FALSE(body.hasFiniteMass());
    body.setMass(1e-6);
    EXPECT_TRUE(body.hasFiniteMass());
}

// --- Inertia -----------------------------------------------------------------------------

TEST(RigidBodyInertia, DiagonalTensorAndItsInverse) {
    RigidBody body;
    body.setInertiaTensor(diag(2, 4, 8));
    // The inverse of a diagonal tensor is the diagonal of reciprocals.
    Matrix3 m;
    body.getInverseInertiaTensor(&m);
    EXPECT_TRUE(near(m, diag(0.5, 0.25, 0.125)));
    EXPECT_TRUE(near(body.getInverseInertiaTensor(), diag(0.5, 0.25, 0.125)));
    body.getInertiaTensor(&m);
    EXPECT_TRUE(near(m, diag(2, 4, 8)));
    EXPECT_TRUE(near(body.getInertiaTensor(), diag(2, 4, 8)));
}

TEST(RigidBodyInertia, FullSymmetricTensorInverse) {
    RigidBody body;
    Matrix3 inertia;
    inertia << 2, 1, 0, 1, 2, 0, 0, 0, 4;
    body.setInertiaTensor(inertia);
    // The 2x2 block [2 1; 1 2] has determinant 3 and inverse [2 -1; -1 2] / 3.
    Matrix3 inverse;
    inverse << 2.0 / 3, -1.0 / 3, 0, -1.0 / 3, 2.0 / 3, 0, 0, 0, 0.25;
    EXPECT_TRUE(near(body.getInverseInertiaTensor(), inverse));
    EXPECT_TRUE(near(body.getInertiaTensor(), inertia));
}

TEST(RigidBodyInertia, SetInverseInertiaTensorGivesTheTensor) {
    RigidBody body;
    body.setInverseInertiaTensor(diag(0.5, 0.25, 0.125));
    Matrix3 m;
    body.getInverseInertiaTensor(&m);
    EXPECT_EQ(m, diag(0.5, 0.25, 0.125));
    EXPECT_TRUE(near(body.getInertiaTensor(), diag(2, 4, 8)));
}

TEST(RigidBodyInertia, WorldTensorOfAQuarterTurnSwapsXAndY) {
    RigidBody body;
    body.setInertiaTensor(diag(2, 4, 8));
    body.setOrientation(quarterTurnZ());
    // R I R^T: the body x axis (2 kg m^2) now lies along world y, body y along world x.
    Matrix3 m;
    body.getInertiaTensorWorld(&m);
    EXPECT_TRUE(near(m, diag(4, 2, 8)));
    EXPECT_TRUE(near(body.getInertiaTensorWorld(), diag(4, 2, 8)));
    body.getInverseInertiaTensorWorld(&m);
    EXPECT_TRUE(near(m, diag(0.25, 0.5, 0.125)));
    EXPECT_TRUE(near(body.getInverseInertiaTensorWorld(), diag(0.25, 0.5, 0.125)));
    // The body-space tensor does not move with the body.
    EXPECT_TRUE(near(body.getInertiaTensor(), diag(2, 4, 8)));
}

// Damping over a duration: linearDamping^duration and angularDamping^duration, by hand
// 0.25^0.5 = 0.5 and 0.81^0.5 = 0.9; a damping set between calls is taken.
TEST(RigidBodyDamping, FactorsOverADurationArePowersOfTheDamping) {
    RigidBody body;
    body.setDamping(0.25, 0.81);
    real linear = 0, angular = 0;
    body.getDampingFactors(0.5, &linear, &angular);
    EXPECT_NEAR(linear, 0.5, 1e-15);
    EXPECT_NEAR(angular, 0.9, 1e-15);
    body.getDampingFactors(2, &linear, &angular);
    EXPECT_NEAR(linear, 0.0625, 1e-15);
    body.setLinearDamping(1);
    body.getDampingFactors(2, &linear, &angular);
    EXPECT_EQ(linear, 1);
    EXPECT_NEAR(angular, 0.6561, 1e-15);
}

// A cube's (or sphere's) inertia c I looks the same from any orientation: R (c I) R^T = c I
// exactly, with none of the rounding the two products would leave off the diagonal.
TEST(RigidBodyInertia, IsotropicWorldTensorIsExactAtAnyOrientation) {
    RigidBody body;
    body.setInertiaTensor(diag(4, 4, 4));
    body.setOrientation(std::cos(0.35), 0.6 * std::sin(0.35), 0, 0.8 * std::sin(0.35));  // 40 deg about (0.6, 0, 0.8)
    EXPECT_EQ(body.getInverseInertiaTensorWorld(), diag(0.25, 0.25, 0.25));
    // Not isotropic (one axis differs by far more than rounding): rotated as before.
    body.setInertiaTensor(diag(4, 4, 8));
    body.setOrientation(quarterTurnZ() * Quaternion(kHalfSqrt2, kHalfSqrt2, 0, 0));  // z first turns to -y, then to x
    EXPECT_TRUE(near(body.getInverseInertiaTensorWorld(), diag(0.125, 0.25, 0.25)));
}

TEST(RigidBodyInertia, WorldTensorAtFortyFiveDegrees) {
    RigidBody body;
    body.setOrientation(std::cos(kPi / 8), 0, 0, std::sin(kPi / 8));  // 45 deg about z
    body.setInertiaTensor(diag(2, 4, 8));  // set after the orientation: still rotated
    // R diag(a, b) R^T with c = s = 1/sqrt2: [(a+b)/2, (a-b)/2; (a-b)/2, (a+b)/2].
    Matrix3 world;
    world << 3, -1, 0, -1, 3, 0, 0, 0, 8;
    EXPECT_TRUE(near(body.getInertiaTensorWorld(), world));
    Matrix3 inverseWorld;  // the same with a = 0.5, b = 0.25
    inverseWorld << 0.375, 0.125, 0, 0.125, 0.375, 0, 0, 0, 0.125;
    EXPECT_TRUE(near(body.getInverseInertiaTensorWorld(), inverseWorld));
    EXPECT_TRUE(near(Matrix3(body.getInertiaTensorWorld() * body.getInverseInertiaTensorWorld()),
                     Matrix3::Identity()));
}

TEST(RigidBodyInertia, WorldTensorOfTheAxisCycle) {
    RigidBody body;
    body.setInertiaTensor(diag(2, 4, 8));
    body.setOrientation(axisCycle());
    // Body x (2) -> world y, body y (4) -> world z, body z (8) -> world x.
    EXPECT_TRUE(near(body.getInertiaTensorWorld(), diag(8, 2, 4)));
    EXPECT_TRUE(near(body.getInverseInertiaTensorWorld(), diag(0.125, 0.5, 0.25)));
}

// --- Damping -----------------------------------------------------------------------------

TEST(RigidBodyDamping, SettersAndGetters) {
    RigidBody body;
    body.setDamping(0.25, 0.75);
    EXPECT_EQ(body.getLinearDamping(), 0.25);
    EXPECT_EQ(body.getAngularDamping(), 0.75);
    body.setLinearDamping(0.5);
    EXPECT_EQ(body.getLinearDamping(), 0.5);
    EXPECT_EQ(body.getAngularDamping(), 0.75);
    body.setAngularDamping(0.125);
    EXPECT_EQ(body.getLinearDamping(), 0.5);
    EXPECT_EQ(body.getAngularDamping(), 0.125);
}

TEST(RigidBodyDamping, BoundsOfTheUnitIntervalAreAccepted) {
    RigidBody body;
    body.setDamping(0, 1);
    EXPECT_EQ(body.getLinearDamping(), 0);
    EXPECT_EQ(body.getAngularDamping(), 1);
    body.setLinearDamping(1);
    body.setAngularDamping(0);
    EXPECT_EQ(body.getLinearDamping(), 1);
    EXPECT_EQ(body.getAngularDamping(), 0);
}

// --- Position and orientation ------------------------------------------------------------

TEST(RigidBodyPosition, BothSettersAndBothGetters) {
    RigidBody body;
    body.setPosition(Vector3(1, 2, 3));
    Vector3 p;
    body.getPosition(&p);
    EXPECT_EQ(p, Vector3(1, 2, 3));
    body.setPosition(-4, 5, -6);
    EXPECT_EQ(body.getPosition(), Vector3(-4, 5, -6));
    // The transform follows at once.
    EXPECT_EQ(body.getTransform().translation(), Vector3(-4, 5, -6));
}

TEST(RigidBodyOrientation, IsNormalised) {
    RigidBody body;
    body.setOrientation(Quaternion(2, 0, 0, 0));
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(1, 0, 0, 0)));
    body.setOrientation(1, 0, 0, 1);  // |q| = sqrt2
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(kHalfSqrt2, 0, 0, kHalfSqrt2)));
    body.setOrientation(0, 3, 0, -4);  // |q| = 5
    Quaternion q;
    body.getOrientation(&q);
    EXPECT_TRUE(near(q, Quaternion(0, 0.6, 0, -0.8)));
}

TEST(RigidBodyOrientation, ZeroQuaternionMeansIdentity) {
    RigidBody body;
    body.setOrientation(quarterTurnZ());
    body.setOrientation(0, 0, 0, 0);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(1, 0, 0, 0), 0));
    body.setOrientation(quarterTurnZ());
    body.setOrientation(Quaternion(0, 0, 0, 0));
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(1, 0, 0, 0), 0));
}

TEST(RigidBodyOrientation, ExtremeMagnitudesAreNormalised) {
    // The normalisation must neither overflow nor underflow: these are 90 degrees about
    // z and 180 degrees about x.
    RigidBody body;
    body.setOrientation(1e200, 0, 0, 1e200);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(kHalfSqrt2, 0, 0, kHalfSqrt2)));
    body.setOrientation(0, 1e-200, 0, 0);
    EXPECT_TRUE(near(body.getOrientation(), Quaternion(0, 1, 0, 0)));
}

TEST(RigidBodyOrientation, MatrixOverloads) {
    RigidBody body;
    body.setOrientation(quarterTurnZ());
    Matrix3 expected;  // columns are the images of body x, y, z: (0,1,0), (-1,0,0), (0,0,1)
    expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    Matrix3 m;
    body.getOrientation(&m);
    EXPECT_TRUE(near(m, expected));

    real rowMajor[9];
    body.getOrientation(rowMajor);
    const real expectedRows[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(rowMajor[i], expectedRows[i], 1e-12) << "index " << i;
}

TEST(RigidBodyTransform, AllOverloadsOfARotatedTranslatedBody) {
    RigidBody body;
    body.setOrientation(quarterTurnZ());
    body.setPosition(1, 2, 3);
    Eigen::Matrix4d expected;
    expected << 0, -1, 0, 1,  //
        1, 0, 0, 2,           //
        0, 0, 1, 3,           //
        0, 0, 0, 1;

    cyclone::Matrix4 t;
    body.getTransform(&t);
    EXPECT_TRUE(near(t.matrix(), expected));
    EXPECT_TRUE(near(body.getTransform().matrix(), expected));

    real rowMajor[16];
    body.getTransform(rowMajor);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(rowMajor[r * 4 + c], expected(r, c), 1e-12) << r << "," << c;
    EXPECT_EQ(rowMajor[12], 0);
    EXPECT_EQ(rowMajor[13], 0);
    EXPECT_EQ(rowMajor[14], 0);
    EXPECT_EQ(rowMajor[15], 1);

    // OpenGL's column-major layout: the translation is in elements 12..14.
    float gl[16];
    body.getGLTransform(gl);
    const float expectedGl[16] = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(gl[i], expectedGl[i], 1e-6f) << "index " << i;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(gl[c * 4 + r], static_cast<float>(rowMajor[r * 4 + c])) << r << "," << c;
}

TEST(RigidBodySpaces, PointsAndDirectionsOfAQuarterTurn) {
    RigidBody body;
    body.setOrientation(quarterTurnZ());
    body.setPosition(1, 2, 3);
    // Body x maps to world y, then the body's position is added: (0,1,0) + (1,2,3).
    EXPECT_TRUE(near(body.getPointInWorldSpace(Vector3(1, 0, 0)), Vector3(1, 3, 3)));
    EXPECT_TRUE(near(body.getPointInLocalSpace(Vector3(1, 3, 3)), Vector3(1, 0, 0)));
    // The body's own centre.
    EXPECT_TRUE(near(body.getPointInLocalSpace(Vector3(1, 2, 3)), Vector3::Zero()));
    EXPECT_TRUE(near(body.getPointInWorldSpace(Vector3::Zero()), Vector3(1, 2, 3)));
    // Directions are not translated.
    EXPECT_TRUE(near(body.getDirectionInWorldSpace(Vector3(1, 0, 0)), Vector3(0, 1, 0)));
    EXPECT_TRUE(near(body.getDirectionInWorldSpace(Vector3(0, 1, 0)), Vector3(-1, 0, 0)));
    EXPECT_TRUE(near(body.getDirectionInLocalSpace(Vector3(0, 1, 0)), Vector3(1, 0, 0)));
    EXPECT_TRUE(near(body.getDirectionInLocalSpace(Vector3(0, 0, 5)), Vector3(0, 0, 5)));
}

TEST(RigidBodySpaces, PointsOfTheAxisCycle) {
    RigidBody body;
    body.setOrientation(axisCycle());
    body.setPosition(10, 20, 30);
    // R (1,2,3) = (3,1,2); plus the position.
    EXPECT_TRUE(near(body.getPointInWorldSpace(Vector3(1, 2, 3)), Vector3(13, 21, 32)));
    EXPECT_TRUE(near(body.getPointInLocalSpace(Vector3(13, 21, 32)), Vector3(1, 2, 3)));
    EXPECT_TRUE(near(body.getDirectionInWorldSpace(Vector3(1, 2, 3)), Vector3(3, 1, 2)));
    EXPECT_TRUE(near(body.getDirectionInLocalSpace(Vector3(3, 1, 2)), Vector3(1, 2, 3)));
}

TEST(RigidBodySpaces, RoundTripsOfAGenericPose) {
    RigidBody body;
    body.setOrientation(Quaternion(Eigen::AngleAxis<real>(2.1, Vector3(-1, 4, 2).normalized())));
    body.setPosition(-3.5, 0.25, 7);
    const Vector3 samples[] = {Vector3(1, 2, 3), Vector3(-0.5, 8, -2), Vector3::Zero()};
    for (const Vector3 &s : samples) {
        EXPECT_TRUE(near(body.getPointInLocalSpace(body.getPointInWorldSpace(s)), s));
        EXPECT_TRUE(near(body.getPointInWorldSpace(body.getPointInLocalSpace(s)), s));
        EXPECT_TRUE(near(body.getDirectionInLocalSpace(body.getDirectionInWorldSpace(s)), s));
        EXPECT_TRUE(near(body.getDirectionInWorldSpace(body.getDirectionInLocalSpace(s)), s));
        // A rotation keeps lengths; a point's distance from the centre is kept too.
        EXPECT_NEAR(body.getDirectionInWorldSpace(s).norm(), s.norm(), 1e-12);
        EXPECT_NEAR((body.getPointInWorldSpace(s) - body.getPosition()).norm(), s.norm(), 1e-12);
    }
}

// --- Velocity, rotation, acceleration ----------------------------------------------------

TEST(RigidBodyVelocity, SettersGettersAndAdd) {
    RigidBody body;
    body.setVelocity(Vector3(1, 2, 3));
    Vector3 v;
    body.getVelocity(&v);
    EXPECT_EQ(v, Vector3(1, 2, 3));
    body.setVelocity(-1, 0.5, 4);
    EXPECT_EQ(body.getVelocity(), Vector3(-1, 0.5, 4));
    body.addVelocity(Vector3(2, 0.25, -4));
    EXPECT_EQ(body.getVelocity(), Vector3(1, 0.75, 0));
}

TEST(RigidBodyRotation, SettersGettersAndAdd) {
    RigidBody body;
    body.setRotation(Vector3(0.5, -1, 2));
    Vector3 w;
    body.getRotation(&w);
    EXPECT_EQ(w, Vector3(0.5, -1, 2));
    body.setRotation(3, 0, -3);
    EXPECT_EQ(body.getRotation(), Vector3(3, 0, -3));
    body.addRotation(Vector3(-1, 1, 0.5));
    EXPECT_EQ(body.getRotation(), Vector3(2, 1, -2.5));
}

TEST(RigidBodyAcceleration, SettersAndGetters) {
    RigidBody body;
    body.setAcceleration(Vector3(0, -9.81, 0));
    Vector3 a;
    body.getAcceleration(&a);
    EXPECT_EQ(a, Vector3(0, -9.81, 0));
    body.setAcceleration(1, 2, 3);
    EXPECT_EQ(body.getAcceleration(), Vector3(1, 2, 3));
}

TEST(RigidBodyAcceleration, LastFrameAccelerationIsZeroBeforeAnyStep) {
    RigidBody body;
    body.setAcceleration(0, -10, 0);
    body.addForce(Vector3(1, 0, 0));
    Vector3 a;
    body.getLastFrameAcceleration(&a);
    EXPECT_EQ(a, Vector3::Zero());
    EXPECT_EQ(body.getLastFrameAcceleration(), Vector3::Zero());
}

// --- Derived data ------------------------------------------------------------------------

// Changes protected state directly, as a subclass may, to test calculateDerivedData().
class DirectStateBody : public RigidBody {
public:
    void placeWithoutDerivedData(const Vector3 &p, const Quaternion &q) {
        position = p;
        orientation = q;
    }
};

TEST(RigidBodyDerivedData, CalculateDerivedDataFollowsDirectStateChanges) {
    DirectStateBody body;
    body.setInertiaTensor(diag(2, 4, 8));
    body.placeWithoutDerivedData(Vector3(1, 2, 3), quarterTurnZ());
    // Not yet: the derived data still describes the body at the origin.
    EXPECT_EQ(body.getTransform().translation(), Vector3::Zero());
    body.calculateDerivedData();
    EXPECT_TRUE(near(body.getPointInWorldSpace(Vector3(1, 0, 0)), Vector3(1, 3, 3)));
    EXPECT_TRUE(near(body.getInertiaTensorWorld(), diag(4, 2, 8)));
    EXPECT_TRUE(near(body.getInverseInertiaTensorWorld(), diag(0.25, 0.5, 0.125)));
}

// --- Forces and torques ------------------------------------------------------------------

TEST(RigidBodyForces, AddForceAccumulatesWithoutTorque) {
    RigidBody body;
    body.setPosition(5, 5, 5);
    body.addForce(Vector3(1, 2, 3));
    body.addForce(Vector3(-0.5, 0, 1));
    EXPECT_EQ(body.getAccumulatedForce(), Vector3(0.5, 2, 4));
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3::Zero());
}

TEST(RigidBodyForces, AddTorqueAccumulates) {
    RigidBody body;
    body.addTorque(Vector3(1, 0, 0));
    body.addTorque(Vector3(0.5, -2, 3));
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3(1.5, -2, 3));
    EXPECT_EQ(body.getAccumulatedForce(), Vector3::Zero());
}

TEST(RigidBodyForces, AddForceAtPointGivesForceAndTorque) {
    RigidBody body;
    body.setPosition(1, 0, 0);
    // Lever arm p - x = (0,0,2); (0,0,2) x (0,10,0) = (0*0 - 2*10, 2*0 - 0*0, 0*10 - 0*0).
    body.addForceAtPoint(Vector3(0, 10, 0), Vector3(1, 0, 2));
    EXPECT_EQ(body.getAccumulatedForce(), Vector3(0, 10, 0));
    EXPECT_TRUE(near(body.getAccumulatedTorque(), Vector3(-20, 0, 0)));
    // At the centre of mass: no further torque. Lever (0,1,0) x (0,0,3) = (3,0,0).
    body.addForceAtPoint(Vector3(0, 0, 7), Vector3(1, 0, 0));
    body.addForceAtPoint(Vector3(0, 0, 3), Vector3(1, 1, 0));
    EXPECT_EQ(body.getAccumulatedForce(), Vector3(0, 10, 10));
    EXPECT_TRUE(near(body.getAccumulatedTorque(), Vector3(-17, 0, 0)));
}

TEST(RigidBodyForces, AddForceAtBodyPointUsesTheBodySpacePoint) {
    RigidBody body;
    body.setPosition(1, 2, 3);
    body.setOrientation(quarterTurnZ());
    // Body point (1,0,0) is world (1,3,3): lever (0,1,0); (0,1,0) x (0,0,5) = (5,0,0).
    // (Taken as a world point the lever would be (0,-2,-3); unrotated it would be
    // (1,0,0), giving (0,-5,0).)
    body.addForceAtBodyPoint(Vector3(0, 0, 5), Vector3(1, 0, 0));
    EXPECT_EQ(body.getAccumulatedForce(), Vector3(0, 0, 5));
    EXPECT_TRUE(near(body.getAccumulatedTorque(), Vector3(5, 0, 0)));
}

TEST(RigidBodyForces, ClearAccumulators) {
    RigidBody body;
    body.addForce(Vector3(1, 2, 3));
    body.addTorque(Vector3(4, 5, 6));
    body.clearAccumulators();
    EXPECT_EQ(body.getAccumulatedForce(), Vector3::Zero());
    EXPECT_EQ(body.getAccumulatedTorque(), Vector3::Zero());
    // Nothing is left to act on the next step.
    body.integrate(1);
    EXPECT_EQ(body.getVelocity(), Vector3::Zero());
    EXPECT_EQ(body.getRotation(), Vector3::Zero());
}

}  // namespace
}  // namespace cyclone_test
