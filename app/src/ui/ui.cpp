// The classroom panel (see ui.h).
#include "ui/ui.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui_stdlib.h>

#include "ui/keys.h"
#include "util/log.h"

namespace shadowlab {
namespace {

// A TrueType font where Debian has one (fonts-dejavu-core): sharp at any UI scale, unlike
// ImGui's built-in 13 px bitmap font scaled up.
constexpr const char* kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr float kFontPixels = 15.0f;
constexpr float kPresenterFontPixels = 28.0f;

void scrollCallback(GLFWwindow* window, double, double dy) {
    if (auto* state = static_cast<UiState*>(glfwGetWindowUserPointer(window))) state->scroll += float(dy);
}

// Key presses are queued here: ImGui 1.86 keeps only "is down" per frame, so a key pressed and
// released between two frames (a quick tap at 10 frames per second) would be lost.
// Where the cursor was when the left button went down, from the events in their order: at a
// few frames per second the cursor has moved on by the frame that sees the click, and the wipe
// handle would be missed.
void cursorCallback(GLFWwindow* window, double x, double y) {
    if (auto* state = static_cast<UiState*>(glfwGetWindowUserPointer(window))) state->eventCursor = {float(x), float(y)};
}

void mouseButtonCallback(GLFWwindow* window, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    auto* state = static_cast<UiState*>(glfwGetWindowUserPointer(window));
    if (!state) return;
    if (action == GLFW_PRESS) state->leftPresses.push_back(state->eventCursor);
    if (action == GLFW_RELEASE) state->leftRelease = state->eventCursor;
}

void keyCallback(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    if (auto* state = static_cast<UiState*>(glfwGetWindowUserPointer(window))) state->pressedKeys.push_back(key);
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

// A label on its own line, wrapped rather than cut ("slope-scaled bias" whole at any width), and
// the widget under it across the panel.
void fieldLabel(const std::string& label, const std::string& help = "") {
    const float helpWidth = help.empty() ? 0.0f : ImGui::CalcTextSize("(?)").x + 2.0f * ImGui::GetStyle().ItemSpacing.x;
    ImGui::PushTextWrapPos(ImGui::GetContentRegionMax().x - helpWidth);
    ImGui::TextUnformatted(label.c_str());
    ImGui::PopTextWrapPos();
    helpMarker(help);
    ImGui::SetNextItemWidth(-FLT_MIN);
}

// A checkbox with its label wrapped beside it.
bool checkbox(const std::string& label, bool* value, const std::string& help = "") {
    const bool changed = ImGui::Checkbox(("##" + label).c_str(), value);
    ImGui::SameLine();
    const float helpWidth = help.empty() ? 0.0f : ImGui::CalcTextSize("(?)").x + 2.0f * ImGui::GetStyle().ItemSpacing.x;
    ImGui::PushTextWrapPos(ImGui::GetContentRegionMax().x - helpWidth);
    ImGui::TextUnformatted(label.c_str());
    ImGui::PopTextWrapPos();
    helpMarker(help);
    return changed;
}

// One widget per declared parameter; the descriptor decides the kind of widget.
bool parameterWidget(const ParamSpec& spec, double& value) {
    const std::string label = spec.label.empty() ? spec.id : spec.label;
    const std::string help = spec.help + "\nid: " + spec.id + "  range: [" + formatParamValue(spec, spec.minValue) + ", " +
                             formatParamValue(spec, spec.maxValue) + "]  default: " + formatParamValue(spec, spec.defaultValue);
    const std::string id = "##param-" + spec.id;
    bool changed = false;
    switch (spec.type) {
    case ParamType::Bool: {
        bool b = value != 0.0;
        if ((changed = checkbox(label, &b, help))) value = b ? 1.0 : 0.0;
        break;
    }
    case ParamType::Enum: {
        fieldLabel(label, help);
        int index = int(value);
        const std::string preview = index >= 0 && index < int(spec.enumLabels.size()) ? spec.enumLabels[size_t(index)] : "?";
        if (ImGui::BeginCombo(id.c_str(), preview.c_str())) {
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
        fieldLabel(label, help);
        int i = int(std::lround(value));
        const bool wide = spec.maxValue / std::max(spec.minValue, 1.0) >= 16.0;
        if ((changed = ImGui::SliderInt(id.c_str(), &i, int(spec.minValue), int(spec.maxValue), "%d",
                                        wide ? ImGuiSliderFlags_Logarithmic : 0)))
            value = i;
        break;
    }
    case ParamType::Float: {
        fieldLabel(label, help);
        float f = float(value);
        const std::string format = "%.4g" + (spec.unit.empty() ? "" : " " + spec.unit);
        const bool wide = spec.maxValue - spec.minValue >= 1000.0;
        if ((changed = ImGui::SliderFloat(id.c_str(), &f, float(spec.minValue), float(spec.maxValue), format.c_str(),
                                          wide ? ImGuiSliderFlags_Logarithmic : 0)))
            value = f;
        break;
    }
    }
    value = std::clamp(value, spec.minValue, spec.maxValue);
    return changed;
}

// Error against GPU milliseconds for every measurement of this session: the live version of the
// speed-versus-accuracy chart. Lower left is better.
void drawSpeedAccuracyPlot(const std::vector<UiState::MeasuredPoint>& points) {
    if (points.empty()) return;
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 10.0f * ImGui::GetFontSize());
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
    ImGui::TextWrapped("x: GPU ms per frame (max %.3f)   y: MAE (max %.4f)", maxMs, maxError);
    if (hovered >= 0) {
        ImGui::BeginTooltip();
        ImGui::Text("%s\n%.3f ms, MAE %.4f", points[size_t(hovered)].label.c_str(), points[size_t(hovered)].gpuMs,
                    points[size_t(hovered)].mae);
        ImGui::EndTooltip();
    }
}

// Text with a dark box behind it: legible on a white wall or a black shadow alike. The box is
// kept inside [minX, maxX] (a wipe divider near the edge moves its label inward, not off screen).
void labelBox(ImDrawList* draw, ImVec2 anchor, const std::string& text, bool alignRight,
              ImU32 colour = IM_COL32(255, 255, 255, 255), float minX = -FLT_MAX, float maxX = FLT_MAX) {
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    const float pad = 0.4f * ImGui::GetFontSize();
    float x = alignRight ? anchor.x - size.x - 2 * pad : anchor.x;
    x = std::max(std::min(x, maxX - size.x - 2 * pad), minX);
    const ImVec2 min(x, anchor.y - size.y - 2 * pad);
    draw->AddRectFilled(min, ImVec2(min.x + size.x + 2 * pad, min.y + size.y + 2 * pad), IM_COL32(0, 0, 0, 190), pad);
    draw->AddText(ImVec2(min.x + pad, min.y + pad), colour, text.c_str());
}

std::string techniqueTitle(App& app, const std::string& id) {
    const TechniqueInfo* info = app.techniques().find(id);
    return info ? info->displayName + " (" + id + ")" : id;
}

void timingsTable(const char* id, const std::map<std::string, double>& timings) {
    if (!ImGui::BeginTable(id, 2, ImGuiTableFlags_BordersInnerH)) return;
    for (const auto& [pass, ms] : timings) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextWrapped("%s", pass == "frame" ? "GPU total" : pass.c_str());
        ImGui::TableSetColumnIndex(1);
        ImGui::Text("%.3f ms", ms);
    }
    ImGui::EndTable();
}

// What a key of the table does (the fly keys are held, read by the frame loop).
void runKeyAction(KeyAction action, UiState& state) {
    switch (action) {
    case KeyAction::Screenshot: return state.commands.push_back({UiCommand::Kind::Screenshot, ""});
    case KeyAction::ToggleUi: state.showUi = !state.showUi; return;
    case KeyAction::Measure: return state.commands.push_back({UiCommand::Kind::Measure, ""});
    case KeyAction::SaveSession: return state.commands.push_back({UiCommand::Kind::SaveSession, ""});
    case KeyAction::Quit: state.quitRequested = true; return;
    case KeyAction::Presenter: return setPresenter(state, !state.presenter);
    case KeyAction::Help: state.showHelp = !state.showHelp; return;
    case KeyAction::PlayPath: state.pathPlaying = !state.pathPlaying; return;
    case KeyAction::NextStep:
        if (state.tour) state.commands.push_back({UiCommand::Kind::TourStep, "next"});
        return;
    case KeyAction::PreviousStep:
        if (state.tour) state.commands.push_back({UiCommand::Kind::TourStep, "previous"});
        return;
    case KeyAction::RestartStep:
        if (state.tour) state.commands.push_back({UiCommand::Kind::TourStep, "restart"});
        return;
    default: return;   // fly keys: held, read each frame
    }
}

} // namespace

bool Ui::init(GLFWwindow* window, float uiScale) {
    window_ = window;
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;   // no imgui.ini litter in the working folder
    if (window) {
        glfwSetScrollCallback(window, scrollCallback);   // the ImGui backend chains to both
        glfwSetKeyCallback(window, keyCallback);
        glfwSetMouseButtonCallback(window, mouseButtonCallback);
        glfwSetCursorPosCallback(window, cursorCallback);
        double x = 0.0, y = 0.0;
        glfwGetCursorPos(window, &x, &y);
        initialCursor_ = {float(x), float(y)};
        if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) return false;
    } else {
        ImGui::GetIO().BackendPlatformName = "shadowlab offscreen";
    }
    initialised_ = true;
    applyScale(uiScale);   // builds the font atlas the renderer uploads
    std::string error;
    if (!renderer_.init(error)) {
        logError(error);
        return false;
    }
    return true;
}

