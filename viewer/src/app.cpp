#include "app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "scene_fields.h"
#include "screenshot.h"

namespace cyclone::viewer {

namespace {

// Simulated time of one headless frame, s: a fixed frame makes --frames runs repeatable.
constexpr double kHeadlessFrameSeconds = 1.0 / 60.0;
// Radians of orbit per pixel dragged, and the zoom factor per wheel notch.
constexpr float kOrbitPerPixel = 0.005f;
constexpr float kZoomPerNotch = 0.88f;
// Frames left out of --benchmark's mean: Mesa compiles shaders on their first draws.
constexpr int kWarmUpFrames = 10;
// Follow mode: the camera covers this share of the way to its goal in 1/60 s (a time
// constant of about 0.15 s), and frames at least this radius, m, so that a small body
// is seen with what lies around it (a ragdoll with its stairs).
constexpr double kFollowRatePerFrame = 0.1;
constexpr float kFollowMinRadius = 2.5f;

void reportGlfwError(int code, const char *message) { std::fprintf(stderr, "cyclone-viewer: GLFW error %d: %s\n", code, message); }

Vector3 toReal(const Eigen::Vector3f &v) { return v.cast<real>(); }

}  // namespace

App::App(const Options &options) : options_(options) {
    session_ = std::make_unique<Session>(options.scene, options.strict);
    std::fputs(session_->warnings().c_str(), stderr);
    if (!options.follow.empty() && !session_->world().findBody(options.follow)) {
        std::vector<std::string> names;
        for (const scene::SceneBody &body : session_->scene().bodies) names.push_back(body.settings.name);
        throw std::invalid_argument("--follow: " + options.scene + " has no body named \"" + options.follow + "\"" +
                                 scene::didYouMean(options.follow, names));
    }
    overlay_ = std::make_unique<Overlay>(std::filesystem::path(options.scene).parent_path().empty()
                                             ? std::string(".")
                                             : std::filesystem::path(options.scene).parent_path().string());
    view_.contacts = options.contacts;

    glfwSetErrorCallback(reportGlfwError);
    if (glfwInit() != GLFW_TRUE) {
        throw std::runtime_error("cannot open a window: no display (without one, run under xvfb-run)");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, options.frames ? GLFW_FALSE : GLFW_TRUE);
    const std::string title = "cyclone-viewer: " + session_->scene().name;
    window_ = glfwCreateWindow(options.width, options.height, title.c_str(), nullptr, nullptr);
    if (window_ == nullptr) {
        glfwTerminate();
        throw std::runtime_error("cannot open a window with an OpenGL 3.3 core context");
    }
    glfwMakeContextCurrent(window_);
    // Interactive frames follow the display; headless ones run as fast as they can.
    glfwSwapInterval(options.frames ? 0 : 1);

    // Installed before ImGui's backend, which calls it after its own.
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, onKey);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    renderer_ = std::make_unique<Renderer>();
    frameScene();
}

App::~App() {
    worldView_.clear();
    renderer_.reset();
    if (window_ != nullptr) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
}

float App::aspect() const {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
}

Bounds App::followedBounds() const {
    const World &world = session_->world();
    if (!options_.follow.empty()) {
        const std::optional<BodyId> id = world.findBody(options_.follow);
        if (!id || !world.body(*id).getPosition().allFinite()) return Bounds();
        return bodyBounds(world, *id);
    }
    Bounds bounds = sceneBounds(world);
    // A spring's world anchor belongs in the picture with the body it holds.
    for (const Vector3 &end : session_->springLines()) bounds.add(end.cast<float>());
    return bounds;
}

void App::frameScene() {
    if (options_.cameraEye) {
        camera_.lookAt(*options_.cameraEye, options_.cameraTarget);
        following_ = false;
        return;
    }
    camera_.frame(followedBounds(), aspect(), kFollowMinRadius);
    following_ = true;
}

void App::openScene(const std::string &path) {
    try {
        auto next = std::make_unique<Session>(path, options_.strict);
        session_ = std::move(next);
        character_.forget();
        std::fputs(session_->warnings().c_str(), stderr);
    } catch (const std::exception &error) {
        problem_ = error.what();
        return;
    }
    worldView_.clear();
    overlay_->clearHistory();
    problem_.clear();
    drag_ = Drag::None;
    glfwSetWindowTitle(window_, ("cyclone-viewer: " + session_->scene().name).c_str());
    frameScene();
}

void App::shootBall() {
    double x = 0, y = 0;
    int width = 0, height = 0;
    glfwGetCursorPos(window_, &x, &y);
    glfwGetWindowSize(window_, &width, &height);
    const bool inside = x >= 0 && y >= 0 && x < width && y < height;
    const Ray ray = inside ? camera_.ray(static_cast<float>(x), static_cast<float>(y), width, height)
                           : Ray{camera_.eye(), camera_.forward()};
    // The ball is a moving body: following it would pull the camera after it.
    following_ = false;
    try {
        session_->shootBall(toReal(ray.origin), toReal(ray.direction));
    } catch (const std::exception &error) {
        problem_ = error.what();
    }
}

