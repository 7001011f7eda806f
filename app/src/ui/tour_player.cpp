// Tours and sessions on the running app (see tour_player.h).
#include "ui/tour_player.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>

#include "app_paths.h"

namespace shadowlab {

ViewSelection viewFromStepName(const std::string& name) {
    if (name == "error") return {};   // lit until measured (the step's Measure command)
    return viewFromName(name);
}

std::string stepViewName(const ViewSelection& view) { return viewName(view); }

bool applyTourStep(App& app, const TourStep& step, UiState& state, std::string& error) {
    const std::map<std::string, double> overrides(step.sceneParameters.begin(), step.sceneParameters.end());
    if (!app.loadScene(step.scene, overrides, error)) return false;
    for (const std::string& id : {step.technique, step.compare}) {
        if (id.empty()) continue;
        const TechniqueInfo* info = app.techniques().find(id);
        if (!info) {
            error = "technique '" + id + "': no such technique";
            return false;
        }
        app.params().resetToDefaults(*info);
    }
    std::vector<std::string> assignments;
    for (const auto& [key, text] : step.parameters) assignments.push_back(key + "=" + text);
    if (!app.applyAssignments(assignments, step.technique, error)) return false;
    if (step.camera) {
        SceneCamera camera = app.scene().camera;   // near and far planes stay the scene's
        camera.position = step.camera->position;
        camera.target = step.camera->target;
        camera.fovY = glm::radians(step.camera->fovDegrees);
        app.camera().reset(camera);
    }
    LightInfo& light = app.light();
    if (step.light.direction) light.direction = glm::normalize(*step.light.direction);
    if (step.light.size)
        light.size = light.type == LightType::Directional ? glm::radians(float(*step.light.size)) : float(*step.light.size);
    state.path.reset();
    if (!step.path.empty()) {
        // The path starts from the step's camera and light, just placed; restarting the step
        // (applying it again) starts it again from its first frame.
        CameraPath path;
        if (!resolveTourPath(app, step, app.camera().pose(), app.light(), path, error)) return false;
        state.pathCamera = app.camera().pose();
        state.pathLight = app.light();
        state.path = std::move(path);
        state.pathName = step.path;
        state.pathFrames = step.pathFrames;
        state.pathFrame = 0;
        state.pathClock = 0.0f;
        state.pathPlaying = true;
    }
    state.technique = step.technique;
    state.compareTechnique = step.compare;
    state.compareLayout = step.layout;
    state.wipe = step.wipe;
    state.view = viewFromStepName(step.view);
    state.measurement.clear();
    state.staleReason.clear();
    state.measureError.clear();
    state.frameError.clear();
    // Measured after the next frame is drawn, when the main targets have the view's size.
    if (step.view == "error") state.commands.push_back({UiCommand::Kind::Measure, ""});
    return true;
}

// A debug view exists only once its technique has drawn a frame (plugins register their images
// when they create them): one frame of each such technique, before any step is rendered, so a
// view no technique has is refused before the first slide.
bool checkStepView(App& app, const TourStep& step, const std::string& where, std::string& error) {
    const std::string problem = app.viewProblem(step.technique, step.view);
    if (problem.empty()) return true;
    error = where + (step.title.empty() ? "" : " (\"" + step.title + "\")") + ": " + problem;
    return false;
}

bool checkTourDebugViews(App& app, const Tour& tour, std::string& error) {
    for (size_t i = 0; i < tour.steps.size(); ++i)
        if (!checkStepView(app, tour.steps[i], tour.source + ": steps[" + std::to_string(i) + "]", error)) return false;
    return true;
}

bool resolveTourPath(App& app, const TourStep& step, const SceneCamera& camera, const LightInfo& light, CameraPath& path,
                     std::string& error) {
    const Scene& scene = app.scene();
    const auto& builtins = builtinPathNames();
    const bool builtin = std::find(builtins.begin(), builtins.end(), step.path) != builtins.end();
    if (builtin) {
        BuiltinPathOptions options;
        options.frames = step.pathFrames;
        options.camera = camera;
        options.light = light;
        // The dolly moves by a quarter of the step technique's own texel, as the shimmer case.
        if (const TechniqueInfo* info = app.techniques().find(step.technique); info && step.path == "dolly")
            options.texelWorldSize = techniqueTexelWorldSize(app, *info, camera, light, app.renderer().size());
        if (!builtinPath(step.path, scene, options, path, error)) return false;
    } else {
        if (!loadPathFile(step.path, path, error)) return false;
        if (step.pathFrames > 0) path.frames = step.pathFrames;
    }
    if (const std::string problem = pathSceneProblem(path, scene); !problem.empty()) {
        error = problem;
        return false;
    }
    return true;
}

namespace {

// Parameter values as text that reads back as the same double (floats in full precision).
std::string exactValueText(const ParamSpec& spec, double value) {
    if (spec.type != ParamType::Float) return formatParamValue(spec, value);
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", value);
    return text;
}

} // namespace

TourStep captureSession(App& app, const UiState& state) {
    TourStep step;
    const Scene& scene = app.scene();
    step.scene = scene.source.rfind("builtin:", 0) == 0 ? scene.source.substr(8)
                                                        : std::filesystem::absolute(scene.source).lexically_normal().string();
    for (const auto& [name, value] : scene.parameters) step.sceneParameters.emplace_back(name, value);
    step.technique = state.technique;
    step.compare = state.compareTechnique;
    step.layout = state.compareLayout;
    step.wipe = state.wipe;
    for (const std::string& id : {state.technique, state.compareTechnique}) {
        const TechniqueInfo* info = id.empty() ? nullptr : app.techniques().find(id);
        if (!info) continue;
        const auto& values = app.params().values(*info);
        const std::string prefix = id == state.technique ? "" : id + ".";
        for (size_t i = 0; i < info->params.size(); ++i)
            step.parameters.emplace_back(prefix + info->params[i].id, exactValueText(info->params[i], values[i]));
    }
    // On a path the step is the path's: its start (camera and light) and the path itself, so the
    // session plays it again rather than freezing the frame it was saved on.
    const bool onPath = state.path.has_value() && !state.pathName.empty();
    if (onPath) {
        step.path = state.pathName;
        step.pathFrames = state.pathFrames;
    }
    const SceneCamera pose = onPath ? state.pathCamera : app.camera().pose();
    step.camera = TourCamera{pose.position, pose.target, glm::degrees(pose.fovY)};
    const LightInfo& light = onPath ? state.pathLight : app.light();
    step.light.direction = light.direction;
    step.light.size = light.type == LightType::Directional ? double(glm::degrees(light.size)) : double(light.size);
    step.view = stepViewName(state.view);
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M", std::localtime(&now));
    const std::string what = state.technique + (state.compareTechnique.empty() ? "" : " against " + state.compareTechnique);
    step.title = "session: " + what + " on " + scene.name;
    step.caption = "Saved " + std::string(date) + ": " + what + " on " + scene.name + ". Write what to look at here.";
    return step;
}

} // namespace shadowlab
