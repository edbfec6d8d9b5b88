/// \file
/// The pre-solve contact callback: World::setContactListener's ContactListener sees each
/// contact manifold the step is about to solve and may disable it or change how it is
/// solved (one-way platforms, conveyor belts, surfaces of their own).
#pragma once

#include "cyclone/core.h"
#include "cyclone/world/settings.h"

namespace cyclone {

/// Most points of a contact manifold.
inline constexpr int kMaxContactPoints = 4;

/// A contact manifold the step is about to solve: what it is (read only) and how it will
/// be solved (the fields a listener may change).
struct PreSolveContact {
    /// One body of the pair (the one with the smaller BodyId::index).
    BodyId a;
    /// The other body.
    BodyId b;
    /// Unit contact normal, world space, from `a` towards `b`.
    Vector3 normal = Vector3::UnitY();
    /// Points in use, in [1, kMaxContactPoints].
    int pointCount = 0;
    /// World-space contact points, midway between the two surfaces, m.
    Vector3 points[kMaxContactPoints];
    /// Penetration at each point when the step began, m (< 0: apart, a speculative contact).
    real depths[kMaxContactPoints] = {};

    /// False: the manifold is not solved this step (the bodies pass through each other
    /// there); its contact stays in the contact events.
    bool enabled = true;
    /// Coulomb coefficient, >= 0, finite; starts as the geometric mean of the materials'.
    real friction = 0;
    /// Restitution in [0, 1]; starts as the larger of the materials'.
    real restitution = 0;
    /// Velocity of b's surface relative to a's, world space, m/s, finite: the friction
    /// drives the bodies' relative sliding towards it, as on a conveyor belt (only its part
    /// in the contact's plane acts). Starts as the bodies' BodySettings::surfaceVelocity.
    Vector3 surfaceVelocity = Vector3::Zero();
};

/// Receives each contact manifold before the solver sees it (World::setContactListener).
///
/// preSolve is called once per manifold that will be solved in the step, after the
/// built-in rules (BodySettings::oneWay and surfaceVelocity) have set it up, from the
/// thread that called World::step, in the solver's order (the same from run to run), so
/// that the step stays deterministic. It must not call the World. A value it sets out of
/// range (a negative or non-finite friction, a restitution outside [0, 1], a non-finite
/// surface velocity) makes World::step throw InvalidArgument before any body moves.
class ContactListener {
public:
    virtual ~ContactListener() = default;
    /// Sees, and may change, one manifold about to be solved.
    virtual void preSolve(PreSolveContact &contact) = 0;
};

}  // namespace cyclone