void App::toggleCharacter() {
    World &world = session_->world();
    if (character_.on()) {
        character_.stop(world);
        return;
    }
    const Vector3 target = toReal(camera_.target);
    const auto ground = world.rayCast(target + Vector3(0, 50, 0), Vector3(0, -1, 0));
    try {
        character_.start(world, ground ? ground->point : target);
    } catch (const std::exception &error) {
        problem_ = error.what();
    }
}

void App::walk() {
    if (!character_.on() || options_.frames) return;
    WalkKeys keys;
    const bool typing = ImGui::GetIO().WantCaptureKeyboard;
    const auto held = [&](int key) { return !typing && glfwGetKey(window_, key) == GLFW_PRESS; };
    keys.forward = held(GLFW_KEY_W);
    keys.back = held(GLFW_KEY_S);
    keys.left = held(GLFW_KEY_A);
    keys.right = held(GLFW_KEY_D);
    keys.jump = held(GLFW_KEY_SPACE);
    character_.drive(session_->world(), keys, toReal(camera_.forward()));
    camera_.target = character_.focus(session_->world()).cast<float>();
}

void App::handleMouse() {
    const ImGuiIO &io = ImGui::GetIO();
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    if (width <= 0 || height <= 0) return;
    const Ray ray = camera_.ray(io.MousePos.x, io.MousePos.y, width, height);

    if (!io.WantCaptureMouse) {
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
            if (io.KeyShift) {
                drag_ = Drag::Pan;
            } else if (session_->grab(toReal(ray.origin), toReal(ray.direction))) {
                drag_ = Drag::Body;
                const Vector3 held = session_->grabbed()->target;
                grabDepth_ = (held.cast<float>() - ray.origin).dot(camera_.forward());
            } else {
                drag_ = Drag::Orbit;
            }
        }
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Right) || ImGui::IsMouseClicked(ImGuiMouseButton_Middle)) {
            drag_ = Drag::Pan;
        }
        if (io.MouseWheel != 0) {
            camera_.zoom(std::pow(kZoomPerNotch, io.MouseWheel));
            following_ = false;
        }
    }

    const bool anyDown = ImGui::IsMouseDown(ImGuiMouseButton_Left) || ImGui::IsMouseDown(ImGuiMouseButton_Right) ||
                         ImGui::IsMouseDown(ImGuiMouseButton_Middle);
    const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    const bool moved = std::isfinite(dx) && std::isfinite(dy) && (dx != 0 || dy != 0);
    switch (drag_) {
    case Drag::Orbit:
        if (moved) camera_.orbit(-dx * kOrbitPerPixel, -dy * kOrbitPerPixel);
        break;
    case Drag::Pan:
        if (moved) {
            camera_.pan(dx, dy, height);
            following_ = false;
        }
        break;
    case Drag::Body: {
        const float along = ray.direction.dot(camera_.forward());
        if (along > 1e-4f) session_->moveGrab(toReal(ray.origin + ray.direction * (grabDepth_ / along)));
        break;
    }
    case Drag::None: break;
    }
    if (!anyDown) {
        if (drag_ == Drag::Body) session_->release();
        drag_ = Drag::None;
    }
}

void App::onKey(GLFWwindow *window, int key, int, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    auto *app = static_cast<App *>(glfwGetWindowUserPointer(window));
    // A held key repeats only the actions that make sense many times in a row.
    if (action == GLFW_REPEAT && key != GLFW_KEY_N && key != GLFW_KEY_B) return;
    app->pressedKeys_.push_back(key);
}

void App::handleKeys(UiRequests &requests) {
    std::vector<int> keys;
    keys.swap(pressedKeys_);
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    for (int key : keys) {
        // In the character mode Space jumps and S walks back (walk() reads them held).
        if (character_.on() && (key == GLFW_KEY_SPACE || key == GLFW_KEY_S)) continue;
        switch (key) {
        case GLFW_KEY_C: toggleCharacter(); break;
        case GLFW_KEY_SPACE: controls_.paused = !controls_.paused; break;
        case GLFW_KEY_N: requests.singleStep = true; break;
        case GLFW_KEY_R: requests.restart = true; break;
        case GLFW_KEY_S: controls_.slowMotion = !controls_.slowMotion; break;
        case GLFW_KEY_F: requests.frameScene = true; break;
        case GLFW_KEY_B: requests.shootBall = true; break;
        case GLFW_KEY_F5: session_->keep(); break;
        case GLFW_KEY_F9: session_->rewind(); break;
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
        default: break;
        }
    }
}

void App::carryOut(const UiRequests &requests) {
    if (requests.openScene) {
        openScene(*requests.openScene);
        return;
    }
    if (requests.restart) {
        character_.forget();
        session_->restart();
        worldView_.clear();
        overlay_->clearHistory();
        problem_.clear();
        drag_ = Drag::None;
    }
    if (requests.singleStep) {
        controls_.paused = true;
        session_->singleStep();
        overlay_->recordStep(session_->world().stats());
    }
    if (requests.frameScene) frameScene();
    if (requests.shootBall) shootBall();
}

