// Springs between bodies (or a body and a world point): their records and the forces
// they exert at the start of every sub-step, explicit (the seed's) or backward Euler.
#pragma once

#include <Eigen/LU>

#include <cstdint>
#include <vector>

#include "world/body_store.h"

namespace cyclone::detail {

struct SpringRecord {
    SpringSettings settings;
    std::uint32_t generation = 0;
    bool alive = false;
    Vector3 implicitForce = Vector3::Zero();  ///< Force on a in the last sub-step, N (the implicit solve's warm start).
    bool implicit = false;                    ///< Backward Euler in this sub-step (SpringSet::chooseForces).
};

/// Passes over the implicit springs per sub-step (block Gauss-Seidel on the coupled system).
inline constexpr int kImplicitSpringPasses = 4;

/// An implicit spring during one sub-step: what stays fixed through the passes.
struct ImplicitSpring {
    std::uint32_t spring = 0;         ///< Index in SpringSet::records.
    bool aMoves = false;
    bool bMoves = false;
    Vector3 pa = Vector3::Zero();     ///< World attachment points, m.
    Vector3 pb = Vector3::Zero();
    Vector3 force0 = Vector3::Zero(); ///< Spring force on a at the sub-step's start, N.
    Matrix3 response = Matrix3::Zero();  ///< h K + C, N s/m.
    Eigen::PartialPivLU<Matrix3> system;  ///< 1 + h (h K + C) W.
};

struct SpringSet {
    std::vector<SpringRecord> records;
    std::vector<std::uint32_t> free;  ///< Slots of removed springs, reused first.
    std::vector<ImplicitSpring> solving;  ///< Scratch of addImplicitForces.

    std::vector<SpringRecord>::iterator begin() { return records.begin(); }
    std::vector<SpringRecord>::iterator end() { return records.end(); }
    std::vector<SpringRecord>::const_iterator begin() const { return records.begin(); }
    std::vector<SpringRecord>::const_iterator end() const { return records.end(); }

    /// Marks the springs that get the backward-Euler force in a sub-step of h seconds;
    /// returns how many.
    int chooseForces(BodyStore &bodies, const WorldSettings &settings, real h);
    /// Adds each explicit spring's force at the bodies' current state (symplectic Euler: stable
    /// while omega h < 2).
    void addExplicitForces(BodyStore &bodies);
    /// Adds the force each implicit spring will exert at the end of a sub-step of h seconds
    /// (backward Euler: never gains energy).
    void addImplicitForces(BodyStore &bodies, real h);

private:
    std::vector<real> load_;  ///< Per body: sum of k (w_a + w_b) of its springs, 1/s^2.
};

}  // namespace cyclone::detail
