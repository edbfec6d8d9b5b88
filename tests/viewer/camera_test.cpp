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

// Whether every corner of `bounds` projects inside a width x height picture.
bool cornersInView(const OrbitCamera &camera, const Bounds &bounds, int width, int height) {
    for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3f p((corner & 1) ? bounds.hi.x() : bounds.lo.x(), (corner & 2) ? bounds.hi.y() : bounds.lo.y(),
                                (corner & 4) ? bounds.hi.z() : bounds.lo.z());
        const std::optional<Eigen::Vector2f> pixel = camera.project(p, width, height);
        if (!pixel || pixel->x() < 0 || pixel->x() > width || pixel->y() < 0 || pixel->y() > height) return false;
    }
    return true;
}

// A 1 m box falling as a body does, 4.9 t^2 m in t s, and sliding 3 m/s sideways: follow
// mode keeps all of it in view at every frame, although the camera only glides a tenth of
// the way to its goal each frame; once the box stops, the camera settles on it (the target
// within 1 cm of its centre).
TEST(ViewerCamera, FollowKeepsAMovingBoxInViewAndSettlesOnIt) {
    const float aspect = static_cast<float>(kWidth) / kHeight;
    const auto boxAt = [](const Eigen::Vector3f &centre) {
        Bounds b;
        b.add(centre - Eigen::Vector3f::Constant(0.5f));
        b.add(centre + Eigen::Vector3f::Constant(0.5f));
        return b;
    };
    OrbitCamera camera;
    Eigen::Vector3f centre(0, 30, 0);
    camera.frame(boxAt(centre), aspect, 2.5f);
    for (int frame = 1; frame <= 120; ++frame) {
        const float t = static_cast<float>(frame) / 60;
        centre = Eigen::Vector3f(3 * t, 30 - 4.9f * t * t, 0);
        camera.follow(boxAt(centre), aspect, 0.1f, 2.5f);
        ASSERT_TRUE(cornersInView(camera, boxAt(centre), kWidth, kHeight)) << "frame " << frame;
    }
    for (int frame = 0; frame < 120; ++frame) camera.follow(boxAt(centre), aspect, 0.1f, 2.5f);
    // 0.9^120 = 3e-6 of the gap is left.
    EXPECT_LT((camera.target - centre).norm(), 0.01f);
    // The goal distance frames a sphere of the minimum radius, 2.5 m (the box's own is
    // sqrt(3)/2 m): 1.05 * 2.5 / sin(22.5 degrees) = 6.86 m for a 16:9 picture.
    EXPECT_NEAR(camera.distance, 1.05f * 2.5f / std::sin(0.392699f), 0.01f);
}

// lookAt puts the eye where it is asked: (10, 5, 10) looking at (0, 1, 0).
TEST(ViewerCamera, LookAtPutsTheEyeWhereAsked) {
    OrbitCamera camera;
    camera.lookAt(Eigen::Vector3f(10, 5, 10), Eigen::Vector3f(0, 1, 0));
    EXPECT_LT((camera.eye() - Eigen::Vector3f(10, 5, 10)).norm(), 1e-4f);
    EXPECT_LT((camera.target - Eigen::Vector3f(0, 1, 0)).norm(), 1e-6f);
    // sqrt(10^2 + 4^2 + 10^2) = sqrt(216) m.
    EXPECT_NEAR(camera.distance, std::sqrt(216.0f), 1e-4f);
}

TEST(ViewerCamera, EmptyBoundsLeaveTheCameraAlone) {
    OrbitCamera camera;
    const float distance = camera.distance;
    camera.frame(Bounds(), 1.5f);
    EXPECT_EQ(camera.distance, distance);
}

}  // namespace
}  // namespace cyclone::viewer