void App::simulate(double seconds) {
    if (controls_.paused) return;
    const double scale = controls_.slowMotion ? RunControls::kSlowMotion : 1.0;
    try {
        if (session_->advance(static_cast<real>(seconds * scale)) > 0) overlay_->recordStep(session_->world().stats());
    } catch (const std::exception &error) {
        problem_ = error.what();
        controls_.paused = true;
    }
    if (problem_.empty() && !session_->lastProblem().empty()) problem_ = session_->lastProblem();
}

void App::render() {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    const float ratio = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
    renderer_->beginFrame(width, height, camera_.projection(ratio) * camera_.view(), camera_.eye());
    worldView_.draw(*renderer_, *session_, view_);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

int App::run() {
    using Clock = std::chrono::steady_clock;
    const int frames = options_.frames.value_or(0);
    double lastFrameMs = 0;
    auto last = Clock::now();
    const auto start = last;
    auto warm = last;
    std::clock_t warmCpu = std::clock();
    // Each frame's wall-clock time after the warm-up, for --benchmark's 95th percentile.
    std::vector<double> frameMs;
    if (options_.benchmark) frameMs.reserve(static_cast<std::size_t>(std::max(frames, 0)));
    int frame = 0;
    while (!glfwWindowShouldClose(window_) && (!options_.frames || frame < frames)) {
        glfwPollEvents();
        const auto now = Clock::now();
        const double realSeconds = std::chrono::duration<double>(now - last).count();
        last = now;
        if (frame > 0) lastFrameMs = realSeconds * 1000;
        if (options_.benchmark && frame > kWarmUpFrames) frameMs.push_back(lastFrameMs);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        UiRequests requests;
        if (!options_.frames) {
            handleMouse();
            handleKeys(requests);
        }
        if (!options_.hideUi) {
            const UiRequests clicked = overlay_->draw(*session_, controls_, view_, lastFrameMs, problem_);
            requests.restart |= clicked.restart;
            requests.singleStep |= clicked.singleStep;
            requests.frameScene |= clicked.frameScene;
            requests.shootBall |= clicked.shootBall;
            if (clicked.openScene) requests.openScene = clicked.openScene;
        }
        carryOut(requests);
        walk();
        const double frameSeconds = options_.frames ? kHeadlessFrameSeconds : std::min(realSeconds, 0.25);
        simulate(frameSeconds);
        if (following_) {
            const double rate = 1 - std::pow(1 - kFollowRatePerFrame, frameSeconds / kHeadlessFrameSeconds);
            camera_.follow(followedBounds(), aspect(), static_cast<float>(rate), kFollowMinRadius);
        }
        // The last frame is shown only now: its picture was handed to the renderer (glFlush)
        // before this frame's simulation, so that a software renderer's threads draw it
        // while this thread steps the World.
        if (frame > 0) glfwSwapBuffers(window_);
        render();
        glFlush();
        ++frame;
        if (options_.frames && frame == frames && !options_.screenshot.empty()) {
            int width = 0, height = 0;
            glfwGetFramebufferSize(window_, &width, &height);
            writeScreenshot(options_.screenshot, width, height);
        }
        if (frame == kWarmUpFrames) {
            glFinish();
            warm = Clock::now();
            warmCpu = std::clock();
        }
    }
    if (frame > 0) glfwSwapBuffers(window_);
    if (options_.benchmark && frame > kWarmUpFrames) {
        glFinish();
        const auto end = Clock::now();
        const double warmUpMs = std::chrono::duration<double, std::milli>(warm - start).count() / kWarmUpFrames;
        const double meanMs = std::chrono::duration<double, std::milli>(end - warm).count() / (frame - kWarmUpFrames);
        // Processor time of every thread of the viewer (Mesa renders on threads of its
        // own), which a busy machine does not inflate as it does the wall-clock time.
        const double cpuMs = 1000.0 * static_cast<double>(std::clock() - warmCpu) / CLOCKS_PER_SEC / (frame - kWarmUpFrames);
        std::sort(frameMs.begin(), frameMs.end());
        const double p95Ms = frameMs.empty() ? meanMs : frameMs[frameMs.size() * 95 / 100];
        int width = 0, height = 0;
        glfwGetFramebufferSize(window_, &width, &height);
        std::printf("cyclone-viewer: %s at %dx%d, %d frames after %d of warm-up: mean frame %.2f ms (%.1f fps), "
                    "95th percentile %.2f ms (%.1f fps), processor time %.2f ms a frame; warm-up frames %.2f ms; "
                    "renderer %s\n",
                    session_->scene().name.c_str(), width, height, frame - kWarmUpFrames, kWarmUpFrames, meanMs,
                    1000.0 / meanMs, p95Ms, 1000.0 / p95Ms, cpuMs, warmUpMs,
                    reinterpret_cast<const char *>(glGetString(GL_RENDERER)));
    } else if (options_.benchmark) {
        std::printf("cyclone-viewer: --benchmark needs more than %d frames (the first ones compile shaders)\n",
                    kWarmUpFrames);
    }
    return 0;
}

}  // namespace cyclone::viewer
