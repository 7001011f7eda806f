// Guided tours and saved sessions (see tour.h).
#include "ui/tour.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <map>
#include <set>

#include "scene/scene.h"
#include "util/paths.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

using nlohmann::json;

// A finite number that stays finite as a float (the GL side stores most values as float).
bool finiteNumber(const json& value, double& out) {
    if (!value.is_number()) return false;
    out = value.get<double>();
    return std::isfinite(out) && std::abs(out) <= double(std::numeric_limits<float>::max());
}

std::string typeName(const json& value) {
    return value.is_string() ? "a string" : value.is_number() ? "a number" : value.is_boolean() ? "a boolean"
           : value.is_array() ? "an array" : value.is_object() ? "an object" : "null";
}

bool rejectUnknownKeys(const json& object, const std::set<std::string>& allowed, const std::string& where, std::string& error) {
    for (const auto& [key, value] : object.items()) {
        if (allowed.count(key)) continue;
        std::string known;
        for (const auto& name : allowed) appendListItem(known, name);
        error = where + ": unknown field '" + key + "' (expected " + known + ")";
        return false;
    }
    return true;
}

bool readString(const json& object, const char* key, const std::string& where, std::string& out, std::string& error,
                bool required, size_t maxBytes = 1024) {
    if (!object.contains(key)) {
        if (!required) return true;
        error = where + ": missing '" + key + "'";
        return false;
    }
    const json& value = object[key];
    if (!value.is_string()) {
        error = where + "." + key + ": expected a string, found " + typeName(value);
        return false;
    }
    out = value.get<std::string>();
    if (out.size() > maxBytes) {
        error = where + "." + key + ": " + std::to_string(out.size()) + " bytes, at most " + std::to_string(maxBytes);
        return false;
    }
    if (required && out.empty()) {
        error = where + "." + key + ": must not be empty";
        return false;
    }
    return true;
}

bool readVec3(const json& value, const std::string& where, glm::vec3& out, std::string& error) {
    bool valid = value.is_array() && value.size() == 3;
    for (size_t i = 0; valid && i < 3; ++i) {
        double number = 0.0;
        valid = finiteNumber(value[i], number) && std::abs(number) <= kMaxWorldCoordinate;
        out[glm::length_t(i)] = float(number);
    }
    if (!valid) error = where + ": expected [x, y, z], three finite numbers within +-1e9";
    return valid;
}

// Parameter values as --set takes them: a number in full precision (so a saved session reads
// back the same double), true/false, or an enum label.
bool valueText(const json& value, const std::string& where, std::string& text, std::string& error) {
    double number = 0.0;
    if (value.is_boolean()) {
        text = value.get<bool>() ? "true" : "false";
    } else if (value.is_string() && !value.get<std::string>().empty() && value.get<std::string>().size() <= 256) {
        text = value.get<std::string>();
    } else if (finiteNumber(value, number)) {
        char buffer[32];
        std::snprintf(buffer, sizeof(buffer), "%.17g", number);
        text = buffer;
    } else {
        error = where + ": expected a number, true/false or an enum label, found " + typeName(value);
        return false;
    }
    return true;
}

json textValue(const std::string& text) {
    if (text == "true") return true;
    if (text == "false") return false;
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    if (!text.empty() && end && *end == '\0' && std::isfinite(number)) {
        if (number == std::floor(number) && std::abs(number) < 1e15) return static_cast<long long>(number);
        return number;
    }
    return text;
}

bool isBuiltinScene(const std::string& name) {
    const auto names = builtinSceneNames();
    return std::find(names.begin(), names.end(), name) != names.end();
}

std::string availableTechniques(const std::vector<TechniqueInfo>& techniques) {
    std::string known;
    for (const auto& t : techniques) appendListItem(known, t.id);
    return known;
}

const TechniqueInfo* findTechnique(const std::vector<TechniqueInfo>& techniques, const std::string& id) {
    for (const auto& t : techniques)
        if (t.id == id) return &t;
    return nullptr;
}

// A step's path names a file (rather than a built-in path) when it holds a '/', ends in .json or
// names a file that exists (relative to `baseDir` when given), as --path's rule.
bool tourPathIsFile(const std::string& text, const std::filesystem::path& baseDir = {}) {
    const auto& names = builtinPathNames();
    if (std::find(names.begin(), names.end(), text) != names.end()) return false;
    std::error_code ignored;
    const std::filesystem::path file = baseDir.empty() || std::filesystem::path(text).is_absolute() ? std::filesystem::path(text)
                                                                                                     : baseDir / text;
    return text.find('/') != std::string::npos || text.ends_with(".json") || std::filesystem::exists(file, ignored);
}

} // namespace

