// Camera and light paths (see camera_path.h). Parsing is strict like the scene reader's: every
// field is checked for type and range and an unknown field (a typo) is an error naming it.
#include "scene/camera_path.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab {

namespace {

using nlohmann::json;

constexpr int kMaxPathFrames = 100000;
constexpr size_t kMaxKeyframes = 10000;
constexpr double kDegrees = glm::pi<double>() / 180.0;

// Thrown inside the parser only; parsePath turns it into its error string.
struct PathProblem {
    std::string field, what;
};

[[noreturn]] void fail(const std::string& field, const std::string& what) { throw PathProblem{field, what}; }

void onlyKnownFields(const json& node, const std::string& path, std::initializer_list<const char*> known) {
    if (!node.is_object()) fail(path, "expected an object");
    for (const auto& item : node.items()) {
        bool ok = false;
        std::string list;
        for (const char* key : known) {
            ok = ok || item.key() == key;
            appendListItem(list, key);
        }
        if (!ok) fail(path.empty() ? item.key() : path + "." + item.key(), "unknown field (expected one of: " + list + ")");
    }
}

double finiteNumber(const json& value, const std::string& field, double lo, double hi) {
    if (!value.is_number()) fail(field, "expected a number");
    const double v = value.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) fail(field, "must be between " + formatNumber(lo) + " and " + formatNumber(hi) + " (got " + formatNumber(v) + ")");
    return v;
}

glm::dvec3 vector3(const json& value, const std::string& field) {
    if (!value.is_array() || value.size() != 3) fail(field, "expected an array of 3 numbers");
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = finiteNumber(value[size_t(i)], field + "[" + std::to_string(i) + "]", -kMaxWorldCoordinate, kMaxWorldCoordinate);
    return v;
}

void addKey(PathChannel& channel, int width, double time, glm::dvec3 value) {
    channel.width = width;
    channel.times.push_back(time);
    channel.values.push_back(value);
}