void Ui::applyScale(float scale) {
    scale = std::clamp(scale, 0.5f, 4.0f);
    if (scale == appliedScale_) return;
    ImGuiIO& io = ImGui::GetIO();
    // Fonts rasterised at the scaled size (outside NewFrame/Render, on a change only).
    const bool uploaded = appliedScale_ > 0.0f && io.Fonts->IsBuilt();
    io.Fonts->Clear();
    std::error_code ec;
    largeFont_ = nullptr;
    if (std::filesystem::exists(kFontFile, ec)) {
        io.Fonts->AddFontFromFileTTF(kFontFile, std::round(kFontPixels * scale));   // the first font is the default
        // Presenter captions: read from the back of a room.
        largeFont_ = io.Fonts->AddFontFromFileTTF(kFontFile, std::round(kPresenterFontPixels * scale));
        io.FontGlobalScale = 1.0f;
    } else {
        io.Fonts->AddFontDefault();
        io.FontGlobalScale = scale;
    }
    io.Fonts->Build();
    if (uploaded) renderer_.createFontTexture();
    ImGuiStyle style;
    ImGui::StyleColorsDark(&style);
    style.ScaleAllSizes(scale);
    ImGui::GetStyle() = style;
    appliedScale_ = scale;
}

void Ui::shutdown() {
    if (!initialised_) return;
    renderer_ = {};
    if (window_) {
        ImGui_ImplGlfw_Shutdown();
        glfwSetWindowUserPointer(window_, nullptr);
    }
    ImGui::DestroyContext();
    initialised_ = false;
}

bool Ui::wantsMouse() const { return initialised_ && ImGui::GetIO().WantCaptureMouse; }
bool Ui::wantsKeyboard() const { return initialised_ && ImGui::GetIO().WantCaptureKeyboard; }

bool Ui::onWipeHandle(const UiState& state, glm::vec2 p) const {
    const ViewLayout& layout = state.layout;
    if (!layout.comparing || state.compareLayout != CompareLayout::Wipe) return false;
    const float r = 0.7f * kFontPixels * std::max(appliedScale_, 0.5f);   // the handle's radius at this UI scale
    return std::abs(p.x - float(layout.wipeX)) < r && layout.view.contains(p);
}

