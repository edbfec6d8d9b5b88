#include "ui.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "palette.h"

namespace cyclone::viewer {

namespace {

// Width of the step-time plot, pixels.
constexpr float kPlotWidth = 270;

void stageRow(const char *name, double ms) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextUnformatted(name);
    ImGui::TableSetColumnIndex(1);
    ImGui::Text("%7.3f", ms);
}

void legendEntry(const char *name, BodyState state) {
    const Rgb c = stateColor(state);
    ImGui::ColorButton(name, ImVec4(c.r, c.g, c.b, 1), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
    ImGui::SameLine();
    ImGui::TextUnformatted(name);
}

}  // namespace

Overlay::Overlay(const std::string &sceneFolder) {
    std::error_code error;
    for (const auto &entry : std::filesystem::directory_iterator(sceneFolder, error)) {
        if (entry.path().extension() == ".json") {
            scenes_.push_back(std::filesystem::weakly_canonical(entry.path(), error).string());
        }
    }
    std::sort(scenes_.begin(), scenes_.end());
    history_.reserve(kHistory);
}

void Overlay::recordStep(const StepStats &stats) {
    const float ms = static_cast<float>(stats.ms.total);
    if (history_.size() < kHistory) {
        history_.push_back(ms);
    } else {
        history_[next_] = ms;
        next_ = (next_ + 1) % kHistory;
    }
}

void Overlay::clearHistory() {
    history_.clear();
    next_ = 0;
}

UiRequests Overlay::draw(Session &session, RunControls &controls, ViewOptions &view, double frameMs,
                         const std::string &problem) {
    UiRequests requests;
    drawStats(session, frameMs);
    drawControls(session, controls, view, requests);
    if (!problem.empty()) {
        const ImGuiViewport *viewport = ImGui::GetMainViewport();
        ImGui::SetNextWindowPos(ImVec2(viewport->WorkSize.x / 2, viewport->WorkSize.y - 10), ImGuiCond_Always,
                                ImVec2(0.5f, 1));
        ImGui::Begin("Problem", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoTitleBar);
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", problem.c_str());
        ImGui::End();
    }
    return requests;
}

void Overlay::drawStats(const Session &session, double frameMs) {
    const World &world = session.world();
    const StepStats &stats = world.stats();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::Begin("Step", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%s  step %llu  t = %.2f s", session.scene().name.c_str(),
                static_cast<unsigned long long>(session.stepper().totalSteps()),
                static_cast<double>(session.stepper().totalSteps()) * static_cast<double>(session.stepSeconds()));
    ImGui::Text("frame %.1f ms (%.0f fps)", frameMs, frameMs > 0 ? 1000.0 / frameMs : 0.0);
    ImGui::Text("bodies %d  awake %d (held %d)  islands %d", stats.bodies, stats.awakeBodies, stats.heldBodies,
                stats.islands);
    ImGui::Text("contacts %d  manifolds %d", stats.contacts, stats.manifolds);
    ImGui::Text("deepest contact %.2f mm", static_cast<double>(stats.maxPenetration) * 1000);
    if (stats.isolatedBodies > 0) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "isolated bodies %d", stats.isolatedBodies);

    std::vector<float> ordered(history_.begin() + static_cast<std::ptrdiff_t>(next_), history_.end());
    ordered.insert(ordered.end(), history_.begin(), history_.begin() + static_cast<std::ptrdiff_t>(next_));
    const float peak = ordered.empty() ? 1.0f : std::max(1.0f, *std::max_element(ordered.begin(), ordered.end()));
    char label[48];
    std::snprintf(label, sizeof label, "step ms (max %.2f)", static_cast<double>(peak));
    ImGui::PlotLines("##steps", ordered.data(), static_cast<int>(ordered.size()), 0, label, 0.0f, peak * 1.1f,
                     ImVec2(kPlotWidth, 60));

    if (ImGui::BeginTable("stages", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchSame, ImVec2(kPlotWidth, 0))) {
        const StageTimes &ms = stats.ms;
        stageRow("forces", ms.forces);
        stageRow("broadphase", ms.broadphase);
        stageRow("narrowphase", ms.narrowphase);
        stageRow("events", ms.events);
        stageRow("manifolds", ms.manifolds);
        stageRow("islands", ms.islands);
        stageRow("solve", ms.solve);
        stageRow("integrate", ms.integrate);
        stageRow("ccd", ms.ccd);
        stageRow("sleep", ms.sleep);
        stageRow("total (ms)", ms.total);
        ImGui::EndTable();
    }
    legendEntry("awake", BodyState::Awake);
    ImGui::SameLine();
    legendEntry("asleep", BodyState::Asleep);
    ImGui::SameLine();
    legendEntry("static", BodyState::Static);
    ImGui::SameLine();
    legendEntry("non-finite", BodyState::NonFinite);
    legendEntry("kinematic", BodyState::Kinematic);
    ImGui::SameLine();
    legendEntry("sensor", BodyState::Sensor);
    ImGui::End();
}

void Overlay::drawControls(Session &session, RunControls &controls, ViewOptions &view, UiRequests &requests) {
    const ImGuiViewport *viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkSize.x - 10, 10), ImGuiCond_FirstUseEver, ImVec2(1, 0));
    ImGui::Begin("Controls", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    if (ImGui::Button(controls.paused ? "Run (Space)" : "Pause (Space)")) controls.paused = !controls.paused;
    ImGui::SameLine();
    if (ImGui::Button("Step (N)")) requests.singleStep = true;
    ImGui::SameLine();
    if (ImGui::Button("Restart (R)")) requests.restart = true;
    ImGui::Checkbox("Slow motion (S)", &controls.slowMotion);
    if (ImGui::Button("Frame (F)")) requests.frameScene = true;
    ImGui::SameLine();
    if (ImGui::Button("Shoot a ball (B)")) requests.shootBall = true;

    if (ImGui::CollapsingHeader("Show", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("solid shapes", &view.solids);
        ImGui::SameLine();
        ImGui::Checkbox("wireframes", &view.wireframes);
        ImGui::Checkbox("contacts", &view.contacts);
        ImGui::SameLine();
        ImGui::Checkbox("broadphase", &view.boundingBoxes);
        ImGui::Checkbox("springs", &view.springs);
        ImGui::SameLine();
        ImGui::Checkbox("joints", &view.joints);
        ImGui::Checkbox("box edges", &view.edges);
    }

    if (ImGui::CollapsingHeader("Solver")) {
        WorldSettings settings = session.world().settings();
        bool changed = false;
        changed |= ImGui::SliderInt("velocity its", &settings.velocityIterations, 1, 50);
        changed |= ImGui::SliderInt("position its", &settings.positionIterations, 0, 20);
        changed |= ImGui::SliderInt("sub-steps", &settings.substeps, 1, 16);
        changed |= ImGui::Checkbox("sleep", &settings.sleep);
        ImGui::SameLine();
        changed |= ImGui::Checkbox("warm start", &settings.debug.warmStarting);
        if (changed) session.setSettings(settings);
    }

    if (ImGui::CollapsingHeader("Scenes")) {
        std::error_code error;
        const std::string current = std::filesystem::weakly_canonical(session.path(), error).string();
        for (const std::string &path : scenes_) {
            const std::string name = std::filesystem::path(path).stem().string();
            if (ImGui::Selectable(name.c_str(), path == current) && path != current) {
                requests.openScene = path;
            }
        }
    }
    ImGui::End();
}

}  // namespace cyclone::viewer
