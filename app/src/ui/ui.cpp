// The classroom panel (see ui.h).
#include "ui/ui.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui_stdlib.h>

#include "util/log.h"

namespace shadowlab {
namespace {

void scrollCallback(GLFWwindow* window, double, double dy) {
    if (auto* state = static_cast<UiState*>(glfwGetWindowUserPointer(window))) state->scroll += float(dy);
}

void helpMarker(const std::string& text) {
    if (text.empty()) return;
    ImGui::SameLine();
    ImGui::TextDisabled("(?)");
    if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
        ImGui::TextUnformatted(text.c_str());
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
    }
}

// One widget per declared parameter; the descriptor decides the kind of widget.
bool parameterWidget(const ParamSpec& spec, double& value) {
    const std::string label = spec.label.empty() ? spec.id : spec.label;
    bool changed = false;
    switch (spec.type) {
    case ParamType::Bool: {
        bool b = value != 0.0;
        if ((changed = ImGui::Checkbox(label.c_str(), &b))) value = b ? 1.0 : 0.0;
        break;
    }
    case ParamType::Enum: {
        int index = int(value);
        const std::string preview = index >= 0 && index < int(spec.enumLabels.size()) ? spec.enumLabels[size_t(index)] : "?";
        if (ImGui::BeginCombo(label.c_str(), preview.c_str())) {
            for (int i = 0; i < int(spec.enumLabels.size()); ++i)
                if (ImGui::Selectable(spec.enumLabels[size_t(i)].c_str(), i == index)) {
                    value = i;
                    changed = true;
                }
            ImGui::EndCombo();
        }
        break;
    }
    case ParamType::Int: {
        int i = int(std::lround(value));
        const bool wide = spec.maxValue / std::max(spec.minValue, 1.0) >= 16.0;
        if ((changed = ImGui::SliderInt(label.c_str(), &i, int(spec.minValue), int(spec.maxValue), "%d",
                                        wide ? ImGuiSliderFlags_Logarithmic : 0)))
            value = i;
        break;
    }
    case ParamType::Float: {
        float f = float(value);
        const std::string format = "%.4g" + (spec.unit.empty() ? "" : " " + spec.unit);
        const bool wide = spec.maxValue - spec.minValue >= 1000.0;
        if ((changed = ImGui::SliderFloat(label.c_str(), &f, float(spec.minValue), float(spec.maxValue), format.c_str(),
                                          wide ? ImGuiSliderFlags_Logarithmic : 0)))
            value = f;
        break;
    }
    }
    helpMarker(spec.help + "\nid: " + spec.id + "  range: [" + formatParamValue(spec, spec.minValue) + ", " +
               formatParamValue(spec, spec.maxValue) + "]  default: " + formatParamValue(spec, spec.defaultValue));
    value = std::clamp(value, spec.minValue, spec.maxValue);
    return changed;
}

// Error against GPU milliseconds for every measurement of this session: the live version of the
// speed-versus-accuracy chart. Lower left is better.
void drawSpeedAccuracyPlot(const std::vector<UiState::MeasuredPoint>& points) {
    if (points.empty()) return;
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 160.0f);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(25, 25, 30, 255));
    double maxMs = 1e-6, maxError = 1e-6;
    for (const auto& p : points) {
        maxMs = std::max(maxMs, p.gpuMs);
        maxError = std::max(maxError, p.mae);
    }
    const float margin = 8.0f;
    int hovered = -1;
    for (size_t i = 0; i < points.size(); ++i) {
        const float x = origin.x + margin + float(points[i].gpuMs / maxMs) * (size.x - 2 * margin);
        const float y = origin.y + size.y - margin - float(points[i].mae / maxError) * (size.y - 2 * margin);
        draw->AddCircleFilled(ImVec2(x, y), 4.0f, IM_COL32(90, 200, 255, 255));
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        if (std::abs(mouse.x - x) < 5 && std::abs(mouse.y - y) < 5) hovered = int(i);
    }
    ImGui::Dummy(size);
    ImGui::TextDisabled("x: GPU ms per frame (max %.3f)   y: MAE (max %.4f)", maxMs, maxError);
    if (hovered >= 0) {
        ImGui::BeginTooltip();
        ImGui::Text("%s\n%.3f ms, MAE %.4f", points[size_t(hovered)].label.c_str(), points[size_t(hovered)].gpuMs,
                    points[size_t(hovered)].mae);
        ImGui::EndTooltip();
    }
}

} // namespace

