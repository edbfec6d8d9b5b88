#include <gtest/gtest.h>
#include "cyclone/body.h"
TEST(Smoke, FallsUnderGravity) {
    cyclone::RigidBody b;
    b.setAcceleration(0, -10, 0);
    b.integrate(0.5);
    EXPECT_DOUBLE_EQ(b.getVelocity().y(), -5.0);
    EXPECT_DOUBLE_EQ(b.getPosition().y(), -2.5);
}