void Ui::draw(App& app, UiState& state, float frameSeconds, GLuint framebuffer, glm::ivec2 display) {
    applyScale(state.uiScale);
    if (window_) {
        if (glfwGetWindowUserPointer(window_) != &state) state.eventCursor = initialCursor_;
        glfwSetWindowUserPointer(window_, &state);
        ImGui_ImplGlfw_NewFrame();
    } else {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(display.x), float(display.y));
        io.DeltaTime = 1.0f / 60.0f;
        io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    }
    ImGui::NewFrame();
    smoothedFrameMs_ = smoothedFrameMs_ == 0.0f ? frameSeconds * 1000.0f : 0.95f * smoothedFrameMs_ + 0.05f * frameSeconds * 1000.0f;

    // Keys typed into a text field are the field's; every key is the table's (ui/keys.h).
    if (!ImGui::GetIO().WantCaptureKeyboard)
        for (const int key : state.pressedKeys)
            for (const KeyBinding& binding : keyBindings())
                if (binding.key == key) runKeyAction(binding.action, state);
    state.pressedKeys.clear();

    // The latest hot-reload line of the log (plugin or shader), for the status line.
    const auto log = recentLog();
    for (auto entry = log.rbegin(); entry != log.rend(); ++entry) {
        const std::string& m = entry->message;
        if (m.rfind("hot reload", 0) == 0 || m.rfind("shader reload", 0) == 0) {
            if (m != reloadStatus_) {
                reloadStatus_ = m;
                reloadStatusIsError_ = entry->level == LogLevel::Error;
                reloadStatusSeconds_ = ImGui::GetTime();
            }
            break;
        }
    }

    drawViewOverlay(app, state);
    drawViewLegend(app, state);
    state.leftPresses.clear();
    state.leftRelease.reset();
    if (state.showUi) drawPanel(app, state);
    else drawStatusLine(app, state, true);
    if (state.presenter) drawPresenterOverlay(app, state);
    if (state.showHelp) drawHelpOverlay(state);

    ImGui::Render();
    renderer_.render(ImGui::GetDrawData(), framebuffer);
}