// A step's "camera": {position, target, fov}.
static bool readTourCamera(const json& object, const std::string& where, TourStep& step, std::string& error) {
    const json& camera = object;
    const std::string at = where + ".camera";
    if (!camera.is_object()) {
        error = at + ": expected an object {position, target, fov}, found " + typeName(camera);
        return false;
    }
    if (!rejectUnknownKeys(camera, {"position", "target", "fov"}, at, error)) return false;
    if (!camera.contains("position") || !camera.contains("target")) {
        error = at + ": needs 'position' and 'target'";
        return false;
    }
    TourCamera c;
    if (!readVec3(camera["position"], at + ".position", c.position, error)) return false;
    if (!readVec3(camera["target"], at + ".target", c.target, error)) return false;
    // The scene's check (its up vector is known only in checkTourStep, which checks the view against it).
    if (const std::string problem = cameraProblem(c.position, c.target); !problem.empty()) {
        error = at + ": " + problem;
        return false;
    }
    if (camera.contains("fov")) {
        double fov = 0.0;
        if (!finiteNumber(camera["fov"], fov) || fov < 1.0 || fov > 170.0) {
            error = at + ".fov: expected the vertical field of view in degrees, 1 to 170";
            return false;
        }
        c.fovDegrees = float(fov);
    }
    step.camera = c;
    return true;
}

// A step's "light": {direction, size}.
static bool readTourLight(const json& object, const std::string& where, TourStep& step, std::string& error) {
    const json& light = object;
    const std::string at = where + ".light";
    if (!light.is_object()) {
        error = at + ": expected an object {direction, size}, found " + typeName(light);
        return false;
    }
    if (!rejectUnknownKeys(light, {"direction", "size"}, at, error)) return false;
    if (light.contains("direction")) {
        glm::vec3 direction;
        if (!readVec3(light["direction"], at + ".direction", direction, error)) return false;
        if (const std::string problem = directionProblem(direction); !problem.empty()) {
            error = at + ".direction: " + problem;
            return false;
        }
        step.light.direction = direction;
    }
    if (light.contains("size")) {
        double size = 0.0;
        if (!finiteNumber(light["size"], size)) {
            error = at + ".size: expected a finite number (degrees for a directional light)";
            return false;
        }
        step.light.size = size;
    }
    return true;
}

