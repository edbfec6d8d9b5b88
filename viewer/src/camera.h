// The viewer's camera: it orbits a target point, pans and zooms; it frames a box of the
// scene, projects world points to pixels and casts rays from pixels (mouse picking).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>

namespace cyclone::viewer {

/// An axis-aligned box in world space, m; empty until a point is added.
struct Bounds {
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e30f);
    Eigen::Vector3f hi = Eigen::Vector3f::Constant(-1e30f);
    bool empty() const { return !(lo.x() <= hi.x()); }
    void add(const Eigen::Vector3f &point);
    void add(const Bounds &other);
};

/// A ray in world space: origin (m) and unit direction.
struct Ray {
    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    Eigen::Vector3f direction = -Eigen::Vector3f::UnitZ();
};

/// An orbit camera; y is up. Pixels are counted from the top-left corner of the picture.
class OrbitCamera {
public:
    /// The point looked at and orbited around, m.
    Eigen::Vector3f target = Eigen::Vector3f::Zero();
    /// Angle about +y, rad; 0 puts the eye on the +z side looking towards -z.
    float yaw = 0.35f;
    /// Angle above the horizon, rad, in (-pi/2, pi/2); negative looks down.
    float pitch = -0.3f;
    /// Distance from the eye to the target, m, > 0.
    float distance = 20;
    /// Vertical field of view, rad, in (0, pi).
    float fovY = 0.785398f;

    /// Position of the eye, m.
    Eigen::Vector3f eye() const;
    /// Unit vector from the eye towards the target.
    Eigen::Vector3f forward() const;
    /// World-to-eye transform.
    Eigen::Matrix4f view() const;
    /// Perspective projection for a picture `aspect` = width / height wide.
    Eigen::Matrix4f projection(float aspect) const;
    /// Nearest and farthest distances drawn, m (they follow the distance).
    float nearPlane() const;
    float farPlane() const;

    /// The ray through pixel (x, y) of a width x height picture.
    Ray ray(float x, float y, int width, int height) const;
    /// The pixel (x, y) where `point` appears in a width x height picture; none when the
    /// point is behind the eye.
    std::optional<Eigen::Vector2f> project(const Eigen::Vector3f &point, int width, int height) const;

    /// Turns about the target by `dYaw` and `dPitch`, rad (pitch kept within +-85 degrees).
    void orbit(float dYaw, float dPitch);
    /// Moves the target (and the eye with it) across the view by a drag of (dx, dy) pixels
    /// in a picture `height` pixels high, so that the point under the cursor follows it.
    void pan(float dx, float dy, int height);
    /// Multiplies the distance by `factor` (> 0), within [0.5 m, 2 km].
    void zoom(float factor);
    /// Looks at the centre of `bounds` from far enough that its bounding sphere, of at
    /// least `minRadius` m, fits the view of a picture `aspect` wide, keeping the
    /// direction of view.
    void frame(const Bounds &bounds, float aspect, float minRadius = 0.5f);
    /// One frame of follow mode: moves the target the fraction `rate` (in (0, 1]) of the
    /// way to the centre of `bounds`, and the distance as much towards the one frame()
    /// would choose, but never nearer than the distance from which every corner of
    /// `bounds` is in view: what moves never leaves the picture, and the camera glides.
    void follow(const Bounds &bounds, float aspect, float rate, float minRadius);
    /// Puts the eye at `eye` looking at `target` (m; the pitch kept within +-85 degrees,
    /// the distance within [0.5 m, 2 km]).
    void lookAt(const Eigen::Vector3f &eye, const Eigen::Vector3f &target);
    /// Distance from which a sphere of `radius` m about the target fits the view of a
    /// picture `aspect` wide, with a 5 % margin.
    float framingDistance(float radius, float aspect) const;
};

}  // namespace cyclone::viewer