// Catmull-Rom (uniform in keyframe index, tangents from the neighbours; the ends repeat).
glm::dvec3 sampleChannel(const PathChannel& c, double t, PathInterpolation interpolation) {
    const size_t n = c.times.size();
    if (n == 1 || t <= c.times.front()) return c.values.front();
    if (t >= c.times.back()) return c.values.back();
    const size_t i = size_t(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
    const double u = (t - c.times[i]) / (c.times[i + 1] - c.times[i]);
    const glm::dvec3 p1 = c.values[i], p2 = c.values[i + 1];
    if (interpolation == PathInterpolation::Linear) return p1 + (p2 - p1) * u;
    const glm::dvec3 p0 = i > 0 ? c.values[i - 1] : p1, p3 = i + 2 < n ? c.values[i + 2] : p2;
    const double u2 = u * u, u3 = u2 * u;
    return 0.5 * ((2.0 * p1) + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 + (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
}

glm::dvec3 towardsFromAngles(double azimuthDegrees, double elevationDegrees) {
    const double a = azimuthDegrees * kDegrees, e = elevationDegrees * kDegrees;
    // The scene format's convention (docs/scene-format.md, light): towards (cos e cos a, sin e, cos e sin a).
    return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

void parseKeyframe(const json& key, const std::string& at, double time, CameraPath& path) {
    onlyKnownFields(key, at, {"time", "camera", "light"});
    if (const auto camera = key.find("camera"); camera != key.end()) {
        const std::string field = at + ".camera";
        onlyKnownFields(*camera, field, {"position", "target", "azimuth", "elevation", "distance"});
        const bool lookAt = camera->contains("position");
        const bool orbit = camera->contains("azimuth") || camera->contains("elevation") || camera->contains("distance");
        if (lookAt && orbit) fail(field, "give either position or azimuth/elevation/distance (an orbit), not both");
        if (!lookAt && !orbit && !camera->contains("target")) fail(field, "sets nothing (position, target or orbit angles)");
        const auto form = lookAt ? CameraPath::CameraForm::LookAt : orbit ? CameraPath::CameraForm::Orbit : path.cameraForm;
        if (lookAt || orbit) {
            if (path.cameraForm != CameraPath::CameraForm::None && path.cameraForm != form)
                fail(field, "one path moves its camera one way: by position or by orbit angles in every keyframe");
            path.cameraForm = form;
        }
        if (lookAt) addKey(path.cameraPosition, 3, time, vector3((*camera)["position"], field + ".position"));
        if (orbit) {
            for (const char* name : {"azimuth", "elevation", "distance"})
                if (!camera->contains(name)) fail(field, std::string("an orbit keyframe needs azimuth, elevation and distance (") + name + " is missing)");
            const double azimuth = finiteNumber((*camera)["azimuth"], field + ".azimuth", -36000, 36000);
            const double elevation = finiteNumber((*camera)["elevation"], field + ".elevation", -89.9, 89.9);
            const double distance = finiteNumber((*camera)["distance"], field + ".distance", 1e-4, kMaxWorldCoordinate);
            addKey(path.cameraOrbit, 3, time, {azimuth, elevation, distance});
        }
        if (camera->contains("target")) addKey(path.cameraTarget, 3, time, vector3((*camera)["target"], field + ".target"));
        // A keyframe that gives both is checked here, as a scene's camera is (the frames between,
        // and keyframes that leave the target to the scene, by pathProblem).
        if (lookAt && camera->contains("target"))
            if (const std::string problem = cameraProblem(path.cameraPosition.values.back(), path.cameraTarget.values.back());
                !problem.empty())
                fail(field, problem);
    }
    if (const auto light = key.find("light"); light != key.end()) {
        const std::string field = at + ".light";
        onlyKnownFields(*light, field, {"direction", "elevation", "azimuth", "position", "size"});
        const bool direction = light->contains("direction"), position = light->contains("position");
        const bool angles = light->contains("elevation") || light->contains("azimuth");
        if (int(direction) + int(position) + int(angles) > 1)
            fail(field, "give one of direction, elevation/azimuth or position");
        if (!direction && !position && !angles && !light->contains("size")) fail(field, "sets nothing (direction, elevation/azimuth, position or size)");
        const auto form = direction ? CameraPath::LightForm::Direction
                          : angles  ? CameraPath::LightForm::Angles
                          : position ? CameraPath::LightForm::Position
                                     : CameraPath::LightForm::None;
        if (form != CameraPath::LightForm::None) {
            if (path.lightForm != CameraPath::LightForm::None && path.lightForm != form)
                fail(field, "one path moves its light one way: by direction, by elevation/azimuth or by position in every keyframe");
            path.lightForm = form;
        }
        if (direction) {
            const glm::dvec3 d = vector3((*light)["direction"], field + ".direction");
            if (const std::string problem = directionProblem(d); !problem.empty()) fail(field + ".direction", problem);
            addKey(path.light, 3, time, glm::normalize(d));
        }
        if (angles) {
            if (!light->contains("elevation") || !light->contains("azimuth")) fail(field, "give both elevation and azimuth");
            // The scene reader's range: a light at or below the horizon lights nothing.
            const double elevation = finiteNumber((*light)["elevation"], field + ".elevation", 0.01, 90);
            const double azimuth = finiteNumber((*light)["azimuth"], field + ".azimuth", -36000, 36000);
            addKey(path.light, 2, time, {elevation, azimuth, 0.0});
        }
        if (position) addKey(path.light, 3, time, vector3((*light)["position"], field + ".position"));
        if (light->contains("size"))
            addKey(path.lightSize, 1, time, {finiteNumber((*light)["size"], field + ".size", 0, kMaxWorldCoordinate), 0, 0});
    }
}

} // namespace

double CameraPath::frameTime(int frame) const {
    if (frames <= 1) return startTime;
    return startTime + (endTime - startTime) * double(frame) / double(frames - 1);
}

PathState samplePath(const CameraPath& path, double time) {
    PathState state;
    auto sample = [&](const PathChannel& c) { return sampleChannel(c, time, path.interpolation); };
    if (path.cameraTarget.animated()) state.cameraTarget = glm::vec3(sample(path.cameraTarget));
    if (path.cameraForm == CameraPath::CameraForm::LookAt && path.cameraPosition.animated())
        state.cameraPosition = glm::vec3(sample(path.cameraPosition));
    if (path.cameraForm == CameraPath::CameraForm::Orbit && path.cameraOrbit.animated())
        state.cameraOrbit = glm::vec3(sample(path.cameraOrbit));
    if (path.light.animated()) {
        const glm::dvec3 v = sample(path.light);
        switch (path.lightForm) {
        case CameraPath::LightForm::Direction: state.lightDirection = glm::vec3(glm::normalize(v)); break;
        case CameraPath::LightForm::Angles: state.lightDirection = glm::vec3(-towardsFromAngles(v.y, v.x)); break;
        case CameraPath::LightForm::Position: state.lightPosition = glm::vec3(v); break;
        case CameraPath::LightForm::None: break;
        }
    }
    if (path.lightSize.animated()) state.lightSize = float(std::max(sample(path.lightSize).x, 0.0));
    return state;
}

bool parsePath(const json& node, const std::string& source, CameraPath& path, std::string& error) {
    path = {};
    path.source = source;
    try {
        onlyKnownFields(node, "", {"name", "frames", "interpolation", "keyframes"});
        if (node.contains("name")) {
            if (!node["name"].is_string() || node["name"].get<std::string>().size() > 100) fail("name", "expected a string of up to 100 characters");
            path.name = node["name"].get<std::string>();
        }
        if (node.contains("interpolation")) {
            const json& value = node["interpolation"];
            const std::string text = value.is_string() ? value.get<std::string>() : "";
            if (text == "linear") path.interpolation = PathInterpolation::Linear;
            else if (text == "smooth") path.interpolation = PathInterpolation::Smooth;
            else fail("interpolation", "expected \"linear\" or \"smooth\"");
        }
        if (!node.contains("keyframes")) fail("keyframes", "missing (a path needs at least one keyframe)");
        const json& keys = node["keyframes"];
        if (!keys.is_array() || keys.empty() || keys.size() > kMaxKeyframes)
            fail("keyframes", "expected an array of 1 to " + std::to_string(kMaxKeyframes) + " keyframes");
        double last = -1e300;
        for (size_t i = 0; i < keys.size(); ++i) {
            const std::string at = "keyframes[" + std::to_string(i) + "]";
            if (!keys[i].is_object()) fail(at, "expected an object");
            if (!keys[i].contains("time")) fail(at + ".time", "missing (seconds)");
            const double time = finiteNumber(keys[i]["time"], at + ".time", -1e6, 1e6);
            if (i > 0 && !(time > last)) fail(at + ".time", "times must increase (" + formatNumber(time) + " after " + formatNumber(last) + ")");
            last = time;
            parseKeyframe(keys[i], at, time, path);
        }
        path.startTime = keys.front()["time"].get<double>();
        path.endTime = last;
        if (node.contains("frames")) {
            const json& value = node["frames"];
            if (!value.is_number_integer() || value.get<long long>() < 1 || value.get<long long>() > kMaxPathFrames)
                fail("frames", "expected a whole number from 1 to " + std::to_string(kMaxPathFrames));
            path.frames = int(value.get<long long>());
        } else {
            // 60 frames a second of the path, at least two.
            const double frames = std::round(60.0 * (path.endTime - path.startTime)) + 1.0;
            if (frames > kMaxPathFrames) fail("frames", "the keyframes span more than " + std::to_string(kMaxPathFrames / 60) + " s at 60 frames a second; give frames");
            path.frames = std::max(2, int(frames));
        }
    } catch (const PathProblem& problem) {
        error = source + (problem.field.empty() ? "" : ": " + problem.field) + ": " + problem.what;
        return false;
    }
    return true;
}

bool loadPathFile(const std::string& file, CameraPath& path, std::string& error) {
    json node;
    if (!readJsonFile(file, node, error, "path file")) return false;
    if (!parsePath(node, file, path, error)) return false;
    if (path.name.empty()) path.name = std::filesystem::path(file).stem().string();
    return true;
}

std::string pathProblem(const CameraPath& path, const std::string& sceneName, const SceneCamera& camera,
                        const LightInfo& light) {
    const LightType type = light.type;
    const std::string who = path.source + ": ";
    if (path.lightForm == CameraPath::LightForm::Position && type == LightType::Directional)
        return who + "moves the light by position, but scene '" + sceneName + "' has a directional light (give direction or elevation/azimuth)";
    if ((path.lightForm == CameraPath::LightForm::Direction || path.lightForm == CameraPath::LightForm::Angles) && type == LightType::Point)
        return who + "turns the light, but scene '" + sceneName + "' has a point light (give position)";
    for (size_t i = 0; i < path.lightSize.values.size(); ++i)
        if (const std::string problem = lightSizeProblem(type, path.lightSize.values[i].x); !problem.empty())
            return who + "light size at time " + formatNumber(path.lightSize.times[i]) + ": " + problem;
    // Every frame as it will be drawn: a keyframe may leave the target to the scene, and
    // interpolation may bring the eye onto the target or turn the light through zero (between
    // opposite directions), which no keyframe shows. At most 100,000 samples, each a few
    // binary searches: milliseconds.
    for (int frame = 0; frame < path.frames; ++frame) {
        SceneCamera c = camera;
        LightInfo l = light;
        const PathState state = samplePath(path, path.frameTime(frame));
        applyPathState(state, c, l);
        const std::string at = who + "frame " + std::to_string(frame) + " (time " + formatNumber(path.frameTime(frame)) + "): ";
        if (const std::string problem = cameraProblem(c.position, c.target, glm::dvec3(c.up)); !problem.empty())
            return at + problem;
        if (state.lightDirection) {
            const glm::dvec3 direction(*state.lightDirection);
            if (!(std::abs(glm::length(direction) - 1.0) < 1e-3))
                return at + "the light's direction passes through zero between keyframes (opposite directions; add a keyframe between them)";
        }
    }
    return "";
}

std::string pathSceneProblem(const CameraPath& path, const Scene& scene) {
    return pathProblem(path, scene.name, scene.camera, scene.light);
}

void applyPathState(const PathState& state, SceneCamera& camera, LightInfo& light) {
    if (state.cameraPosition) camera.position = *state.cameraPosition;
    if (state.cameraTarget) camera.target = *state.cameraTarget;
    if (state.cameraOrbit)
        camera.position = camera.target + glm::vec3(double((*state.cameraOrbit).z) *
                                                    towardsFromAngles((*state.cameraOrbit).x, (*state.cameraOrbit).y));
    if (state.lightDirection) light.direction = *state.lightDirection;
    if (state.lightPosition) light.position = *state.lightPosition;
    if (state.lightSize) light.size = light.type == LightType::Directional ? float(*state.lightSize * kDegrees) : *state.lightSize;
}

const std::vector<std::string>& builtinPathNames() {
    static const std::vector<std::string> names = {"orbit", "dolly", "sweep", "walk", "static"};
    return names;
}

bool builtinPath(const std::string& name, const Scene& scene, const BuiltinPathOptions& options, CameraPath& path,
                 std::string& error) {
    path = {};
    path.name = name;
    path.source = "builtin path '" + name + "'";
    const SceneCamera& camera = options.camera ? *options.camera : scene.camera;
    const LightInfo& sceneLight = options.light ? *options.light : scene.light;
    const glm::dvec3 eye = camera.position, target = camera.target;
    auto lookAtKey = [&](double time, glm::dvec3 position, glm::dvec3 at) {
        path.cameraForm = CameraPath::CameraForm::LookAt;
        addKey(path.cameraPosition, 3, time, position);
        addKey(path.cameraTarget, 3, time, at);
    };
    const Bounds all = scene.worldBounds();
    const double sceneSize = std::max(double(glm::length(all.max - all.min)), 1e-3);
    if (name == "orbit") {
        // A slow orbit: 0.5 degrees a frame about the vertical through the target.
        path.frames = options.frames > 0 ? options.frames : 120;
        const glm::dvec3 offset = eye - target;
        const double distance = glm::length(offset);
        const double elevation = std::asin(std::clamp(offset.y / std::max(distance, 1e-9), -1.0, 1.0)) / kDegrees;
        const double azimuth = std::atan2(offset.z, offset.x) / kDegrees;
        const double seconds = double(path.frames - 1) / 60.0;
        path.cameraForm = CameraPath::CameraForm::Orbit;
        addKey(path.cameraOrbit, 3, 0.0, {azimuth, elevation, distance});
        addKey(path.cameraOrbit, 3, seconds, {azimuth + 0.5 * (path.frames - 1), elevation, distance});
        addKey(path.cameraTarget, 3, 0.0, target);
    } else if (name == "dolly") {
        // Sideways in the view's plane by a fraction of a texel per frame (the map's crop, or the
        // scene fit's texel, moves by that fraction: unsnapped edges crawl).
        path.frames = options.frames > 0 ? options.frames : 60;
        const double texel = options.texelWorldSize > 0.0 ? options.texelWorldSize : sceneSize / 2048.0;
        const glm::dvec3 view = glm::normalize(target - eye);
        glm::dvec3 right = glm::cross(view, glm::dvec3(0, 1, 0));
        if (glm::length(right) < 1e-6) right = glm::dvec3(1, 0, 0);
        right = glm::normalize(right);
        const glm::dvec3 move = right * texel * options.texelsPerFrame * double(path.frames - 1);
        const double seconds = double(path.frames - 1) / 60.0;
        lookAtKey(0.0, eye, target);
        lookAtKey(seconds, eye + move, target + move);
    } else if (name == "sweep") {
        if (sceneLight.type == LightType::Point) {
            error = "builtin path 'sweep' turns the light; scene '" + scene.name + "' has a point light";
            return false;
        }
        path.frames = options.frames > 0 ? options.frames : 120;
        const glm::dvec3 towards = -glm::dvec3(sceneLight.direction);
        const double azimuth = std::atan2(towards.z, towards.x) / kDegrees;
        const double seconds = double(path.frames - 1) / 60.0;
        path.lightForm = CameraPath::LightForm::Angles;
        addKey(path.light, 2, 0.0, {90.0, azimuth, 0.0});
        addKey(path.light, 2, seconds, {2.0, azimuth, 0.0});
    } else if (name == "walk") {
        // The ground under the walker: the largest object's mesh, sampled by a vertical ray.
        path.frames = options.frames > 0 ? options.frames : 240;
        const SceneObject* ground = nullptr;
        double largest = -1.0;
        for (size_t i = 0; i < scene.objects.size(); ++i) {
            const Bounds& b = scene.objectInfo.size() == scene.objects.size() ? scene.objectInfo[i].bounds : all;
            const double area = double(b.max.x - b.min.x) * double(b.max.z - b.min.z);
            if (area > largest) largest = area, ground = &scene.objects[i];
        }
        auto heightAt = [&](double x, double z) {
            double best = -1e300;
            if (!ground) return 0.0;
            const Mesh& mesh = scene.meshes[ground->mesh];
            for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
                glm::dvec3 p[3];
                for (int k = 0; k < 3; ++k)
                    p[k] = glm::dvec3(ground->transform * glm::vec4(mesh.vertices[mesh.indices[t + size_t(k)]].position, 1.0f));
                // Barycentric coordinates of (x, z) in the triangle's xz projection.
                const double d = (p[1].z - p[2].z) * (p[0].x - p[2].x) + (p[2].x - p[1].x) * (p[0].z - p[2].z);
                if (std::abs(d) < 1e-12) continue;
                const double a = ((p[1].z - p[2].z) * (x - p[2].x) + (p[2].x - p[1].x) * (z - p[2].z)) / d;
                const double b = ((p[2].z - p[0].z) * (x - p[2].x) + (p[0].x - p[2].x) * (z - p[2].z)) / d;
                if (a < -1e-9 || b < -1e-9 || a + b > 1.0 + 1e-9) continue;
                best = std::max(best, a * p[0].y + b * p[1].y + (1.0 - a - b) * p[2].y);
            }
            return best > -1e300 ? best : double(all.min.y);
        };
        glm::dvec3 heading = target - eye;
        heading.y = 0.0;
        heading = glm::length(heading) > 1e-9 ? glm::normalize(heading) : glm::dvec3(0, 0, -1);
        const double speed = 1.4 / 60.0, eyeHeight = 1.7;
        const int keys = std::min(path.frames, 9);
        for (int k = 0; k < keys; ++k) {
            const double frame = keys > 1 ? double(k) * double(path.frames - 1) / double(keys - 1) : 0.0;
            glm::dvec3 at = glm::dvec3(target.x, 0.0, target.z) + heading * speed * frame;
            at.y = heightAt(at.x, at.z) + eyeHeight;
            glm::dvec3 ahead = at + heading * 10.0;
            ahead.y = at.y - 0.5;
            lookAtKey(frame / 60.0, at, ahead);
        }
        path.interpolation = PathInterpolation::Smooth;
    } else if (name == "static") {
        path.frames = options.frames > 0 ? options.frames : 16;
        lookAtKey(0.0, eye, target);
        lookAtKey(double(path.frames - 1) / 60.0, eye, target);
    } else {
        std::string names;
        for (const std::string& known : builtinPathNames()) appendListItem(names, known);
        error = "no built-in path '" + name + "' (built-in: " + names + ")";
        return false;
    }
    path.startTime = 0.0;
    path.endTime = double(path.frames - 1) / 60.0;
    return true;
}

bool resolvePath(const std::string& text, const Scene& scene, const BuiltinPathOptions& options, CameraPath& path,
                 std::string& error) {
    std::error_code ignored;
    const bool looksLikeFile = text.find('/') != std::string::npos || text.ends_with(".json") || std::filesystem::exists(text, ignored);
    if (looksLikeFile) {
        if (!loadPathFile(text, path, error)) {
            if (error.rfind(text, 0) != 0) error = "--path " + text + ": " + error;
            return false;
        }
    } else {
        const auto own = std::find_if(scene.paths.begin(), scene.paths.end(), [&](const CameraPath& p) { return p.name == text; });
        if (own != scene.paths.end()) {
            path = *own;
        } else if (std::find(builtinPathNames().begin(), builtinPathNames().end(), text) != builtinPathNames().end()) {
            if (!builtinPath(text, scene, options, path, error)) return false;
        } else {
            std::string names;
            for (const CameraPath& p : scene.paths) appendListItem(names, p.name);
            for (const std::string& known : builtinPathNames()) appendListItem(names, known);
            error = "--path '" + text + "': not a file, nor a path of scene '" + scene.name + "' or a built-in path (" + names + ")";
            return false;
        }
    }
    if (options.frames > 0 && path.frames != options.frames) path.frames = options.frames;
    if (const std::string problem = pathSceneProblem(path, scene); !problem.empty()) {
        error = problem;
        return false;
    }
    return true;
}

} // namespace shadowlab