bool parseTourStep(const json& object, const std::string& where, const std::filesystem::path& baseDir, TourStep& step,
                   std::string& error) {
    step = {};
    if (!object.is_object()) {
        error = where + ": expected an object (a step), found " + typeName(object);
        return false;
    }
    if (!rejectUnknownKeys(object,
                           {"title", "scene", "sceneParameters", "technique", "compare", "layout", "wipe", "parameters",
                            "camera", "light", "view", "path", "pathFrames", "caption", "expect"},
                           where, error))
        return false;
    if (!readString(object, "title", where, step.title, error, true, 200)) return false;
    if (!readString(object, "scene", where, step.scene, error, true)) return false;
    if (!isBuiltinScene(step.scene) && std::filesystem::path(step.scene).is_relative() && !baseDir.empty())
        step.scene = (baseDir / step.scene).lexically_normal().string();
    if (object.contains("sceneParameters")) {
        const json& params = object["sceneParameters"];
        if (!params.is_object()) {
            error = where + ".sceneParameters: expected an object of name: number, found " + typeName(params);
            return false;
        }
        for (const auto& [name, value] : params.items()) {
            double number = 0.0;
            if (!finiteNumber(value, number)) {
                error = where + ".sceneParameters." + name + ": expected a finite number, found " + typeName(value);
                return false;
            }
            step.sceneParameters.emplace_back(name, number);
        }
    }
    if (!readString(object, "technique", where, step.technique, error, true, 64)) return false;
    if (!readString(object, "compare", where, step.compare, error, false, 64)) return false;
    std::string layout;
    if (!readString(object, "layout", where, layout, error, false, 64)) return false;
    if (!layout.empty() && !parseCompareLayout(layout, step.layout)) {
        error = where + ".layout: '" + layout + "': expected side-by-side, wipe or difference";
        return false;
    }
    if (!layout.empty() && step.compare.empty()) {
        error = where + ".layout: a layout needs 'compare' (the second technique)";
        return false;
    }
    if (object.contains("wipe")) {
        double wipe = 0.0;
        if (!finiteNumber(object["wipe"], wipe) || wipe < 0.0 || wipe > 1.0) {
            error = where + ".wipe: expected a number from 0 to 1";
            return false;
        }
        step.wipe = float(wipe);
    }
    if (object.contains("parameters")) {
        const json& params = object["parameters"];
        if (!params.is_object()) {
            error = where + ".parameters: expected an object of parameter: value, found " + typeName(params);
            return false;
        }
        for (const auto& [key, value] : params.items()) {
            std::string text;
            if (!valueText(value, where + ".parameters." + key, text, error)) return false;
            step.parameters.emplace_back(key, text);
        }
    }
    if (object.contains("camera") && !readTourCamera(object["camera"], where, step, error)) return false;
    if (object.contains("light") && !readTourLight(object["light"], where, step, error)) return false;
    if (!readString(object, "view", where, step.view, error, false, 128)) return false;
    if (step.view.empty()) step.view = "lit";
    if (object.contains("path")) {
        if (!readString(object, "path", where, step.path, error, true)) return false;
        if (tourPathIsFile(step.path, baseDir) && std::filesystem::path(step.path).is_relative() && !baseDir.empty())
            step.path = (baseDir / step.path).lexically_normal().string();
    }
    if (object.contains("pathFrames")) {
        const json& frames = object["pathFrames"];
        if (!frames.is_number_integer() || frames.get<long long>() < 2 || frames.get<long long>() > 10000) {
            error = where + ".pathFrames: expected a whole number from 2 to 10000";
            return false;
        }
        if (step.path.empty()) {
            error = where + ".pathFrames: needs 'path'";
            return false;
        }
        step.pathFrames = int(frames.get<long long>());
    }
    if (!readString(object, "caption", where, step.caption, error, true, kMaxCaptionBytes)) return false;
    if (object.contains("expect") &&
        !parseTourExpect(object["expect"], where, !step.compare.empty(), !step.path.empty(), step.expect, error))
        return false;
    return true;
}

json tourStepJson(const TourStep& step) {
    json out = json::object();
    out["title"] = step.title;
    out["scene"] = step.scene;
    if (!step.sceneParameters.empty()) {
        json params = json::object();
        for (const auto& [name, value] : step.sceneParameters) params[name] = value;
        out["sceneParameters"] = params;
    }
    out["technique"] = step.technique;
    if (!step.compare.empty()) {
        out["compare"] = step.compare;
        out["layout"] = compareLayoutName(step.layout);
        if (step.layout == CompareLayout::Wipe) out["wipe"] = step.wipe;
    }
    if (!step.parameters.empty()) {
        json params = json::object();
        for (const auto& [key, text] : step.parameters) params[key] = textValue(text);
        out["parameters"] = params;
    }
    if (step.camera) {
        const TourCamera& c = *step.camera;
        out["camera"] = {{"position", {c.position.x, c.position.y, c.position.z}},
                         {"target", {c.target.x, c.target.y, c.target.z}},
                         {"fov", c.fovDegrees}};
    }
    if (step.light.direction || step.light.size) {
        json light = json::object();
        if (step.light.direction) light["direction"] = {step.light.direction->x, step.light.direction->y, step.light.direction->z};
        if (step.light.size) light["size"] = *step.light.size;
        out["light"] = light;
    }
    out["view"] = step.view;
    if (!step.path.empty()) out["path"] = step.path;
    if (step.pathFrames > 0) out["pathFrames"] = step.pathFrames;
    out["caption"] = step.caption;
    if (!step.expect.empty()) out["expect"] = tourExpectJson(step.expect);
    return out;
}

