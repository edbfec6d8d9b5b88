#include "session.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "run_loop.h"
#include "scene_file.h"
#include "scene_loader.h"

namespace cyclone::viewer {

namespace {

// The grab's mouse joint pulls at this frequency (Hz) and damping ratio whatever the mass
// held (JointPull), with at most this many times the held body's weight: enough to lift
// a ragdoll by its hand, not enough to fling a light body through a wall.
constexpr real kGrabFrequency = 5;
constexpr real kGrabDampingRatio = 0.7;
constexpr real kGrabWeights = 100;

std::string readFile(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string stem(const std::string &path) {
    const std::size_t slash = path.find_last_of('/');
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    const std::size_t dot = name.rfind('.');
    return dot == std::string::npos ? name : name.substr(0, dot);
}

}  // namespace

Session::Session(const std::string &path, bool strict) : path_(path) {
    try {
        scene::SceneFile file(readFile(path), stem(path), strict);
        std::ostringstream warnings;
        file.writeWarnings(warnings, path);
        warnings_ = warnings.str();
        scene_ = std::move(file.scene());
    } catch (const scene::SceneError &error) {
        throw scene::SceneError(path + ": " + error.path(), error.message());
    }
    eventOrder_.resize(scene_.events.size());
    std::iota(eventOrder_.begin(), eventOrder_.end(), std::size_t{0});
    std::stable_sort(eventOrder_.begin(), eventOrder_.end(),
                     [&](std::size_t x, std::size_t y) { return scene_.events[x].step < scene_.events[y].step; });
    build();
}

void Session::build() {
    stepper_.reset();
    grab_.reset();
    built_ = std::make_unique<scene::SceneWorld>(scene::buildWorld(scene_));
    FixedStepSettings steps;
    steps.stepSeconds = scene_.dt;
    stepper_ = std::make_unique<FixedStepper>(built_->world, steps);
    nextEvent_ = 0;
    stepsBefore_ = 0;
    present_.assign(scene_.bodies.size(), true);
    problem_.clear();
}

void Session::keep() {
    keptState_ = world().saveState();
    keptStep_ = sceneStep();
    keptNextEvent_ = nextEvent_;
    keptPresent_ = present_;
}

bool Session::rewind() {
    if (keptState_.empty()) return false;
    release();
    world().restoreState(keptState_);
    const FixedStepSettings steps = stepper_->settings();
    stepper_ = std::make_unique<FixedStepper>(built_->world, steps);
    stepsBefore_ = keptStep_;
    nextEvent_ = keptNextEvent_;
    present_ = keptPresent_;
    return true;
}

void Session::restart() {
    const WorldSettings settings = world().settings();
    build();
    world().setSettings(settings);
}

void Session::setSettings(const WorldSettings &settings) { world().setSettings(settings); }

void Session::applyEvents(std::int64_t step) {
    for (; nextEvent_ < eventOrder_.size() && scene_.events[eventOrder_[nextEvent_]].step <= step; ++nextEvent_) {
        const scene::SceneEvent &event = scene_.events[eventOrder_[nextEvent_]];
        if (event.step < step || !present_[event.body]) continue;
        const BodyId id = built_->ids[event.body];
        try {
            if (event.kind == scene::EventKind::Remove && grab_ && grab_->body == id) release();
            scene::applyEvent(world(), id, event);
            if (event.kind == scene::EventKind::Remove) present_[event.body] = false;
        } catch (const InvalidArgument &error) {
            problem_ = event.path + " (step " + std::to_string(step) + "): " + error.what();
        }
    }
}

int Session::advance(real frameSeconds) {
    return stepper_->advance(frameSeconds, [&](real) { applyEvents(sceneStep()); });
}

void Session::singleStep() {
    // A whole step more than what is accumulated runs exactly one step.
    advance(stepSeconds());
}

bool Session::grab(const Vector3 &origin, const Vector3 &direction) {
    release();
    QueryFilter filter;
    filter.staticBodies = false;
    const std::optional<RayHit> hit = world().rayCast(origin, direction, std::numeric_limits<real>::infinity(), filter);
    if (!hit) return false;
    Grab held;
    held.body = hit->body;
    held.localPoint = world().body(hit->body).getPointInLocalSpace(hit->point);
    held.target = hit->point;
    JointSettings mouse;
    mouse.type = JointType::Mouse;
    mouse.a = hit->body;
    mouse.anchor = hit->point;
    JointPull pull;
    pull.frequency = kGrabFrequency;
    pull.dampingRatio = kGrabDampingRatio;
    pull.maxForce = kGrabWeights * world().body(hit->body).getMass() * world().settings().gravity.norm();
    // Without gravity, a weight means nothing: the pull is then unbounded.
    if (!(pull.maxForce > 0)) pull.maxForce = std::numeric_limits<real>::infinity();
    mouse.pull = pull;
    held.joint = world().addJoint(mouse);
    grab_ = held;
    return true;
}

void Session::moveGrab(const Vector3 &target) {
    if (!grab_ || !world().contains(grab_->joint)) return;
    try {
        world().setMouseTarget(grab_->joint, target);
        grab_->target = target;
    } catch (const InvalidArgument &) {
        // A cursor ray gone far or non-finite: the target stays where it was.
    }
}

void Session::release() {
    if (grab_ && world().contains(grab_->joint)) world().removeJoint(grab_->joint);
    grab_.reset();
}

void Session::shootBall(const Vector3 &origin, const Vector3 &direction, const BallSettings &ball) {
    BodySettings body;
    body.shape = Shape::sphere(ball.radius);
    body.mass = ball.mass;
    body.position = origin;
    body.velocity = direction.normalized() * ball.speed;
    body.ccd = true;
    world().addBody(body);
}

BodyState Session::state(BodyId id) const {
    if (world().isSensor(id)) return BodyState::Sensor;
    if (world().motion(id) == Motion::Static) return BodyState::Static;
    const RigidBody &body = world().body(id);
    if (!scene::hasFiniteState(body)) return BodyState::NonFinite;
    if (world().motion(id) == Motion::Kinematic) return BodyState::Kinematic;
    return body.getAwake() ? BodyState::Awake : BodyState::Asleep;
}

std::vector<Vector3> Session::springLines() const {
    std::vector<Vector3> lines;
    for (const scene::SceneSpring &spring : scene_.springs) {
        if (!present_[spring.a] || (spring.b && !present_[*spring.b])) continue;
        lines.push_back(world().body(built_->ids[spring.a]).getPointInWorldSpace(spring.settings.aPoint));
        lines.push_back(spring.b ? world().body(built_->ids[*spring.b]).getPointInWorldSpace(spring.settings.bPoint)
                                 : spring.settings.bPoint);
    }
    if (grab_) {
        lines.push_back(world().body(grab_->body).getPointInWorldSpace(grab_->localPoint));
        lines.push_back(grab_->target);
    }
    return lines;
}

}  // namespace cyclone::viewer
