// The viewer's camera: pixels and rays agree, framing shows the whole box, orbiting never
// flips over the pole.
#include <gtest/gtest.h>

#include <cmath>

#include "camera.h"

namespace cyclone::viewer {
namespace {

constexpr int kWidth = 1280, kHeight = 720;

TEST(ViewerCamera, APointOnThePixelsRayProjectsBackToThePixel) {
    OrbitCamera camera;
    camera.target = Eigen::Vector3f(1, 2, 3);
    camera.distance = 15;
    for (const Eigen::Vector2f &pixel : {Eigen::Vector2f(640, 360), Eigen::Vector2f(10, 20), Eigen::Vector2f(1200, 700)}) {
        const Ray ray = camera.ray(pixel.x(), pixel.y(), kWidth, kHeight);
        EXPECT_NEAR(ray.direction.norm(), 1, 1e-5);
        const std::optional<Eigen::Vector2f> back = camera.project(ray.origin + 12 * ray.direction, kWidth, kHeight);
        ASSERT_TRUE(back.has_value());
        EXPECT_NEAR(back->x(), pixel.x(), 0.05);
        EXPECT_NEAR(back->y(), pixel.y(), 0.05);
    }
}

TEST(ViewerCamera, TheCentrePixelLooksAtTheTargetAndUpIsUp) {
    OrbitCamera camera;
    const std::optional<Eigen::Vector2f> centre = camera.project(camera.target, kWidth, kHeight);
    ASSERT_TRUE(centre.has_value());
    EXPECT_NEAR(centre->x(), kWidth / 2.0f, 1e-3);
    EXPECT_NEAR(centre->y(), kHeight / 2.0f, 1e-3);
    const std::optional<Eigen::Vector2f> above = camera.project(camera.target + Eigen::Vector3f(0, 1, 0), kWidth, kHeight);
    ASSERT_TRUE(above.has_value());
    EXPECT_LT(above->y(), centre->y()) << "a point above the target is higher in the picture";
    EXPECT_FALSE(camera.project(camera.eye() - camera.forward(), kWidth, kHeight).has_value()) << "behind the eye";
}

TEST(ViewerCamera, FramingShowsEveryCornerOfTheBox) {
    Bounds bounds;
    bounds.add(Eigen::Vector3f(-10.5f, 0, -0.5f));
    bounds.add(Eigen::Vector3f(10.5f, 20, 0.5f));
    for (float aspect : {16.0f / 9.0f, 0.5f}) {
        OrbitCamera camera;
        const int width = static_cast<int>(std::lround(kHeight * aspect));
        camera.frame(bounds, aspect);
        for (int corner = 0; corner < 8; ++corner) {
            const Eigen::Vector3f p((corner & 1) ? bounds.hi.x() : bounds.lo.x(), (corner & 2) ? bounds.hi.y() : bounds.lo.y(),
                                    (corner & 4) ? bounds.hi.z() : bounds.lo.z());
            const std::optional<Eigen::Vector2f> pixel = camera.project(p, width, kHeight);
            ASSERT_TRUE(pixel.has_value());
            EXPECT_GE(pixel->x(), 0);
            EXPECT_LE(pixel->x(), width);
            EXPECT_GE(pixel->y(), 0);
            EXPECT_LE(pixel->y(), kHeight);
        }
    }
}

TEST(ViewerCamera, OrbitKeepsThePitchWithin85Degrees) {
    OrbitCamera camera;
    camera.orbit(0, 10);
    EXPECT_NEAR(camera.pitch, 85 * 3.14159265f / 180, 1e-4);
    camera.orbit(0, -20);
    EXPECT_NEAR(camera.pitch, -85 * 3.14159265f / 180, 1e-4);
    EXPECT_NEAR((camera.eye() - camera.target).norm(), camera.distance, 1e-3);
}

TEST(ViewerCamera, EmptyBoundsLeaveTheCameraAlone) {
    OrbitCamera camera;
    const float distance = camera.distance;
    camera.frame(Bounds(), 1.5f);
    EXPECT_EQ(camera.distance, distance);
}

}  // namespace
}  // namespace cyclone::viewer