void Ui::drawStatusLine(App& app, const UiState& state, bool overlay) {
    (void)app;
    const bool recent = ImGui::GetTime() - reloadStatusSeconds_ < 6.0;
    if (overlay) {
        // UI hidden: only a fresh reload result (or a failure, which stays) shows, over the view.
        if (reloadStatus_.empty() || (!recent && !reloadStatusIsError_)) return;
        labelBox(ImGui::GetForegroundDrawList(),
                 ImVec2(float(state.layout.view.origin.x) + 8.0f, float(state.layout.view.size.y) - 8.0f), reloadStatus_, false,
                 reloadStatusIsError_ ? IM_COL32(255, 110, 110, 255) : IM_COL32(150, 255, 150, 255));
        return;
    }
    const ImVec4 colour = reloadStatus_.empty()     ? ImVec4(0.6f, 0.6f, 0.6f, 1)
                          : reloadStatusIsError_    ? ImVec4(1, 0.45f, 0.45f, 1)
                          : recent                  ? ImVec4(0.55f, 1, 0.55f, 1)
                                                    : ImVec4(0.75f, 0.75f, 0.75f, 1);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(reloadStatus_.empty() ? "hot reload: watching plugins and shaders" : reloadStatus_.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
}

void Ui::drawViewOverlay(App& app, UiState& state) {
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const ViewLayout& layout = state.layout;
    const float bottom = float(layout.view.origin.y + layout.view.size.y) - 8.0f;
    if (layout.comparing) {
        const std::string a = "A: " + techniqueTitle(app, state.technique);
        const std::string b = "B: " + techniqueTitle(app, state.compareTechnique);
        const float left = float(layout.view.origin.x) + 8.0f, right = float(layout.view.origin.x + layout.view.size.x) - 8.0f;
        if (state.compareLayout == CompareLayout::Grid) {
            // A B over C D: lines between the quarters and each one's label in its lower left corner.
            const PixelRect& first = layout.cells[0];
            const float midX = float(first.origin.x + first.size.x), midY = float(first.origin.y + first.size.y);
            for (const ImU32 colour : {IM_COL32(0, 0, 0, 160), IM_COL32(255, 255, 255, 230)}) {
                const float width = colour == IM_COL32(0, 0, 0, 160) ? 4.0f : 2.0f;
                draw->AddLine(ImVec2(midX, float(layout.view.origin.y)), ImVec2(midX, bottom + 8.0f), colour, width);
                draw->AddLine(ImVec2(left - 8.0f, midY), ImVec2(right + 8.0f, midY), colour, width);
            }
            const std::vector<std::string> sides = shownTechniques(state);
            for (size_t i = 0; i < sides.size(); ++i) {
                const PixelRect& cell = layout.cells[i];
                labelBox(draw, ImVec2(float(cell.origin.x) + 8.0f, float(cell.origin.y + cell.size.y) - 8.0f),
                         std::string(1, char('A' + i)) + ": " + techniqueTitle(app, sides[i]), false);
            }
        } else if (state.compareLayout == CompareLayout::Difference) {
            labelBox(draw, ImVec2(left, bottom),
                     "difference of the shadow terms\n" + a + "\n" + b + "\norange: A darker, blue: B darker", false,
                     IM_COL32(255, 255, 255, 255), left, right);
        } else {
            const float divider = state.compareLayout == CompareLayout::Wipe ? float(layout.wipeX)
                                                                             : float(layout.halves[1].origin.x);
            draw->AddLine(ImVec2(divider, float(layout.view.origin.y)), ImVec2(divider, bottom + 8.0f), IM_COL32(0, 0, 0, 160), 4.0f);
            draw->AddLine(ImVec2(divider, float(layout.view.origin.y)), ImVec2(divider, bottom + 8.0f), IM_COL32(255, 255, 255, 230), 2.0f);
            // Side by side: beside the divider. Wipe: in the view's corners, so they never cover
            // each other wherever the divider is.
            const bool wipe = state.compareLayout == CompareLayout::Wipe;
            labelBox(draw, ImVec2(wipe ? left : divider - 8.0f, bottom), a, !wipe, IM_COL32(255, 255, 255, 255), left, right);
            labelBox(draw, ImVec2(wipe ? right : divider + 8.0f, bottom), b, wipe, IM_COL32(255, 255, 255, 255), left, right);
            if (state.compareLayout == CompareLayout::Wipe) {
                // The handle: drag it (anywhere on the divider line) to move the wipe.
                const float y = float(layout.view.origin.y) + 0.5f * float(layout.view.size.y);
                const float r = 0.7f * ImGui::GetFontSize();
                draw->AddCircleFilled(ImVec2(divider, y), r, IM_COL32(255, 255, 255, 230));
                draw->AddCircle(ImVec2(divider, y), r, IM_COL32(0, 0, 0, 200), 0, 2.0f);
                const ImGuiIO& io = ImGui::GetIO();
                const bool near = onWipeHandle(state, {io.MousePos.x, io.MousePos.y});
                for (const glm::vec2 press : state.leftPresses)
                    if (onWipeHandle(state, press) && !io.WantCaptureMouse) state.draggingWipe = true;
                // Follow the cursor; a release ends the drag where the button went up (a slow
                // frame may see the release and later moves together).
                const bool released = state.leftRelease.has_value() || !ImGui::IsMouseDown(0);
                const float x = state.leftRelease ? state.leftRelease->x : io.MousePos.x;
                if (state.draggingWipe && layout.view.size.x > 0)
                    state.wipe = std::clamp((x - float(layout.view.origin.x)) / float(layout.view.size.x), 0.02f, 0.98f);
                if (near || state.draggingWipe) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
                if (released) state.draggingWipe = false;
            }
        }
    }
    if (state.view.kind == ViewSelection::Kind::Kernel && !layout.comparing) {
        // The kernel's numbers in the view's corner, UI shown or not (a slide keeps them).
        std::string text = describeProbe(app.lastProbe());
        for (size_t at = text.find(", "); at != std::string::npos; at = text.find(", ", at)) text.replace(at, 2, "\n");
        if (app.probePixel()) text = "pixel " + std::to_string(app.probePixel()->x) + ", " + std::to_string(app.probePixel()->y) + ": " + text;
        // Away from the probed pixel: at the top when it is in the lower half of the view.
        const bool top = app.probePixel() && app.probePixel()->y * 2 > layout.renderSize.y;
        const float height = ImGui::CalcTextSize(text.c_str()).y + 0.8f * ImGui::GetFontSize();
        labelBox(draw, ImVec2(float(layout.view.origin.x) + 8.0f, top ? float(layout.view.origin.y) + 8.0f + height : bottom),
                 text, false);
        if (app.probePixel()) drawKernelInset(app, state, *app.probePixel(), top);
    }
    if (state.showUi && state.view.kind == ViewSelection::Kind::ErrorHeatmap && !state.measurement.empty()) {
        // Say so when the heatmap no longer shows what is on screen, and offer to measure again.
        const std::string text = state.staleReason.empty()
                                     ? "error heatmap: magenta false shadow, green false light, dimmed scene where exact"
                                     : "STALE heatmap: " + state.staleReason + " since it was measured (M or Re-measure)";
        ImGui::SetNextWindowPos(ImVec2(float(layout.view.origin.x) + 8.0f, float(layout.view.origin.y) + 8.0f));
        ImGui::SetNextWindowBgAlpha(0.75f);
        ImGui::Begin("##heatmap-banner", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                         ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoMove);
        if (!state.staleReason.empty()) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
        ImGui::TextUnformatted(text.c_str());
        if (!state.staleReason.empty()) ImGui::PopStyleColor();
        if (!state.staleReason.empty() && ImGui::Button("Re-measure")) state.commands.push_back({UiCommand::Kind::Measure, ""});
        ImGui::SameLine();
        if (ImGui::Button("Back to lit")) state.view = {};
        ImGui::End();
    }
}

// The kernel view's inset: the pixels around the probe magnified (nearest texels, so the taps and
// the box read as the shader's pixels), at the view's right edge on the side away from the probe,
// with a cross on the probed pixel and the kernel's size under it.
void Ui::drawKernelInset(App& app, const UiState& state, glm::ivec2 probe, bool top) {
    const ViewLayout& layout = state.layout;
    // Pixels either side of the probe: the kernel's reach on screen and a little more, at least 8
    // (a kernel of a few pixels is what needs magnifying) and at most 96.
    std::string error;
    LoadedTechnique* loaded = app.techniques().get(state.technique, error);
    if (!loaded || loaded->host().shadowMaps().empty() || !app.lastProbe().valid) return;
    const float reach = kernelPixelRadius(loaded->host().shadowMaps().front(), app.lastProbe(),
                                          app.camera().info(layout.renderSize).viewProjection, layout.renderSize);
    const float side = std::min(16.0f * ImGui::GetFontSize(), 0.4f * float(layout.view.size.y));
    const float kRadius = std::min(std::clamp(std::ceil(1.2f * reach) + 2.0f, 8.0f, 96.0f), 0.5f * side);   // magnified, never shrunk
    const glm::vec2 render(layout.renderSize);
    if (render.x <= 2.0f * kRadius || render.y <= 2.0f * kRadius) return;
    const glm::vec2 centre = glm::clamp(glm::vec2(probe) + 0.5f, glm::vec2(kRadius), render - kRadius);
    const glm::vec2 lo = centre - kRadius, hi = centre + kRadius;
    const float right = float(layout.view.origin.x + layout.view.size.x) - 8.0f;
    const float y0 = top ? float(layout.view.origin.y) + 8.0f : float(layout.view.origin.y + layout.view.size.y) - 8.0f - side - 1.6f * ImGui::GetFontSize();
    const KernelProbe& kernel = app.lastProbe();
    const float scale = side / (2.0f * kRadius);
    char caption[96];
    std::snprintf(caption, sizeof caption, "x%.0f around %d,%d: %.1f texels wide, lit %.3f", scale, probe.x, probe.y,
                  double(kernel.kernelTexels), double(kernel.lit));
    const float captionWidth = ImGui::CalcTextSize(caption).x, font = ImGui::GetFontSize();
    const ImVec2 min(right - side, y0), max(right, y0 + side);
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    draw->AddRectFilled(ImVec2(right - std::max(side, captionWidth) - 4.0f, min.y - 4.0f), ImVec2(max.x + 4.0f, max.y + 1.6f * font),
                        IM_COL32(0, 0, 0, 200), 4.0f);
    // The display texture is bottom-up: v runs against the view's rows.
    draw->AddImage(reinterpret_cast<ImTextureID>(intptr_t(app.renderer().displayTexture())), min, max,
                   ImVec2(lo.x / render.x, 1.0f - lo.y / render.y), ImVec2(hi.x / render.x, 1.0f - hi.y / render.y));
    const ImVec2 at(min.x + (float(probe.x) + 0.5f - lo.x) * scale, min.y + (float(probe.y) + 0.5f - lo.y) * scale);
    draw->AddLine(ImVec2(at.x - scale, at.y), ImVec2(at.x + scale, at.y), IM_COL32(255, 255, 255, 255), 1.0f);
    draw->AddLine(ImVec2(at.x, at.y - scale), ImVec2(at.x, at.y + scale), IM_COL32(255, 255, 255, 255), 1.0f);
    draw->AddText(ImVec2(right - captionWidth, max.y + 0.2f * font), IM_COL32(225, 225, 225, 255), caption);
}

// The panel's "View" section.
void Ui::drawViewSection(App& app, UiState& state) {
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        static const char* const kFootprint = "texel footprint m (log2 heat map)";
        static const char* const kTexelGrid = "shadow-map texel grid";
        static const char* const kCoverage = "map coverage and light frusta";
        static const char* const kFocusBody = "focus body B (seed 002 eq. 4.2)";
        static const char* const kKernel = "filter kernel under the mouse";
        std::string current = state.view.kind == ViewSelection::Kind::Lit            ? "lit"
                              : state.view.kind == ViewSelection::Kind::Visibility   ? "visibility (shadow term)"
                              : state.view.kind == ViewSelection::Kind::ErrorHeatmap ? "error heatmap (last measurement)"
                              : state.view.kind == ViewSelection::Kind::Footprint    ? kFootprint
                              : state.view.kind == ViewSelection::Kind::TexelGrid    ? kTexelGrid
                              : state.view.kind == ViewSelection::Kind::MapCoverage  ? kCoverage
                              : state.view.kind == ViewSelection::Kind::FocusBody    ? kFocusBody
                              : state.view.kind == ViewSelection::Kind::Kernel       ? kKernel
                                                                                     : state.view.debugImage;
        fieldLabel("image");
        if (ImGui::BeginCombo("##image", current.c_str())) {
            if (ImGui::Selectable("lit")) state.view = {};
            if (ImGui::Selectable("visibility (shadow term)")) state.view = {ViewSelection::Kind::Visibility, ""};
            if (!state.measurement.empty() && ImGui::Selectable("error heatmap (last measurement)"))
                state.view = {ViewSelection::Kind::ErrorHeatmap, ""};
            // The host's views of the maps the technique reports (none for techniques without a map).
            if (ImGui::Selectable(kFootprint)) state.view = {ViewSelection::Kind::Footprint, ""};
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Pixels one shadow-map texel covers along its worst direction (seed 002 eq. 8.1, dp/ds).\n"
                                  "Red: m > 1, texels larger than pixels (undersampled, jagged edges); blue: texels wasted.");
            if (ImGui::Selectable(kTexelGrid)) state.view = {ViewSelection::Kind::TexelGrid, ""};
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("The shadow map's texel edges projected on the receivers.");
            if (ImGui::Selectable(kCoverage)) state.view = {ViewSelection::Kind::MapCoverage, ""};
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Which map (or cascade, or cube face) serves each pixel, and the edges of each map's volume.");
            if (ImGui::Selectable(kFocusBody)) state.view = {ViewSelection::Kind::FocusBody, ""};
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("White: the edges of the focus body B = ((V n S) + l) n S n L the map was fitted to (fit = "
                                  "focus-body): the visible part of the scene swept towards the light.\nColoured: the map's "
                                  "volume, B's bounding box in light space.");
            if (ImGui::Selectable(kKernel)) state.view = {ViewSelection::Kind::Kernel, ""};
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("The filter's footprint around the pixel under the mouse, on the receiver: the PCF box, the "
                                  "adaptive disc (grey: samples skipped by the early out), PCSS's blocker search (red: "
                                  "blockers) and penumbra disc, with the numbers below.");
            std::string error;
            if (LoadedTechnique* loaded = app.techniques().get(state.technique, error))
                for (const auto& image : loaded->host().debugImages())
                    if (ImGui::Selectable(image.name.c_str())) state.view = {ViewSelection::Kind::DebugImage, image.name};
            ImGui::EndCombo();
        }
        if (state.view.kind == ViewSelection::Kind::Kernel) {
            const KernelProbe& probe = app.lastProbe();
            ImGui::PushTextWrapPos(0.0f);
            if (app.probePixel()) ImGui::Text("pixel %d, %d", app.probePixel()->x, app.probePixel()->y);
            ImGui::TextUnformatted(describeProbe(probe).c_str());
            ImGui::PopTextWrapPos();
        }
        const char* cameraModes[] = {"orbit (drag, wheel, middle-drag)", "fly (WASD QE + drag)"};
        int mode = app.camera().mode() == CameraController::Mode::Orbit ? 0 : 1;
        fieldLabel("camera");
        if (ImGui::Combo("##camera", &mode, cameraModes, 2))
            app.camera().setMode(mode == 0 ? CameraController::Mode::Orbit : CameraController::Mode::Fly);
        if (ImGui::Button("Reset camera")) app.camera().reset(app.scene().camera);
        bool msaa = state.msaaSamples > 0;
        if (checkbox("MSAA 4x", &msaa, "Multisampling of the main pass. Accuracy runs use it off: resolving averages the "
                                       "G-buffer at edges."))
            state.msaaSamples = msaa ? 4 : 0;
        if (ImGui::Button("Screenshot (F12)")) state.commands.push_back({UiCommand::Kind::Screenshot, ""});
        if (!state.lastScreenshot.empty()) ImGui::TextWrapped("%s", state.lastScreenshot.c_str());
        if (!app.scene().name.empty())
            ImGui::TextWrapped("scene: %s, %zu triangles", app.scene().name.c_str(), app.scene().triangleCount());
        fieldLabel("load scene (name or JSON path)");
        if (ImGui::InputText("##scene", &sceneInput_, ImGuiInputTextFlags_EnterReturnsTrue))
            state.commands.push_back({UiCommand::Kind::LoadScene, sceneInput_});
        if (ImGui::Button("Load scene")) state.commands.push_back({UiCommand::Kind::LoadScene, sceneInput_});
        if (!state.sceneError.empty()) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.4f, 0.4f, 1));
            ImGui::TextWrapped("%s", state.sceneError.c_str());
            ImGui::PopStyleColor();
        }
    }
}

