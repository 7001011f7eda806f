// Presenter mode and the help overlay (see ui.h): what a lecturer shows on a projector. The
// panel is hidden; the tour step's caption is drawn large over the bottom of the view with the
// figures of what is on screen beside it (each side's GPU time, its accuracy once measured), and
// `?` lists every key from the table that binds them (ui/keys.h).
#include <algorithm>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "ui/keys.h"
#include "ui/ui.h"

namespace shadowlab {
namespace {

// A box of `width` holding `text` wrapped, its height measured now: auto-resizing would lag a
// frame behind text that changes (the GPU time arrives frames late) and cut a slide's last line.
ImVec2 presenterBoxSize(const std::string& text, float width, float maxHeight) {
    const ImVec2 padding = ImGui::GetStyle().WindowPadding;
    const ImVec2 textSize = ImGui::CalcTextSize(text.c_str(), nullptr, false, width - 2.0f * padding.x);
    return ImVec2(width, std::min(maxHeight, textSize.y + 2.0f * (padding.y + ImGui::GetStyle().ItemSpacing.y)));
}

constexpr ImGuiWindowFlags kPresenterWindowFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings |
                                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoMove |
                                                   ImGuiWindowFlags_NoNav;

std::string presenterSideTitle(App& app, const std::string& id) {
    const TechniqueInfo* info = app.techniques().find(id);
    return info ? info->displayName + " (" + id + ")" : id;
}

// The figures of side `s`: its GPU time and, once measured, its accuracy (marked stale when the
// view has changed since).
std::string presenterSideFigures(App& app, const UiState& state, int s, const std::string& id) {
    std::string text = (state.compareTechnique.empty() ? "" : std::string(1, char('A' + s)) + ": ") + presenterSideTitle(app, id);
    char line[160];
    const auto frame = state.sideTimings[s].find("frame");
    if (frame != state.sideTimings[s].end()) {
        std::snprintf(line, sizeof line, "\nGPU %.2f ms a frame", frame->second);
        text += line;
    }
    if (size_t(s) < state.measurement.size()) {
        const AccuracyMetrics& m = state.measurement[size_t(s)].metrics;
        std::snprintf(line, sizeof line, "\nMAE %.4f\nfalse shadow %.2f%%, false light %.2f%%", m.mae, 100.0 * m.falseShadowRate,
                      100.0 * m.falseLightRate);
        text += line;
        if (!state.staleReason.empty()) text += "\n(stale: " + state.staleReason + ")";
    }
    return text;
}

} // namespace

std::vector<std::string> shownTechniques(const UiState& state) {
    std::vector<std::string> sides{state.technique};
    if (state.compareTechnique.empty()) return sides;
    sides.push_back(state.compareTechnique);
    if (state.compareLayout == CompareLayout::Grid)
        for (const std::string& id : state.gridTechniques)
            if (!id.empty() && sides.size() < size_t(kMaxGridSides)) sides.push_back(id);
    return sides;
}

void setPresenter(UiState& state, bool on) {
    state.presenter = on;
    state.showUi = !on;
    state.showHelp = false;
}

void Ui::drawPresenterOverlay(App& app, const UiState& state) {
    const PixelRect& view = state.layout.view;
    const float margin = 0.02f * float(std::min(view.size.x, view.size.y));
    const float bottom = float(view.origin.y + view.size.y) - margin;
    const float captionWidth = 0.64f * float(view.size.x) - 1.5f * margin;
    const float figuresWidth = float(view.size.x) - captionWidth - 3.0f * margin;
    if (largeFont_) ImGui::PushFont(largeFont_);
    // The caption: the tour step's, or the technique's name outside a tour.
    std::string heading, caption;
    if (state.tour && !state.tour->steps.empty()) {
        const int count = int(state.tour->steps.size());
        const int index = std::clamp(state.tourStep, 0, count - 1);
        const TourStep& step = state.tour->steps[size_t(index)];
        heading = std::to_string(index + 1) + "/" + std::to_string(count) + "  " + step.title;
        caption = step.caption;
    } else {
        heading = presenterSideTitle(app, state.technique);
    }
    const float maxHeight = 0.6f * float(view.size.y);
    ImGui::SetNextWindowPos(ImVec2(float(view.origin.x) + margin, bottom), ImGuiCond_Always, ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowSize(presenterBoxSize(heading + "\n" + caption, captionWidth, maxHeight));
    ImGui::SetNextWindowBgAlpha(0.78f);
    ImGui::Begin("##presenter-caption", nullptr, kPresenterWindowFlags);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(0.55f, 0.8f, 1.0f, 1.0f), "%s", heading.c_str());
    if (!caption.empty()) ImGui::TextUnformatted(caption.c_str());
    ImGui::PopTextWrapPos();
    ImGui::End();
    // The figures beside it.
    std::string figures;
    const std::vector<std::string> sides = shownTechniques(state);
    for (size_t s = 0; s < sides.size(); ++s) figures += (s ? "\n\n" : "") + presenterSideFigures(app, state, int(s), sides[s]);
    if (state.path && state.path->frames > 0)
        figures += "\n\npath " + state.pathName + ": frame " + std::to_string(state.pathFrame % state.path->frames + 1) + " of " +
                   std::to_string(state.path->frames);
    ImGui::SetNextWindowPos(ImVec2(float(view.origin.x + view.size.x) - margin, bottom), ImGuiCond_Always, ImVec2(1.0f, 1.0f));
    ImGui::SetNextWindowSize(presenterBoxSize(figures, figuresWidth, maxHeight));
    ImGui::SetNextWindowBgAlpha(0.78f);
    ImGui::Begin("##presenter-figures", nullptr, kPresenterWindowFlags);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(figures.c_str());
    ImGui::PopTextWrapPos();
    ImGui::End();
    if (largeFont_) ImGui::PopFont();
}

void Ui::drawHelpOverlay(const UiState& state) {
    const PixelRect& view = state.layout.view;
    ImGui::SetNextWindowPos(ImVec2(float(view.origin.x) + 0.5f * float(view.size.x), float(view.origin.y) + 0.5f * float(view.size.y)),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.9f);
    ImGui::Begin("Keys (? closes)", nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoFocusOnAppearing);
    for (const std::string& line : keyHelpLines()) ImGui::TextUnformatted(line.c_str());
    ImGui::End();
}

} // namespace shadowlab
