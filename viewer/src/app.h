// The viewer application: a GLFW window with an OpenGL 3.3 core context, the ImGui
// overlay, the camera and mouse, and the frame loop, interactive or headless.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "camera.h"
#include "character_mode.h"
#include "options.h"
#include "renderer.h"
#include "session.h"
#include "ui.h"
#include "world_view.h"

struct GLFWwindow;

namespace cyclone::viewer {

/// The window and everything drawn in it.
class App {
public:
    /// Opens the scene and the window; throws scene::SceneError on a bad scene file,
    /// std::invalid_argument when --follow names no body of the scene, and
    /// std::runtime_error when no window or OpenGL 3.3 context can be had.
    explicit App(const Options &options);
    ~App();
    App(const App &) = delete;
    App &operator=(const App &) = delete;

    /// Runs until the window closes (or for Options::frames frames); returns the exit status.
    int run();

private:
    enum class Drag { None, Orbit, Pan, Body };

    /// GLFW's key callback (chained by ImGui's backend): queues presses, so that a key
    /// pressed and released within one slow frame still counts.
    static void onKey(GLFWwindow *window, int key, int scancode, int action, int mods);

    void handleMouse();
    void handleKeys(UiRequests &requests);
    void carryOut(const UiRequests &requests);
    void openScene(const std::string &path);
    void shootBall();
    /// C: turns the character mode on at the camera's target (on the ground below it) or off.
    void toggleCharacter();
    /// In the character mode: W, A, S, D and Space held drive the character; the camera follows.
    void walk();
    /// Frames what the camera follows and follows it again (or puts a --camera back).
    void frameScene();
    /// What follow mode keeps in view: the --follow body, or every moving body and the
    /// springs' anchors.
    Bounds followedBounds() const;
    float aspect() const;
    /// Simulates `seconds` of time (scaled by slow motion); records the steps run.
    void simulate(double seconds);
    /// Draws the world and the overlay into the back buffer.
    void render();

    Options options_;
    GLFWwindow *window_ = nullptr;
    std::unique_ptr<Session> session_;
    std::unique_ptr<Renderer> renderer_;
    WorldView worldView_;
    std::unique_ptr<Overlay> overlay_;
    OrbitCamera camera_;
    CharacterMode character_;
    RunControls controls_;
    ViewOptions view_;
    Drag drag_ = Drag::None;
    /// Distance along the view direction of the plane a held body is dragged in, m.
    float grabDepth_ = 0;
    std::string problem_;
    /// Follow mode: the camera glides to keep followedBounds() in view; moving the
    /// camera by hand (pan, zoom) or a fixed --camera turns it off, F turns it on.
    bool following_ = true;
    /// Keys pressed (or repeated) since the last frame, GLFW key codes.
    std::vector<int> pressedKeys_;
};

}  // namespace cyclone::viewer
