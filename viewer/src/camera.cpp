#include "camera.h"

#include <algorithm>
#include <cmath>

namespace cyclone::viewer {

namespace {
constexpr float kMaxPitch = 1.4835f;  // 85 degrees: the view never flips over the pole.
constexpr float kMinDistance = 0.5f;
constexpr float kMaxDistance = 2000.0f;
}  // namespace

void Bounds::add(const Eigen::Vector3f &point) {
    lo = lo.cwiseMin(point);
    hi = hi.cwiseMax(point);
}

void Bounds::add(const Bounds &other) {
    if (other.empty()) return;
    add(other.lo);
    add(other.hi);
}

Eigen::Vector3f OrbitCamera::forward() const {
    const float c = std::cos(pitch);
    return Eigen::Vector3f(-std::sin(yaw) * c, std::sin(pitch), -std::cos(yaw) * c);
}

Eigen::Vector3f OrbitCamera::eye() const { return target - distance * forward(); }

Eigen::Matrix4f OrbitCamera::view() const {
    const Eigen::Vector3f f = forward();
    const Eigen::Vector3f s = f.cross(Eigen::Vector3f::UnitY()).normalized();
    const Eigen::Vector3f u = s.cross(f);
    const Eigen::Vector3f e = eye();
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(e);
    m(1, 3) = -u.dot(e);
    m(2, 3) = f.dot(e);
    return m;
}

float OrbitCamera::nearPlane() const { return std::max(0.05f, distance * 0.01f); }
float OrbitCamera::farPlane() const { return distance * 20 + 500; }

Eigen::Matrix4f OrbitCamera::projection(float aspect) const {
    const float n = nearPlane(), f = farPlane();
    const float t = 1.0f / std::tan(fovY / 2);
    Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = (f + n) / (n - f);
    m(2, 3) = 2 * f * n / (n - f);
    m(3, 2) = -1;
    return m;
}

Ray OrbitCamera::ray(float x, float y, int width, int height) const {
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const float t = std::tan(fovY / 2);
    const float ndcX = 2 * x / static_cast<float>(width) - 1;
    const float ndcY = 1 - 2 * y / static_cast<float>(height);
    const Eigen::Vector3f f = forward();
    const Eigen::Vector3f s = f.cross(Eigen::Vector3f::UnitY()).normalized();
    const Eigen::Vector3f u = s.cross(f);
    Ray ray;
    ray.origin = eye();
    ray.direction = (f + s * (ndcX * t * aspect) + u * (ndcY * t)).normalized();
    return ray;
}

std::optional<Eigen::Vector2f> OrbitCamera::project(const Eigen::Vector3f &point, int width, int height) const {
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const Eigen::Vector4f clip = projection(aspect) * view() * point.homogeneous();
    if (!(clip.w() > 0)) return std::nullopt;
    const float ndcX = clip.x() / clip.w(), ndcY = clip.y() / clip.w();
    return Eigen::Vector2f((ndcX + 1) / 2 * static_cast<float>(width), (1 - ndcY) / 2 * static_cast<float>(height));
}

void OrbitCamera::orbit(float dYaw, float dPitch) {
    yaw = std::remainder(yaw + dYaw, 6.2831853f);
    pitch = std::clamp(pitch + dPitch, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dx, float dy, int height) {
    const Eigen::Vector3f f = forward();
    const Eigen::Vector3f s = f.cross(Eigen::Vector3f::UnitY()).normalized();
    const Eigen::Vector3f u = s.cross(f);
    const float metresPerPixel = 2 * distance * std::tan(fovY / 2) / static_cast<float>(std::max(height, 1));
    target += (-dx * s + dy * u) * metresPerPixel;
}

void OrbitCamera::zoom(float factor) { distance = std::clamp(distance * factor, kMinDistance, kMaxDistance); }

float OrbitCamera::framingDistance(float radius, float aspect) const {
    const float halfY = fovY / 2;
    const float halfX = std::atan(std::tan(halfY) * aspect);
    return std::clamp(1.05f * radius / std::sin(std::min(halfX, halfY)), kMinDistance, kMaxDistance);
}

void OrbitCamera::frame(const Bounds &bounds, float aspect, float minRadius) {
    if (bounds.empty()) return;
    target = (bounds.lo + bounds.hi) / 2;
    distance = framingDistance(std::max(0.5f * (bounds.hi - bounds.lo).norm(), minRadius), aspect);
}

void OrbitCamera::follow(const Bounds &bounds, float aspect, float rate, float minRadius) {
    if (bounds.empty()) return;
    const Eigen::Vector3f centre = (bounds.lo + bounds.hi) / 2;
    target += (centre - target) * rate;
    const float goal = framingDistance(std::max(0.5f * (bounds.hi - bounds.lo).norm(), minRadius), aspect);
    // The sphere about the new target that holds every corner of the box.
    float reach = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3f p((corner & 1) ? bounds.hi.x() : bounds.lo.x(), (corner & 2) ? bounds.hi.y() : bounds.lo.y(),
                                (corner & 4) ? bounds.hi.z() : bounds.lo.z());
        reach = std::max(reach, (p - target).norm());
    }
    distance = std::max(distance + (goal - distance) * rate, framingDistance(reach, aspect));
}

void OrbitCamera::lookAt(const Eigen::Vector3f &eyeAt, const Eigen::Vector3f &targetAt) {
    const Eigen::Vector3f towards = targetAt - eyeAt;
    target = targetAt;
    distance = std::clamp(towards.norm(), kMinDistance, kMaxDistance);
    if (!(towards.norm() > 0)) return;
    const Eigen::Vector3f f = towards.normalized();
    pitch = std::clamp(std::asin(std::clamp(f.y(), -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    // forward() is (-sin(yaw) cos(pitch), sin(pitch), -cos(yaw) cos(pitch)).
    if (std::abs(f.x()) + std::abs(f.z()) > 0) yaw = std::atan2(-f.x(), -f.z());
}

}  // namespace cyclone::viewer