// The panel's "Accuracy" section.
void Ui::drawAccuracySection(App& app, UiState& state) {
    if (ImGui::CollapsingHeader("Accuracy", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char* modes[] = {"each technique's own (hard or soft)", "hard reference", "soft reference"};
        fieldLabel("against", "Traces the ray-traced reference (Embree, CPU) from the G-buffer of the frame on screen and "
                              "compares the technique's shadow term per pixel; in a comparison each side is measured for "
                              "its own technique. By default each technique against its own kind of reference, as "
                              "the tour pages: hard for hard shadow maps, soft (rays over the light's area) for "
                              "filtered and soft ones, whose penumbrae a hard reference would count as error. The trace "
                              "runs beside the frame loop, so the view keeps drawing; "
                              "changing the scene or the technique cancels it. The heatmap shows false shadow (acne, "
                              "over-darkening) in magenta and false light (leaks, peter panning) in green over the dimmed "
                              "scene.");
        ImGui::Combo("##against", &state.referenceMode, modes, 3);
        if (state.referenceMode != 1) {
            fieldLabel("rays per pixel");
            ImGui::SliderInt("##rays", &state.referenceSamples, 4, 256);
        }
        // Translucent casters: the physical model (1 - a) + a t, or the one the technique declares
        // (in a comparison, each side's own).
        const TechniqueInfo* judged = app.techniques().find(state.technique);
        const TranslucencyModel ownModel = judged ? judged->translucencyModel : TranslucencyModel::Opaque;
        const std::string ownLabel = state.compareTechnique.empty()
                                         ? std::string("technique's own (") + translucencyModelName(ownModel) + ")"
                                         : std::string("each technique's own");
        const char* models[] = {"physical", ownLabel.c_str()};
        fieldLabel("translucency model");
        ImGui::Combo("##translucency-model", &state.referenceModel, models, 2);
        if (ImGui::Button(state.measuring ? "Measure again (M)" : "Measure accuracy (M)"))
            state.commands.push_back({UiCommand::Kind::Measure, ""});
        if (state.measuring) {
            // The reference is traced on a worker: the view keeps drawing meanwhile.
            ImGui::TextWrapped("measuring: %s", state.measureStage.c_str());
            ImGui::ProgressBar(state.measureProgress, ImVec2(-1.0f, 0.0f));
            if (ImGui::Button("Cancel")) state.commands.push_back({UiCommand::Kind::CancelMeasure, ""});
        }
        if (!state.measureError.empty()) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.4f, 0.4f, 1));
            ImGui::TextWrapped("%s", state.measureError.c_str());
            ImGui::PopStyleColor();
        }
        if (!state.measurement.empty() && !state.staleReason.empty())
            ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "stale: %s", state.staleReason.c_str());
        for (size_t s = 0; s < state.measurement.size(); ++s) {
            const SideMeasurement& side = state.measurement[s];
            const AccuracyMetrics& m = side.metrics;
            if (state.measurement.size() > 1) ImGui::Text("%c", char('A' + s));
            ImGui::TextWrapped("%s", side.label.c_str());
            ImGui::TextWrapped("MAE %.4f   RMSE %.4f\nfalse shadow %.3f%%   false light %.3f%%\n"
                               "MAE in penumbra %.4f, elsewhere %.4f\ncompared %.1f%% of pixels (traced in %.2f s)\n"
                               "%.3f ms GPU, %.2f MiB",
                               m.mae, m.rmse, 100.0 * m.falseShadowRate, 100.0 * m.falseLightRate, m.maePenumbra,
                               m.maeOutsidePenumbra, 100.0 * m.comparedFraction, side.traceSeconds, side.gpuMs,
                               double(side.gpuBytes) / (1024.0 * 1024.0));
            if (side.translucentMetrics.comparedPixels > 0) {
                // Seed 001 sec. 5.3.3: the translucent surfaces themselves, peeled from the camera.
                const AccuracyMetrics& t = side.translucentMetrics;
                ImGui::TextWrapped("translucent receivers (%zu layers, %zu px): MAE %.4f (r %.4f g %.4f b %.4f)", side.translucentLayers,
                                   t.comparedPixels, t.mae, t.maePerChannel.r, t.maePerChannel.g, t.maePerChannel.b);
            }
        }
        if (!state.measurement.empty() && ImGui::Button("Show error heatmap")) state.view = {ViewSelection::Kind::ErrorHeatmap, ""};
        drawSpeedAccuracyPlot(state.measured);
    }
}

