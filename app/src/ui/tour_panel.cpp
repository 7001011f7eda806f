// The panel's tour player and its "Lesson" section (tours and sessions). Like the rest of the
// panel they only edit state and queue UiCommands; the session applies steps between frames.
#include <algorithm>
#include <cfloat>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "app_paths.h"
#include "ui/ui.h"

namespace shadowlab {
namespace {

void wrappedText(const std::string& text, ImVec4 colour = ImGui::GetStyleColorVec4(ImGuiCol_Text)) {
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
}

const ImVec4 kErrorColour(1.0f, 0.45f, 0.45f, 1.0f);
const ImVec4 kDimColour(0.7f, 0.7f, 0.7f, 1.0f);

} // namespace

// At the top of the panel, beside the view: where the tour is, its buttons, the step's caption
// and the parameters the step set (they stay editable in the parameter panel below).
void Ui::drawTourPlayer(App& app, UiState& state) {
    (void)app;
    if (!state.tour || state.tour->steps.empty()) return;
    const Tour& tour = *state.tour;
    const int count = int(tour.steps.size());
    const int index = std::clamp(state.tourStep, 0, count - 1);
    const TourStep& step = tour.steps[size_t(index)];
    // A new step brings the panel back to its caption, wherever the reader had scrolled to.
    if (index != scrolledToStep_ || state.tour.get() != scrolledTour_) {
        ImGui::SetScrollHereY(0.0f);
        scrolledToStep_ = index;
        scrolledTour_ = state.tour.get();
    }
    wrappedText(tour.title, ImVec4(0.55f, 0.8f, 1.0f, 1.0f));
    wrappedText("step " + std::to_string(index + 1) + " of " + std::to_string(count) + ": " + step.title);
    ImGui::BeginDisabled(index == 0);
    if (ImGui::Button("< Previous")) state.commands.push_back({UiCommand::Kind::TourStep, "previous"});
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Restart step")) state.commands.push_back({UiCommand::Kind::TourStep, "restart"});
    ImGui::SameLine();
    ImGui::BeginDisabled(index + 1 >= count);
    if (ImGui::Button("Next >")) state.commands.push_back({UiCommand::Kind::TourStep, "next"});
    ImGui::EndDisabled();
    ImGui::Separator();
    wrappedText(step.caption);
    if (!step.parameters.empty()) {
        std::string set;
        for (const auto& [key, value] : step.parameters) set += (set.empty() ? "" : ", ") + key + " = " + value;
        wrappedText("set by this step (editable below): " + set, kDimColour);
    }
    if (state.path && state.path->frames > 0) {
        // The step's path plays in a loop; paused, the camera is the user's again.
        wrappedText("path " + step.path + ": frame " + std::to_string(state.pathFrame % state.path->frames + 1) + " of " +
                        std::to_string(state.path->frames) + (state.pathPlaying ? " (looping)" : " (paused)"),
                    kDimColour);
        if (ImGui::Button(state.pathPlaying ? "Pause path" : "Play path")) state.pathPlaying = !state.pathPlaying;
    }
    if (!state.tourStatus.empty()) wrappedText(state.tourStatus, state.tourStatusIsError ? kErrorColour : kDimColour);
    wrappedText("Right / Page Down: next, Left / Page Up: previous, Home: restart the step", kDimColour);
    ImGui::Separator();
}

// Camera and light paths outside tours: a built-in path or a file, from the camera and light on
// screen, played in a loop at a chosen speed (a tour step's path shows here too).
void Ui::drawPathSection(App& app, UiState& state) {
    (void)app;
    if (!ImGui::CollapsingHeader("Camera and light paths")) return;
    ImGui::TextUnformatted("path (built-in, or a JSON path file)");
    ImGui::SetNextItemWidth(-FLT_MIN);
    if (ImGui::BeginCombo("##path-builtin", pathChoice_.c_str())) {
        for (const std::string& name : builtinPathNames())
            if (ImGui::Selectable(name.c_str(), name == pathChoice_)) pathChoice_ = name;
        ImGui::EndCombo();
    }
    ImGui::SetNextItemWidth(-FLT_MIN);
    ImGui::InputText("##path-file", &pathChoice_);
    if (ImGui::Button("Play from here")) state.commands.push_back({UiCommand::Kind::PlayPath, pathChoice_});
    if (state.path) {
        ImGui::SameLine();
        if (ImGui::Button(state.pathPlaying ? "Pause (Space)" : "Play (Space)")) state.pathPlaying = !state.pathPlaying;
        ImGui::SameLine();
        if (ImGui::Button("Stop")) state.commands.push_back({UiCommand::Kind::PlayPath, ""});
        if (ImGui::Button("Export path (GIF, ffmpeg)")) state.commands.push_back({UiCommand::Kind::ExportPath, ""});
        if (state.path->frames > 0)
            wrappedText("path " + state.pathName + ": frame " + std::to_string(state.pathFrame % state.path->frames + 1) + " of " +
                            std::to_string(state.path->frames),
                        kDimColour);
    }
    ImGui::TextUnformatted("speed (path frames per window frame)");
    ImGui::SetNextItemWidth(-FLT_MIN);
    ImGui::SliderFloat("##path-speed", &state.pathSpeed, 0.1f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    if (!state.pathStatus.empty()) wrappedText(state.pathStatus, kErrorColour);
}

// Tours to load and sessions to save or restore.
void Ui::drawLessonSection(App& app, UiState& state) {
    (void)app;
    if (!ImGui::CollapsingHeader("Lesson: tours and sessions")) return;
    const auto names = builtinTourNames();
    ImGui::TextUnformatted("built-in tours");
    for (const auto& name : names)
        if (ImGui::Button(name.c_str())) state.commands.push_back({UiCommand::Kind::LoadTour, name});
    ImGui::TextUnformatted("tour (name or JSON path)");
    ImGui::SetNextItemWidth(-FLT_MIN);
    if (ImGui::InputText("##tour-file", &tourInput_, ImGuiInputTextFlags_EnterReturnsTrue))
        state.commands.push_back({UiCommand::Kind::LoadTour, tourInput_});
    if (ImGui::Button("Load tour")) state.commands.push_back({UiCommand::Kind::LoadTour, tourInput_});
    if (state.tour) {
        ImGui::SameLine();
        if (ImGui::Button("Leave tour")) state.tour.reset();
    }
    if (!state.tourStatus.empty() && !state.tour) wrappedText(state.tourStatus, state.tourStatusIsError ? kErrorColour : kDimColour);
    ImGui::Separator();
    wrappedText("A session is the current scene, technique and parameters, camera, light and view, saved as JSON: "
                "one tour step (paste it into a tour's \"steps\").",
                kDimColour);
    ImGui::TextUnformatted("session file (empty: a new name under sessions/)");
    ImGui::SetNextItemWidth(-FLT_MIN);
    ImGui::InputText("##session-file", &sessionInput_);
    if (ImGui::Button("Save session")) state.commands.push_back({UiCommand::Kind::SaveSession, sessionInput_});
    ImGui::SameLine();
    if (ImGui::Button("Load session") && !sessionInput_.empty())
        state.commands.push_back({UiCommand::Kind::LoadSession, sessionInput_});
    if (!state.sessionStatus.empty()) wrappedText(state.sessionStatus, state.sessionStatusIsError ? kErrorColour : kDimColour);
}

} // namespace shadowlab
