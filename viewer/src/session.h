// A scene being watched: the scene file, its World and the FixedStepper that runs it live,
// with the scene's scripted events, and what the user does to it (restart, drag a body
// with a mouse joint, shoot a ball). No window or GL here: tests use it as it is.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cyclone/world/game_loop.h"
#include "scene.h"
#include "scene_world.h"

namespace cyclone::viewer {

/// What a body's colour says about it. A new kind of body is one more value here, one
/// more case in Session::state() and one more colour in stateColor() (palette.h).
enum class BodyState {
    Static,     ///< Never moves.
    Awake,      ///< Dynamic and simulated.
    Asleep,     ///< Dynamic and sleeping.
    NonFinite,  ///< Isolated by the World: its state became non-finite or left the 1e12 m range.
    Kinematic,  ///< Moved only at the velocity the scene sets.
    Sensor,     ///< Reports what overlaps it, pushes nothing (whatever its motion).
};

/// A body held by the mouse: a mouse joint (JointType::Mouse) pulls a point of the body
/// to a world point that the cursor moves.
struct Grab {
    BodyId body;
    /// The mouse joint that pulls it.
    JointId joint;
    /// The point held, in the body's space, m.
    Vector3 localPoint = Vector3::Zero();
    /// Where the cursor pulls it, world space, m.
    Vector3 target = Vector3::Zero();
};

/// Settings of the ball shot from the camera.
struct BallSettings {
    /// Radius, m, > 0.
    real radius = 0.3;
    /// Mass, kg, > 0.
    real mass = 5;
    /// Launch speed, m/s, > 0.
    real speed = 30;
};

/// A loaded scene and its running World.
class Session {
public:
    /// Loads the scene file at `path` as the runner does (scene_file.h) and builds its
    /// World; throws scene::SceneError (with the file's name in the message, the place
    /// naming its body or joint) or std::runtime_error when it cannot. With `strict`, a
    /// field the format has not is refused, as cyclone-world --strict does.
    explicit Session(const std::string &path, bool strict = false);

    /// The scene file's path.
    const std::string &path() const { return path_; }
    /// The scene as loaded.
    const scene::Scene &scene() const { return scene_; }
    /// The runner's warnings about the fields the format has not, one line each
    /// ("FILE: PLACE: unknown field; did you mean ...?"), or "".
    const std::string &warnings() const { return warnings_; }
    World &world() { return built_->world; }
    const World &world() const { return built_->world; }
    FixedStepper &stepper() { return *stepper_; }
    const FixedStepper &stepper() const { return *stepper_; }

    /// Builds the World again from the scene, with the solver settings in force kept.
    void restart();

    /// Runs the steps that `frameSeconds` of simulated time complete (FixedStepper::advance),
    /// applying the scene's events due at each step. Returns the number of steps run. An
    /// event the World refuses is skipped and kept in lastProblem().
    int advance(real frameSeconds);
    /// Runs exactly one step.
    void singleStep();
    /// Duration of one step, s.
    real stepSeconds() const { return stepper_->settings().stepSeconds; }

    /// Replaces the World's settings (World::setSettings: validated, wakes every body);
    /// kept across restart().
    void setSettings(const WorldSettings &settings);

    /// Holds the dynamic body the ray from `origin` along `direction` meets first, at the
    /// point met, with a mouse joint; returns false (nothing held) when it meets none.
    bool grab(const Vector3 &origin, const Vector3 &direction);
    /// Moves the point the held body is pulled to (World::setMouseTarget), m.
    void moveGrab(const Vector3 &target);
    /// Lets the held body go.
    void release();
    /// The body held, if any.
    const std::optional<Grab> &grabbed() const { return grab_; }

    /// Adds a ball at `origin` moving along `direction` (unit) at the ball's speed.
    void shootBall(const Vector3 &origin, const Vector3 &direction, const BallSettings &ball = BallSettings());

    /// Keeps the World's state (World::saveState) and the scene's place in its events, for
    /// rewind(); replaces the one kept before.
    void keep();
    /// Puts the World back in the state keep() kept (bodies shot or grabbed since are let
    /// go), the scene's events following from there; false when nothing was kept.
    bool rewind();
    /// Whether keep() has kept a state.
    bool kept() const { return !keptState_.empty(); }
    /// The step the scene's events count to: the stepper's steps since the World was
    /// built or rewound, plus the steps before that.
    std::int64_t sceneStep() const { return stepsBefore_ + static_cast<std::int64_t>(stepper_->totalSteps()); }
    /// The state a body's colour shows.
    BodyState state(BodyId id) const;
    /// The scene's springs whose bodies are all still in the World, and the grab's pull
    /// from the held point to its target, as world-space end points (pairs), for drawing.
    std::vector<Vector3> springLines() const;
    /// The last thing that went wrong while running (a refused event), or "".
    const std::string &lastProblem() const { return problem_; }

private:
    void build();
    void applyEvents(std::int64_t step);

    std::string path_;
    scene::Scene scene_;
    std::string warnings_;
    std::unique_ptr<scene::SceneWorld> built_;
    std::unique_ptr<FixedStepper> stepper_;
    std::vector<std::size_t> eventOrder_;  ///< Indices of scene_.events by step (stable).
    std::size_t nextEvent_ = 0;
    std::vector<bool> present_;            ///< By scene body: not removed by an event.
    std::optional<Grab> grab_;
    std::string problem_;
    std::int64_t stepsBefore_ = 0;          ///< Steps taken before the stepper was made (rewind).
    std::vector<std::uint8_t> keptState_;   ///< keep()'s World state; empty: none.
    std::int64_t keptStep_ = 0;             ///< The scene step it was kept at.
    std::size_t keptNextEvent_ = 0;
    std::vector<bool> keptPresent_;
};

}  // namespace cyclone::viewer
