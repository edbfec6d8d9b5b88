// The ImGui overlay: the step's profile and counters with a plot of recent step times,
// the run controls, the view toggles, the scene list and the solver settings.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "session.h"
#include "world_view.h"

namespace cyclone::viewer {

/// Run controls shared by the overlay and the keyboard.
struct RunControls {
    /// The simulation waits (the camera still moves).
    bool paused = false;
    /// Simulated time runs at kSlowMotion of real time.
    bool slowMotion = false;
    static constexpr float kSlowMotion = 0.25f;
};

/// What the user asked for through the overlay this frame; the application carries it out.
struct UiRequests {
    bool restart = false;
    bool singleStep = false;
    bool frameScene = false;
    bool shootBall = false;
    /// A scene file to open instead of the current one.
    std::optional<std::string> openScene;
};

/// The overlay and what it remembers between frames.
class Overlay {
public:
    /// Lists the scene files (*.json) of `sceneFolder`, sorted by name.
    explicit Overlay(const std::string &sceneFolder);

    /// Records the World's last step (its total time goes into the plot).
    void recordStep(const StepStats &stats);
    /// Forgets the recorded steps (after a restart or a new scene).
    void clearHistory();

    /// Builds this frame's windows (between ImGui::NewFrame and ImGui::Render).
    /// `frameMs` is the last frame's duration, ms; `problem` a message to show, or "".
    UiRequests draw(Session &session, RunControls &controls, ViewOptions &view, double frameMs,
                    const std::string &problem);

private:
    void drawStats(const Session &session, double frameMs);
    void drawControls(Session &session, RunControls &controls, ViewOptions &view, UiRequests &requests);

    std::vector<std::string> scenes_;
    /// Total step time of the last kHistory steps, ms, oldest first once full.
    std::vector<float> history_;
    std::size_t next_ = 0;
    static constexpr std::size_t kHistory = 300;  // 5 s at 60 steps per second
};

}  // namespace cyclone::viewer