std::string UiState::nextScreenshotName() {
    char name[64];
    std::snprintf(name, sizeof(name), "out/screenshot-%03d.png", screenshotCounter++);
    return name;
}

bool Ui::init(GLFWwindow* window) {
    window_ = window;
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;   // no imgui.ini litter in the working folder
    ImGui::StyleColorsDark();
    glfwSetScrollCallback(window, scrollCallback);   // the ImGui backend chains to it
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) return false;
    if (!ImGui_ImplOpenGL3_Init("#version 450")) return false;
    initialised_ = true;
    return true;
}

void Ui::shutdown() {
    if (!initialised_) return;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwSetWindowUserPointer(window_, nullptr);
    initialised_ = false;
}

bool Ui::wantsMouse() const { return initialised_ && ImGui::GetIO().WantCaptureMouse; }
bool Ui::wantsKeyboard() const { return initialised_ && ImGui::GetIO().WantCaptureKeyboard; }

void Ui::draw(App& app, UiState& state, float frameSeconds) {
    glfwSetWindowUserPointer(window_, &state);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    smoothedFrameMs_ = smoothedFrameMs_ == 0.0f ? frameSeconds * 1000.0f : 0.95f * smoothedFrameMs_ + 0.05f * frameSeconds * 1000.0f;

    if (!ImGui::GetIO().WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_F12)) state.screenshotRequested = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) state.quitRequested = true;
    }

    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(400, 640), ImGuiCond_FirstUseEver);
    ImGui::Begin("shadowlab");

    // Technique picker, grouped by category.
    const TechniqueInfo* info = app.techniques().find(state.technique);
    if (ImGui::BeginCombo("technique", info ? info->displayName.c_str() : state.technique.c_str())) {
        std::string category;
        for (const auto& t : app.techniques().techniques()) {
            if (t.category != category) {
                category = t.category;
                ImGui::TextDisabled("%s", category.c_str());
            }
            if (ImGui::Selectable(("  " + t.displayName + "##" + t.id).c_str(), t.id == state.technique)) {
                state.technique = t.id;
                state.view = {};
            }
        }
        ImGui::EndCombo();
    }
    if (ImGui::BeginCombo("compare with", state.compareTechnique.empty() ? "(nothing)" : state.compareTechnique.c_str())) {
        if (ImGui::Selectable("(nothing)", state.compareTechnique.empty())) state.compareTechnique.clear();
        for (const auto& t : app.techniques().techniques())
            if (ImGui::Selectable((t.displayName + "##compare" + t.id).c_str(), t.id == state.compareTechnique))
                state.compareTechnique = t.id;
        ImGui::EndCombo();
    }
    helpMarker("Side by side: the technique above on the left half of the view, this one on the right, "
               "same camera and light. Timings shown are the right-hand one's.");
    if (!state.compareTechnique.empty()) {
        // Divider and labels over the scene.
        ImDrawList* background = ImGui::GetBackgroundDrawList();
        const ImVec2 size = ImGui::GetIO().DisplaySize;
        background->AddLine(ImVec2(size.x * 0.5f, 0), ImVec2(size.x * 0.5f, size.y), IM_COL32(255, 255, 255, 200), 2.0f);
        background->AddText(ImVec2(size.x * 0.5f - 8.0f - ImGui::CalcTextSize(state.technique.c_str()).x, size.y - 24.0f),
                            IM_COL32(255, 255, 255, 255), state.technique.c_str());
        background->AddText(ImVec2(size.x * 0.5f + 8.0f, size.y - 24.0f), IM_COL32(255, 255, 255, 255),
                            state.compareTechnique.c_str());
    }
    info = app.techniques().find(state.technique);
    if (info) {
        ImGui::TextDisabled("%s  |  %s", info->category.c_str(), info->id.c_str());
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(info->explanation.c_str());
        ImGui::PopTextWrapPos();
        if (!info->params.empty() && ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen)) {
            auto& values = app.params().values(*info);
            for (size_t i = 0; i < info->params.size(); ++i) parameterWidget(info->params[i], values[i]);
            if (ImGui::Button("Reset to defaults")) app.params().resetToDefaults(*info);
        }
    }
    if (!state.frameError.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(state.frameError.c_str());
        ImGui::PopTextWrapPos();
        ImGui::PopStyleColor();
    }

    if (ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) {
        LightInfo& light = app.light();
        const glm::vec3 toLight = -glm::normalize(light.direction);
        float azimuth = glm::degrees(std::atan2(toLight.z, toLight.x));
        float elevation = glm::degrees(std::asin(std::clamp(toLight.y, -1.0f, 1.0f)));
        bool changed = ImGui::SliderFloat("azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
        changed |= ImGui::SliderFloat("elevation", &elevation, 1.0f, 90.0f, "%.1f deg");
        helpMarker("Direction the light comes from. Low elevations give long shadows and make acne and "
                   "aliasing easy to see.");
        if (changed) {
            const float a = glm::radians(azimuth), e = glm::radians(elevation);
            light.direction = -glm::vec3(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
        }
        if (light.type == LightType::Directional) {
            float size = glm::degrees(light.size);
            if (ImGui::SliderFloat("angular radius", &size, 0.0f, 10.0f, "%.2f deg")) light.size = glm::radians(size);
        } else {
            ImGui::SliderFloat("radius", &light.size, 0.0f, 2.0f, "%.3f");
        }
        helpMarker("Size of the emitter: soft-shadow techniques widen their penumbrae with it; hard techniques ignore it.");
    }

    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        std::string current = state.view.kind == ViewSelection::Kind::Lit            ? "lit"
                              : state.view.kind == ViewSelection::Kind::Visibility   ? "visibility (shadow term)"
                              : state.view.kind == ViewSelection::Kind::ErrorHeatmap ? "error heatmap (last measurement)"
                                                                                     : state.view.debugImage;
        if (ImGui::BeginCombo("image", current.c_str())) {
            if (ImGui::Selectable("lit")) state.view = {};
            if (ImGui::Selectable("visibility (shadow term)")) state.view = {ViewSelection::Kind::Visibility, ""};
            std::string error;
            if (LoadedTechnique* loaded = app.techniques().get(state.technique, error))
                for (const auto& image : loaded->host().debugImages())
                    if (ImGui::Selectable(image.name.c_str())) state.view = {ViewSelection::Kind::DebugImage, image.name};
            ImGui::EndCombo();
        }
        const char* cameraModes[] = {"orbit (drag, wheel, middle-drag)", "fly (WASD QE + drag)"};
        int mode = app.camera().mode() == CameraController::Mode::Orbit ? 0 : 1;
        if (ImGui::Combo("camera", &mode, cameraModes, 2))
            app.camera().setMode(mode == 0 ? CameraController::Mode::Orbit : CameraController::Mode::Fly);
        if (ImGui::Button("Reset camera")) app.camera().reset(app.scene().camera);
        ImGui::SameLine();
        bool msaa = state.msaaSamples > 0;
        if (ImGui::Checkbox("MSAA 4x", &msaa)) state.msaaSamples = msaa ? 4 : 0;
        helpMarker("Multisampling of the main pass. Accuracy runs use it off: resolving averages the G-buffer at edges.");
        if (ImGui::Button("Screenshot (F12)")) state.screenshotRequested = true;
        if (!app.scene().name.empty()) ImGui::TextDisabled("scene: %s, %zu triangles", app.scene().name.c_str(), app.scene().triangleCount());
        ImGui::InputText("##scene", &sceneInput_);
        ImGui::SameLine();
        if (ImGui::Button("Load scene")) {
            std::string error;
            sceneError_ = app.loadScene(sceneInput_, {}, error) ? "" : error;
        }
        if (!sceneError_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", sceneError_.c_str());
    }

    if (ImGui::CollapsingHeader("Timing and memory", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Text("%.1f FPS  (%.2f ms per frame, host CPU %.3f ms)", 1000.0f / std::max(smoothedFrameMs_, 1e-3f),
                    smoothedFrameMs_, app.lastCpuFrameMs());
        if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_BordersInnerH)) {
            for (const auto& [pass, ms] : app.timer().latest()) {
                ImGui::TableNextRow();
                ImGui::TableSetColumnIndex(0);
                ImGui::TextUnformatted(pass == "frame" ? "GPU total" : pass.c_str());
                ImGui::TableSetColumnIndex(1);
                ImGui::Text("%.3f ms", ms);
            }
            ImGui::EndTable();
        }
        std::string error;
        if (LoadedTechnique* loaded = app.techniques().get(state.technique, error)) {
            ImGui::Text("technique GPU memory: %.2f MiB", double(loaded->host().gpuBytes()) / (1024.0 * 1024.0));
            for (const auto& [name, allocation] : loaded->host().textures())
                ImGui::TextDisabled("  %s: %.2f MiB", allocation.label.c_str(), double(allocation.bytes) / (1024.0 * 1024.0));
            for (const auto& [name, value] : loaded->host().statistics()) ImGui::Text("%s: %.4g", name.c_str(), value);
        }
    }

    if (ImGui::CollapsingHeader("Accuracy", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char* modes[] = {"hard reference", "soft reference"};
        ImGui::Combo("against", &state.referenceMode, modes, 2);
        if (state.referenceMode == 1) ImGui::SliderInt("rays per pixel", &state.referenceSamples, 4, 256);
        // Translucent casters: the physical model (1 - a) + a t, or the one the technique declares.
        const TechniqueInfo* judged = app.techniques().find(state.technique);
        const TranslucencyModel ownModel = judged ? judged->translucencyModel : TranslucencyModel::Opaque;
        const std::string ownLabel = std::string("technique's own (") + translucencyModelName(ownModel) + ")";
        const char* models[] = {"physical", ownLabel.c_str()};
        ImGui::Combo("translucency model", &state.referenceModel, models, 2);
        helpMarker("Traces the ray-traced reference (Embree, CPU) from the G-buffer of the frame on screen and "
                   "compares the technique's shadow term per pixel. The heatmap shows false shadow (acne, "
                   "over-darkening) in magenta and false light (leaks, peter panning) in green.");
        if (ImGui::Button("Measure accuracy")) state.measureRequested = true;
        if (state.measureRequested) {
            state.measureRequested = false;
            ReferenceOptions options;
            options.mode = state.referenceMode == 1 ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
            options.samplesPerPixel = state.referenceSamples;
            options.model = state.referenceModel == 1 ? ownModel : TranslucencyModel::Physical;
            Evaluation evaluation;
            std::string error;
            if (app.evaluate(options, evaluation, error)) {
                const AccuracyMetrics& m = evaluation.metrics;
                char text[512];
                std::snprintf(text, sizeof(text),
                              "MAE %.4f   RMSE %.4f\nfalse shadow %.3f%%   false light %.3f%%\n"
                              "MAE in penumbra %.4f, elsewhere %.4f\ncompared %.1f%% of pixels (traced in %.2f s)",
                              m.mae, m.rmse, 100.0 * m.falseShadowRate, 100.0 * m.falseLightRate, m.maePenumbra,
                              m.maeOutsidePenumbra, 100.0 * m.comparedFraction, evaluation.traceSeconds);
                state.accuracyText = text;
                state.heatmap = evaluation.heatmap();
                state.heatmapUploaded = false;
                state.view = {ViewSelection::Kind::ErrorHeatmap, ""};
                const auto frame = app.timer().latest().find("frame");
                const TechniqueInfo* measuredInfo = app.techniques().find(state.technique);
                std::string label = measuredInfo ? measuredInfo->id : state.technique;
                if (measuredInfo)
                    for (size_t i = 0; i < measuredInfo->params.size(); ++i)
                        label += " " + measuredInfo->params[i].id + "=" +
                                 formatParamValue(measuredInfo->params[i], app.params().values(*measuredInfo)[i]);
                state.measured.push_back({label, frame == app.timer().latest().end() ? 0.0 : frame->second, m.mae});
            } else {
                state.accuracyText = error;
            }
        }
        if (!state.accuracyText.empty()) ImGui::TextUnformatted(state.accuracyText.c_str());
        if (state.heatmap.width > 0 && ImGui::Button("Show error heatmap")) state.view = {ViewSelection::Kind::ErrorHeatmap, ""};
        drawSpeedAccuracyPlot(state.measured);
    }

    if (ImGui::CollapsingHeader("Hot reload and log")) {
        ImGui::TextWrapped("Rebuild a plugin (cmake --build build) or save a .glsl file: it is reloaded in place. "
                           "Failures keep the running version.");
        const std::string& pluginError = app.techniques().lastReloadError();
        const std::string& shaderError = app.shaders().lastReloadError();
        if (!pluginError.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", pluginError.c_str());
        if (!shaderError.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", shaderError.c_str());
        for (const auto& error : app.techniques().scanErrors()) ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1), "%s", error.c_str());
        ImGui::BeginChild("log", ImVec2(0, 160), true);
        for (const auto& entry : recentLog()) {
            const ImVec4 color = entry.level == LogLevel::Error     ? ImVec4(1, 0.4f, 0.4f, 1)
                                 : entry.level == LogLevel::Warning ? ImVec4(1, 0.8f, 0.3f, 1)
                                                                    : ImVec4(0.8f, 0.8f, 0.8f, 1);
            ImGui::PushTextWrapPos(0.0f);
            ImGui::TextColored(color, "%s", entry.message.c_str());
            ImGui::PopTextWrapPos();
        }
        ImGui::EndChild();
    }
    ImGui::End();

    ImGui::Render();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

} // namespace shadowlab