bool parseTour(const json& object, const std::string& source, const std::filesystem::path& baseDir, Tour& tour,
               std::string& error) {
    tour = {};
    tour.source = source;
    if (!object.is_object()) {
        error = source + ": expected an object {title, description, steps}, found " + typeName(object);
        return false;
    }
    if (!rejectUnknownKeys(object, {"title", "description", "steps"}, source, error)) return false;
    if (!readString(object, "title", source, tour.title, error, true, 200)) return false;
    if (!readString(object, "description", source, tour.description, error, false, kMaxCaptionBytes)) return false;
    if (!object.contains("steps") || !object["steps"].is_array() || object["steps"].empty()) {
        error = source + ": 'steps' must be a non-empty array of steps";
        return false;
    }
    const json& steps = object["steps"];
    if (steps.size() > kMaxTourSteps) {
        error = source + ": " + std::to_string(steps.size()) + " steps, at most " + std::to_string(kMaxTourSteps);
        return false;
    }
    for (size_t i = 0; i < steps.size(); ++i) {
        TourStep step;
        const std::string where = source + ": steps[" + std::to_string(i) + "]";
        if (!parseTourStep(steps[i], where, baseDir, step, error)) return false;
        // "previous" names the step before: the first has none, and B of a step without compare is nothing.
        const TourExpectation* first = firstUseOfPreviousStep(step.expect);
        const TourExpectation* firstB = firstUseOfPreviousStep(step.expect, true);
        if ((i == 0 && first) || (i > 0 && firstB && tour.steps.back().compare.empty())) {
            const TourExpectation& e = i == 0 ? *first : *firstB;
            error = where + ".expect." + e.key + ": '" + e.text + "': " +
                    (i == 0 ? "compares with the previous step, and this is the first"
                            : "compares with previous.B, and the previous step has no 'compare'");
            return false;
        }
        tour.steps.push_back(std::move(step));
    }
    return true;
}

bool checkTourStep(const TourStep& step, const std::string& where, const std::vector<TechniqueInfo>& techniques,
                   std::string& error) {
    const std::string name = step.title.empty() ? where : where + " (\"" + step.title + "\")";
    const TechniqueInfo* technique = findTechnique(techniques, step.technique);
    if (!technique) {
        error = name + ": technique '" + step.technique + "': no such technique (available: " + availableTechniques(techniques) + ")";
        return false;
    }
    const TechniqueInfo* compare = step.compare.empty() ? nullptr : findTechnique(techniques, step.compare);
    if (!step.compare.empty() && !compare) {
        error = name + ": compare '" + step.compare + "': no such technique (available: " + availableTechniques(techniques) + ")";
        return false;
    }
    for (const auto& [key, text] : step.parameters) {
        const auto dot = key.find('.');
        const std::string owner = dot == std::string::npos ? step.technique : key.substr(0, dot);
        const std::string param = dot == std::string::npos ? key : key.substr(dot + 1);
        const TechniqueInfo* info = owner == step.technique ? technique : owner == step.compare ? compare : nullptr;
        if (!info) {
            error = name + ": parameters." + key + ": '" + owner + "' is not this step's technique (" + step.technique +
                    (step.compare.empty() ? "" : " or " + step.compare) + ")";
            return false;
        }
        const ParamSpec* spec = info->findParam(param);
        if (!spec) {
            std::string known;
            for (const auto& p : info->params) appendListItem(known, p.id);
            error = name + ": parameters." + key + ": " + info->id + " has no parameter '" + param + "' (parameters: " +
                    (known.empty() ? "none" : known) + ")";
            return false;
        }
        std::string problem;
        if (!parseParamValue(*spec, text, problem)) {
            error = name + ": parameters." + key + ": " + info->id + " " + problem;
            return false;
        }
    }
    for (const TourExpectation& e : step.expect) {
        const std::string& id = e.side == 1 ? step.compare : step.technique;
        const bool errorMetric = e.metric != "frame_ms" && e.metric != "gpu_mib";
        if (id == "reference" && errorMetric) {
            error = name + ": expect." + e.key + ": " + id + " is the ground truth itself; it has no " + e.metric;
            return false;
        }
    }
    std::map<std::string, double> overrides(step.sceneParameters.begin(), step.sceneParameters.end());
    SceneCheck scene;
    try {
        scene = checkScene(step.scene, overrides);
    } catch (const SceneError& e) {
        error = name + ": scene: " + e.what();
        return false;
    }
    if (step.light.size) {
        if (const std::string problem = lightSizeProblem(scene.lightType, *step.light.size); !problem.empty()) {
            error = name + ": light.size: " + problem;
            return false;
        }
    }
    if (step.view.empty()) {
        error = name + ": view: must not be empty";
        return false;
    }
    // The step's camera and light over the scene's, as applyTourStep places them.
    SceneCamera stepCamera = scene.camera;
    LightInfo stepLight = scene.light;
    if (step.camera) {
        stepCamera.position = step.camera->position;
        stepCamera.target = step.camera->target;
        if (const std::string problem = cameraProblem(stepCamera.position, stepCamera.target, glm::dvec3(stepCamera.up));
            !problem.empty()) {
            error = name + ": camera: " + problem + " (scene '" + scene.name + "')";
            return false;
        }
    }
    if (step.light.direction) stepLight.direction = glm::normalize(*step.light.direction);
    if (!step.path.empty()) {
        const std::string at = name + ": path '" + step.path + "'";
        if (step.view == "error") {
            error = at + ": the error view is measured once and goes stale as soon as the path moves the camera "
                         "(use lit, visibility or a debug view)";
            return false;
        }
        if (tourPathIsFile(step.path)) {
            CameraPath path;
            std::string problem;
            if (!loadPathFile(step.path, path, problem)) {
                error = at + ": " + problem;
                return false;
            }
            if (step.pathFrames > 0) path.frames = step.pathFrames;
            // The path's checks from the step's camera and light, as the window will start it (no scene is built here).
            if (const std::string pathError = pathProblem(path, scene.name, stepCamera, stepLight); !pathError.empty()) {
                error = at + ": " + pathError.substr(pathError.rfind(path.source + ": ", 0) == 0 ? path.source.size() + 2 : 0);
                return false;
            }
        } else {
            const auto& names = builtinPathNames();
            if (std::find(names.begin(), names.end(), step.path) == names.end()) {
                std::string known;
                for (const std::string& n : names) appendListItem(known, n);
                error = at + ": not a built-in path (" + known + ") nor a path file (a .json file, relative to the tour file)";
                return false;
            }
            if (step.path == "sweep" && scene.lightType == LightType::Point) {
                error = at + ": turns the light, but scene '" + scene.name + "' has a point light";
                return false;
            }
        }
    }
    return true;
}

