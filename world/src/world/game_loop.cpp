// FixedStepper: the accumulator and the interpolation of a fixed-step game loop.
#include "cyclone/world/game_loop.h"

#include <cmath>
#include <string>

#include "world/validation.h"

namespace cyclone {
namespace {

// A frame time that leaves the accumulator within this fraction of a step short of a
// whole step completes it: 1/60 added sixty times is not exactly sixty sixtieths, and
// without it a frame now and then would run no step and the next two.
constexpr real kStepTolerance = 1e-9;

void validate(const char *function, const FixedStepSettings &s) {
    if (!(s.stepSeconds >= kMinStep && s.stepSeconds <= kMaxStep))
        detail::refuse(function, "stepSeconds",
                       "must be finite and in [1e-06, 1] s (kMinStep, kMaxStep), got " + detail::show(s.stepSeconds));
    if (s.maxStepsPerFrame < 1 || s.maxStepsPerFrame > 1000)
        detail::refuse(function, "maxStepsPerFrame",
                       "must be in [1, 1000], got " + std::to_string(s.maxStepsPerFrame));
}

}  // namespace

FixedStepper::FixedStepper(World &world, const FixedStepSettings &settings) : world_(&world), settings_(settings) {
    validate("FixedStepper::FixedStepper", settings);
}

void FixedStepper::setSettings(const FixedStepSettings &settings) {
    validate("FixedStepper::setSettings", settings);
    settings_ = settings;
    if (accumulator_ >= settings_.stepSeconds) {
        const real kept = std::fmod(accumulator_, settings_.stepSeconds);
        dropped_ += accumulator_ - kept;
        accumulator_ = kept;
    }
}

int FixedStepper::plan(real frameSeconds) {
    if (!(frameSeconds >= 0 && frameSeconds <= kMaxFrameSeconds))
        detail::refuse("FixedStepper::advance", "frameSeconds",
                       "must be finite and in [0, 1e9] s (kMaxFrameSeconds), got " + detail::show(frameSeconds));
    const real step = settings_.stepSeconds;
    const real total = accumulator_ + frameSeconds;
    // Capped before converting, so that a huge frame time cannot overflow the count.
    const real whole = std::floor(total / step + kStepTolerance);
    const int steps = whole >= settings_.maxStepsPerFrame ? settings_.maxStepsPerFrame : static_cast<int>(whole);
    real left = std::max<real>(0, total - steps * step);
    if (left >= step * (1 - kStepTolerance)) {
        // More than maxStepsPerFrame steps were due: keep the fraction of a step, drop
        // the whole steps beyond the cap.
        const real kept = std::fmod(left, step);
        const real fraction = kept >= step * (1 - kStepTolerance) ? 0 : kept;
        dropped_ += left - fraction;
        left = fraction;
    }
    accumulator_ = left;
    return steps;
}

void FixedStepper::capture() {
    world_->bodies(ids_);
    for (const BodyId &id : ids_) {
        if (id.index >= previous_.size()) previous_.resize(id.index + 1);
        const RigidBody &body = world_->body(id);
        Pose &pose = previous_[id.index];
        pose.generation = id.generation;
        pose.valid = true;
        pose.position = body.getPosition();
        pose.orientation = body.getOrientation();
    }
}

Matrix4 FixedStepper::transform(BodyId id) const {
    if (!world_->contains(id))
        detail::refuse("FixedStepper::transform", "id",
                       "does not name a body of the world (index " + std::to_string(id.index) + ", generation " +
                           std::to_string(id.generation) + ")");
    const RigidBody &body = world_->body(id);
    Vector3 position = body.getPosition();
    Quaternion orientation = body.getOrientation();
    if (id.index < previous_.size() && previous_[id.index].valid && previous_[id.index].generation == id.generation) {
        const Pose &before = previous_[id.index];
        const real t = alpha();
        position = before.position + t * (position - before.position);
        orientation = before.orientation.slerp(t, orientation);
    }
    Matrix4 transform = Matrix4::Identity();
    transform.linear() = orientation.toRotationMatrix();
    transform.translation() = position;
    return transform;
}

void FixedStepper::glTransform(BodyId id, float matrix[16]) const {
    const Matrix4 t = transform(id);
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) matrix[col * 4 + row] = static_cast<float>(t.matrix()(row, col));
}

}  // namespace cyclone
