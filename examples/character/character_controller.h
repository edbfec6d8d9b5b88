// A capsule character that walks over steps and slopes, moved by World::shapeCast alone
// (a kinematic controller: the World's bodies do not push it).
//
// Each move: cast the capsule along the wanted motion; where a wall too steep to walk
// stops it, try the same motion lifted by the step height and set down again (a stair);
// else slide along the wall. Then cast down to keep the feet on the ground or fall.
#pragma once

#include <cmath>
#include <optional>

#include <cyclone/world.h>

namespace character {

using cyclone::Quaternion;
using cyclone::real;
using cyclone::Shape;
using cyclone::Vector3;
using cyclone::World;

struct CharacterSettings {
    real radius = 0.3;        ///< Capsule radius, m.
    real length = 1.0;        ///< Capsule's cylindrical part, m (height = length + 2 radius).
    real stepHeight = 0.25;   ///< Highest step climbed, m.
    real maxSlope = 0.8;      ///< Steepest walkable ground, rad (about 46 degrees).
    real skin = 0.005;        ///< Gap kept from what the capsule touches, m.
    real gravity = 9.81;      ///< Fall acceleration, m/s^2.
};

class CharacterController {
public:
    CharacterController(const World &world, const Vector3 &centre, const CharacterSettings &settings = {})
        : world_(world), settings_(settings), centre_(centre),
          shape_(Shape::capsule(settings.radius, settings.length)),
          // The capsule's axis is local z: stood up along y.
          upright_(Eigen::AngleAxis<real>(-1.5707963267948966, Vector3::UnitX())) {}

    /// Walks at `velocity` (horizontal, m/s) for dt seconds.
    void move(const Vector3 &velocity, real dt) {
        Vector3 motion(velocity.x() * dt, 0, velocity.z() * dt);
        for (int slide = 0; slide < 3 && motion.norm() > 1e-9; ++slide) {
            const auto hit = cast(centre_, motion);
            if (!hit) {
                centre_ += motion;
                break;
            }
            if (walkable(hit->normal)) {  // a slope: follow it
                centre_ += advance(motion, hit->fraction);
                motion = (1 - hit->fraction) * along(motion, hit->normal);
                continue;
            }
            if (climb(motion)) break;
            centre_ += advance(motion, hit->fraction);
            // Slide along the wall: the motion less its part into the wall, kept level.
            Vector3 wall(hit->normal.x(), 0, hit->normal.z());
            if (wall.norm() < 1e-9) break;
            wall.normalize();
            motion = (1 - hit->fraction) * motion;
            motion -= motion.dot(wall) * wall;
        }
        fall(dt);
    }

    /// Centre of the capsule, m.
    const Vector3 &centre() const { return centre_; }
    /// Whether the feet were on walkable ground after the last move.
    bool grounded() const { return grounded_; }

private:
    std::optional<cyclone::ShapeCastHit> cast(const Vector3 &from, const Vector3 &motion) const {
        if (motion.norm() < 1e-12) return std::nullopt;
        return world_.shapeCast(shape_, from, upright_, motion);
    }

    real feet() const { return centre_.y() - settings_.length / 2 - settings_.radius; }

    bool walkable(const Vector3 &normal) const { return normal.y() >= std::cos(settings_.maxSlope); }

    // The part of `motion` that keeps `skin` clear of what stopped it at `fraction`.
    Vector3 advance(const Vector3 &motion, real fraction) const {
        const real length = motion.norm();
        return motion * std::max(real(0), fraction - settings_.skin / length);
    }

    // The motion turned to run along a walkable surface of normal n, same horizontal reach.
    static Vector3 along(const Vector3 &motion, const Vector3 &n) {
        return Vector3(motion.x(), -(n.x() * motion.x() + n.z() * motion.z()) / n.y(), motion.z());
    }

    // Up by the step height, across, and down onto a walkable top: false when blocked.
    bool climb(const Vector3 &motion) {
        const Vector3 up(0, settings_.stepHeight, 0);
        if (cast(centre_, up)) return false;
        const Vector3 raised = centre_ + up;
        if (const auto across = cast(raised, motion); across && across->fraction < 1) return false;
        const Vector3 over = raised + motion;
        const auto down = cast(over, -up);
        if (!down) return false;
        if (!walkable(down->normal)) {
            // Set down on the step's edge: the surface just beyond the edge decides.
            const Vector3 probe = down->point + 0.01 * motion.normalized() + Vector3(0, 0.01, 0);
            const auto ground = world_.rayCast(probe, Vector3(0, -1, 0), 0.05);
            if (!ground || !walkable(ground->normal)) return false;
            if (ground->point.y() - feet() > settings_.stepHeight) return false;
        }
        centre_ = over + advance(-up, down->fraction);
        return true;
    }

    void fall(real dt) {
        fallSpeed_ += settings_.gravity * dt;
        // Falling, or held to the ground within a step's height when walking down.
        const real drop = grounded_ ? std::max(fallSpeed_ * dt, settings_.stepHeight) : fallSpeed_ * dt;
        const auto hit = cast(centre_, Vector3(0, -drop, 0));
        if (hit && walkable(hit->normal)) {
            centre_ += advance(Vector3(0, -drop, 0), hit->fraction);
            fallSpeed_ = 0;
            grounded_ = true;
            return;
        }
        grounded_ = false;
        centre_.y() -= fallSpeed_ * dt;
    }

    const World &world_;
    CharacterSettings settings_;
    Vector3 centre_;
    Shape shape_;
    Quaternion upright_;
    real fallSpeed_ = 0;
    bool grounded_ = true;
};

}  // namespace character