bool checkTour(const Tour& tour, const std::vector<TechniqueInfo>& techniques, std::string& error) {
    for (size_t i = 0; i < tour.steps.size(); ++i)
        if (!checkTourStep(tour.steps[i], tour.source + ": steps[" + std::to_string(i) + "]", techniques, error)) return false;
    return true;
}

std::filesystem::path builtinTourDir() { return dataRoot() / "assets" / "tours"; }

std::vector<std::string> builtinTourNames() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(builtinTourDir(), ec))
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

bool loadTour(const std::string& nameOrPath, const std::vector<TechniqueInfo>& techniques, Tour& tour, std::string& error) {
    std::filesystem::path file = nameOrPath;
    const auto names = builtinTourNames();
    if (std::find(names.begin(), names.end(), nameOrPath) != names.end()) {
        file = builtinTourDir() / (nameOrPath + ".json");
    } else if (std::error_code ec; !std::filesystem::exists(file, ec)) {
        std::string known;
        for (const auto& name : names) appendListItem(known, name);
        error = nameOrPath + ": no such tour file (not a built-in tour either; built-in: " + (known.empty() ? "none" : known) + ")";
        return false;
    }
    json object;
    if (!readJsonFile(file, object, error, "tour file")) return false;
    if (!parseTour(object, file.string(), file.parent_path(), tour, error)) return false;
    return checkTour(tour, techniques, error);
}

bool loadSession(const std::filesystem::path& file, const std::vector<TechniqueInfo>& techniques, TourStep& step,
                 std::string& error) {
    std::string text;
    if (!readRegularFile(file, kMaxJsonFileBytes, text, error, "session file")) return false;
    return parseSessionText(text, file.string(), file.parent_path(), techniques, step, error);
}

bool parseSessionText(const std::string& text, const std::string& source, const std::filesystem::path& baseDir,
                      const std::vector<TechniqueInfo>& techniques, TourStep& step, std::string& error) {
    json object;
    if (!parseJsonText(text, source, object, error)) return false;
    if (!parseTourStep(object, source, baseDir, step, error)) return false;
    if (const TourExpectation* e = firstUseOfPreviousStep(step.expect)) {
        error = source + ".expect." + e->key + ": '" + e->text + "': compares with the previous step, and a session is one step";
        return false;
    }
    return checkTourStep(step, source, techniques, error);
}

std::filesystem::path uniqueSessionPath(const std::filesystem::path& folder, const std::string& scene,
                                        const std::string& technique, std::chrono::system_clock::time_point when) {
    // The screenshot's name, as a .json (both never overwrite).
    std::filesystem::path png = uniqueScreenshotPath(folder, scene, technique, "", when);
    std::filesystem::path file = png.replace_extension(".json");
    std::error_code ec;
    for (int n = 2; std::filesystem::exists(file, ec); ++n)
        file = folder / (png.stem().string() + "-" + std::to_string(n) + ".json");
    return file;
}

} // namespace shadowlab
