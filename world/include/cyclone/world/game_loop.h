/// \file
/// A game loop's clock for a World: fixed-size steps taken from the real time of each
/// rendered frame, and body transforms interpolated between the last two steps so that
/// motion looks smooth whatever the frame rate (Glenn Fiedler's "Fix Your Timestep!").
///
/// \code
/// cyclone::FixedStepper stepper(world);            // 60 Hz steps, at most 5 per frame
/// while (running) {
///     stepper.advance(secondsSinceLastFrame,       // 0, 1, 2, ... steps
///                     [&](double dt) { applyInput(world, dt); },
///                     [&](double) { playSounds(world.events()); });
///     for (cyclone::BodyId id : visible) {
///         float model[16];
///         stepper.glTransform(id, model);          // column-major, for OpenGL
///         draw(id, model);
///     }
/// }
/// \endcode
#pragma once

#include <cstdint>
#include <vector>

#include "cyclone/core.h"
#include "cyclone/world/settings.h"
#include "cyclone/world/world.h"

namespace cyclone {

/// Longest frame FixedStepper::advance() takes, s (about 32 years). Why a bound: the time
/// a frame drops is added to droppedSeconds(), and two frames of the largest double made
/// it infinite; at 1e9 s a frame, it stays finite for 1e299 frames.
inline constexpr real kMaxFrameSeconds = 1e9;

/// Settings of a FixedStepper.
struct FixedStepSettings {
    /// Duration of one World::step(), s, in [kMinStep, kMaxStep] = [1e-6, 1]. Every step has this size,
    /// which keeps the simulation stable and reproducible.
    real stepSeconds = real(1) / 60;
    /// Most steps run by one FixedStepper::advance(), in [1, 1000]. When a frame took
    /// longer than this many steps (a stall, a breakpoint, a slow machine), the excess
    /// time is dropped rather than simulated: the game runs slower than real time for
    /// that frame instead of falling further behind with every frame (the "spiral of
    /// death").
    int maxStepsPerFrame = 5;
};

/// Runs a World in fixed steps from variable frame times and interpolates the bodies'
/// transforms for rendering.
///
/// advance(frameSeconds) adds the frame's time to an accumulator and runs as many whole
/// steps as it holds (at most FixedStepSettings::maxStepsPerFrame); what is left, less
/// than one step, carries over to the next frame. Rendering the state of the last step
/// would stutter, so transform() blends the state before the last step with the state
/// after it by alpha() = left-over time / step: the picture shows the world as it was one
/// step ago (between the two states), and moves smoothly.
///
/// The stepper keeps a pointer to the World: the World must outlive it (and must not be
/// moved from). It reads bodies through the World's public calls only, and does not wake
/// anything.
class FixedStepper {
public:
    /// A stepper for `world`; throws InvalidArgument ("FixedStepper::FixedStepper") on
    /// bad settings.
    explicit FixedStepper(World &world, const FixedStepSettings &settings = FixedStepSettings());

    /// The settings in force.
    const FixedStepSettings &settings() const { return settings_; }
    /// Replaces the settings (validated; on refusal nothing changes). The accumulated
    /// time is kept, capped below the new step size.
    void setSettings(const FixedStepSettings &settings);

    /// Adds `frameSeconds` (the real time since the last frame, s, in [0, kMaxFrameSeconds]) and runs
    /// the whole steps it completes, at most FixedStepSettings::maxStepsPerFrame. Returns
    /// the number of steps run. Throws InvalidArgument on a time outside that range
    /// (nothing changes).
    int advance(real frameSeconds) {
        return advance(frameSeconds, [](real) {});
    }

    /// As advance(frameSeconds), calling `beforeStep(stepSeconds)` before each step: the
    /// place to apply a game's forces and impulses, which then act for exactly one step.
    /// If `beforeStep` throws, the frame's remaining steps are skipped.
    template <class BeforeStep>
    int advance(real frameSeconds, BeforeStep &&beforeStep) {
        return advance(frameSeconds, beforeStep, [](real) {});
    }

    /// As advance(frameSeconds, beforeStep), also calling `afterStep(stepSeconds)` after
    /// each step: the place to read World::events(), since each step replaces the events
    /// of the one before and a frame may run several. If a callback throws, the frame's
    /// remaining steps are skipped.
    template <class BeforeStep, class AfterStep>
    int advance(real frameSeconds, BeforeStep &&beforeStep, AfterStep &&afterStep) {
        const int steps = plan(frameSeconds);
        for (int i = 0; i < steps; ++i) {
            beforeStep(settings_.stepSeconds);
            if (i == steps - 1) capture();
            world_->step(settings_.stepSeconds);
            ++totalSteps_;
            afterStep(settings_.stepSeconds);
        }
        return steps;
    }

    /// The interpolation factor of the last advance(), in [0, 1): the left-over time as
    /// a fraction of a step. 0 shows the state before the last step; values near 1 come
    /// close to the state after it.
    real alpha() const { return accumulator_ / settings_.stepSeconds; }
    /// Time accumulated but not yet simulated, s, in [0, stepSeconds).
    real accumulatedSeconds() const { return accumulator_; }
    /// Total time dropped because a frame needed more than maxStepsPerFrame steps, s.
    real droppedSeconds() const { return dropped_; }
    /// Steps run since the stepper was made.
    std::uint64_t totalSteps() const { return totalSteps_; }

    /// The body's transform for rendering: position interpolated linearly and
    /// orientation spherically between the state before the last step and the current
    /// state, by alpha(). A body added (or first seen) after the last step is shown where
    /// it is. Throws InvalidArgument if `id` does not name a body of the World.
    Matrix4 transform(BodyId id) const;

    /// transform(id) as a column-major 4x4 matrix, ready for OpenGL (the layout of
    /// RigidBody::getGLTransform()).
    void glTransform(BodyId id, float matrix[16]) const;

    /// Forgets the state before the last step, so that every body is shown exactly where
    /// it is until the next step: call it after moving bodies by hand (teleporting), or
    /// they are drawn sliding from where they were.
    void resetInterpolation() { capture(); }

private:
    struct Pose {
        std::uint32_t generation = 0;
        bool valid = false;
        Vector3 position = Vector3::Zero();
        Quaternion orientation = Quaternion::Identity();
    };

    int plan(real frameSeconds);
    void capture();

    World *world_;
    FixedStepSettings settings_;
    real accumulator_ = 0;
    real dropped_ = 0;
    std::uint64_t totalSteps_ = 0;
    std::vector<Pose> previous_;  ///< By BodyId::index: the pose before the last step.
    std::vector<BodyId> ids_;     ///< Scratch for World::bodies(), kept between frames.
};

}  // namespace cyclone