// The panel's "Light" section.
void Ui::drawLightSection(App& app) {
    if (ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) {
        LightInfo& light = app.light();
        const glm::vec3 toLight = -glm::normalize(light.direction);
        float azimuth = glm::degrees(std::atan2(toLight.z, toLight.x));
        float elevation = glm::degrees(std::asin(std::clamp(toLight.y, -1.0f, 1.0f)));
        fieldLabel("azimuth");
        bool changed = ImGui::SliderFloat("##azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
        fieldLabel("elevation", "Direction the light comes from. Low elevations give long shadows and make acne and "
                                "aliasing easy to see.");
        changed |= ImGui::SliderFloat("##elevation", &elevation, 1.0f, 90.0f, "%.1f deg");
        if (changed) {
            const float a = glm::radians(azimuth), e = glm::radians(elevation);
            light.direction = -glm::vec3(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
        }
        const std::string sizeHelp = "Size of the emitter: soft-shadow techniques widen their penumbrae with it; hard "
                                     "techniques ignore it.";
        if (light.type == LightType::Directional) {
            fieldLabel("angular radius (degrees)", sizeHelp);
            float size = glm::degrees(light.size);
            if (ImGui::SliderFloat("##light-size", &size, 0.0f, 10.0f, "%.2f deg")) light.size = glm::radians(size);
        } else {
            fieldLabel("radius (scene units)", sizeHelp);
            ImGui::SliderFloat("##light-size", &light.size, 0.0f, 2.0f, "%.3f");
        }
    }
}

// The panel's "Timing and memory" section.
void Ui::drawTimingSection(App& app, UiState& state) {
    if (ImGui::CollapsingHeader("Timing and memory", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextWrapped("%.1f FPS  (%.2f ms per frame, host CPU %.3f ms)", 1000.0f / std::max(smoothedFrameMs_, 1e-3f),
                           smoothedFrameMs_, app.lastCpuFrameMs());
        const std::vector<std::string> sides = shownTechniques(state);
        for (size_t s = 0; s < sides.size(); ++s) {
            if (sides.size() > 1) ImGui::TextWrapped("%c: %s", char('A' + s), techniqueTitle(app, sides[s]).c_str());
            timingsTable(("passes-" + std::to_string(s)).c_str(), state.sideTimings[s]);
            std::string error;
            if (LoadedTechnique* loaded = app.techniques().get(sides[s], error)) {
                ImGui::Text("technique GPU memory: %.2f MiB", double(loaded->host().gpuBytes()) / (1024.0 * 1024.0));
                for (const auto& [name, allocation] : loaded->host().textures())
                    ImGui::TextDisabled("  %s: %.2f MiB", allocation.label.c_str(), double(allocation.bytes) / (1024.0 * 1024.0));
                for (const auto& [name, value] : loaded->host().statistics()) ImGui::Text("%s: %.4g", name.c_str(), value);
            }
        }
    }
}

// The panel's "Hot reload and log" section.
void Ui::drawReloadSection(App& app) {
    if (ImGui::CollapsingHeader("Hot reload and log")) {
        ImGui::TextWrapped("Rebuild a plugin (cmake --build build) or save a .glsl file: it is reloaded in place. "
                           "Failures keep the running version.");
        const std::string& pluginError = app.techniques().lastReloadError();
        const std::string& shaderError = app.shaders().lastReloadError();
        if (!pluginError.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", pluginError.c_str());
        if (!shaderError.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", shaderError.c_str());
        for (const auto& error : app.techniques().scanErrors()) ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1), "%s", error.c_str());
        ImGui::BeginChild("log", ImVec2(0, 12.0f * ImGui::GetFontSize()), true);
        const auto log = recentLog();
        const bool atBottom = ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 1.0f;
        for (const auto& entry : log) {
            const ImVec4 color = entry.level == LogLevel::Error     ? ImVec4(1, 0.4f, 0.4f, 1)
                                 : entry.level == LogLevel::Warning ? ImVec4(1, 0.8f, 0.3f, 1)
                                                                    : ImVec4(0.8f, 0.8f, 0.8f, 1);
            ImGui::PushStyleColor(ImGuiCol_Text, color);
            ImGui::PushTextWrapPos(0.0f);
            ImGui::TextUnformatted(entry.message.c_str());
            ImGui::PopTextWrapPos();
            ImGui::PopStyleColor();
        }
        // Follow the newest line unless the reader has scrolled up to read an older one.
        const std::string newest = log.empty() ? std::string() : log.back().message;
        if (newest != newestLogLine_ && atBottom) ImGui::SetScrollHereY(1.0f);
        newestLogLine_ = newest;
        ImGui::EndChild();
    }
}

// The panel's "Host passes" section.
void Ui::drawHostSection(App& app) {
    if (ImGui::CollapsingHeader("Host passes")) {
        const TechniqueInfo& host = hostParams();
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(host.explanation.c_str());
        ImGui::PopTextWrapPos();
        auto& values = app.params().values(host);
        for (size_t i = 0; i < host.params.size(); ++i) parameterWidget(host.params[i], values[i]);
        // The pre-pass's mode and what the last frame did (auto's decision and what it is based on).
        const DepthPrepassRule& rule = app.depthPrepassRule();
        const DepthPrepassMode mode = app.depthPrepassMode();
        char complexity[64] = "not measured yet";
        if (rule.complexity()) std::snprintf(complexity, sizeof complexity, "%.2f opaque fragments per pixel", *rule.complexity());
        ImGui::Text("Depth pre-pass: %s, %s", depthPrepassModeName(mode), app.depthPrepassActive() ? "running" : "not running");
        ImGui::TextDisabled("depth complexity %s; auto: %s", complexity, rule.autoDecision() ? "on" : "off");
    }
}

// "compare with (B)", the layout, and the grid's C and D.
void Ui::drawComparePicker(App& app, UiState& state) {
    fieldLabel("compare with (B)",
               "Side by side: the view split in two, both halves with the whole camera framing. Wipe: one framing, A left "
               "of a divider you drag, B right of it. Difference: where the two shadow terms differ.");
    const TechniqueInfo* compareInfo = app.techniques().find(state.compareTechnique);
    if (ImGui::BeginCombo("##compare", compareInfo ? compareInfo->displayName.c_str() : "(nothing)")) {
        if (ImGui::Selectable("(nothing)", state.compareTechnique.empty())) state.compareTechnique.clear();
        for (const auto& t : app.techniques().techniques())
            if (ImGui::Selectable((t.displayName + "##compare" + t.id).c_str(), t.id == state.compareTechnique))
                state.compareTechnique = t.id;
        ImGui::EndCombo();
    }
    if (!state.compareTechnique.empty()) {
        int layout = int(state.compareLayout);
        ImGui::RadioButton("side by side", &layout, int(CompareLayout::SideBySide));
        ImGui::SameLine();
        ImGui::RadioButton("wipe", &layout, int(CompareLayout::Wipe));
        ImGui::SameLine();
        ImGui::RadioButton("difference", &layout, int(CompareLayout::Difference));
        ImGui::RadioButton("grid (three or four: C and D below)", &layout, int(CompareLayout::Grid));   // its own line: the panel is narrow
        state.compareLayout = CompareLayout(layout);
    }
    if (!state.compareTechnique.empty() && state.compareLayout == CompareLayout::Grid) {
        // C and D: the grid's lower quarters (D may stay empty).
        state.gridTechniques.resize(2);
        for (int i = 0; i < 2; ++i) {
            std::string& id = state.gridTechniques[size_t(i)];
            const TechniqueInfo* cell = app.techniques().find(id);
            fieldLabel(i == 0 ? "grid: C (lower left)" : "grid: D (lower right)");
            if (ImGui::BeginCombo(i == 0 ? "##grid-c" : "##grid-d", cell ? cell->displayName.c_str() : "(nothing)")) {
                if (ImGui::Selectable("(nothing)", id.empty())) id.clear();
                for (const auto& t : app.techniques().techniques())
                    if (ImGui::Selectable((t.displayName + "##grid" + std::to_string(i) + t.id).c_str(), t.id == id)) id = t.id;
                ImGui::EndCombo();
            }
        }
    }
}

void Ui::drawPanel(App& app, UiState& state) {
    const PixelRect& panel = state.layout.panel;
    ImGui::SetNextWindowPos(ImVec2(float(panel.origin.x), float(panel.origin.y)), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(float(panel.size.x), float(panel.size.y)), ImGuiCond_Always);
    ImGui::Begin("shadowlab", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    drawStatusLine(app, state, false);
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("? lists every key. F1 or H hides this panel, P presents, F12 saves a screenshot, M measures "
                       "accuracy, F5 saves the session");
    ImGui::PopStyleColor();
    ImGui::Separator();
    drawTourPlayer(app, state);

    // Technique picker, grouped by category.
    const TechniqueInfo* info = app.techniques().find(state.technique);
    fieldLabel(state.compareTechnique.empty() ? "technique" : "technique A (left)");
    if (ImGui::BeginCombo("##technique", info ? info->displayName.c_str() : state.technique.c_str())) {
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
    drawComparePicker(app, state);
    info = app.techniques().find(state.technique);
    if (info) {
        ImGui::TextDisabled("%s  |  %s", info->category.c_str(), info->id.c_str());
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(info->explanation.c_str());
        // What it reported on its last frame decides which of the host's views show something.
        const std::string views = app.debugViewsOf(state.technique);
        ImGui::TextDisabled("Debug views here: %s", views.empty() ? "none (lit, visibility and error only)" : views.c_str());
        if (info->debugViewsDeclared) {   // what the descriptor says applies (some only with a parameter set)
            std::string declared;
            for (const std::string& view : info->debugViews) declared += (declared.empty() ? "" : ", ") + view;
            ImGui::TextDisabled("Declared: %s", declared.empty() ? "none" : declared.c_str());
        }
        ImGui::PopTextWrapPos();
        if (!info->params.empty() && ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen)) {
            auto& values = app.params().values(*info);
            for (size_t i = 0; i < info->params.size(); ++i) parameterWidget(info->params[i], values[i]);
            if (ImGui::Button("Reset to defaults")) app.params().resetToDefaults(*info);
        }
    }
    // The host's own parameters (plugin/host_params.h: the eye-space blur and lighting rules of
    // seed 002 ch. 6), with any technique.
    drawHostSection(app);
    if (!state.frameError.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(state.frameError.c_str());
        ImGui::PopTextWrapPos();
        ImGui::PopStyleColor();
    }

    drawLightSection(app);

    drawViewSection(app, state);

    drawLessonSection(app, state);

    drawPathSection(app, state);

    drawTimingSection(app, state);

    drawAccuracySection(app, state);

    drawReloadSection(app);

    if (ImGui::CollapsingHeader("Display")) {
        fieldLabel("UI scale", "Fonts and spacing; 1.5 to 2 for a projector. Also --ui-scale.");
        if (!ImGui::IsAnyItemActive()) scaleSlider_ = state.uiScale;
        ImGui::SliderFloat("##ui-scale", &scaleSlider_, 0.75f, 3.0f, "%.2f");
        // Applied when the slider is released: the fonts are rasterised again at the new size.
        if (ImGui::IsItemDeactivatedAfterEdit()) state.uiScale = scaleSlider_;
    }
    ImGui::End();
}

} // namespace shadowlab
