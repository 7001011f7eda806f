// Camera and light paths as data (issue 12): a list of keyframes, each setting any of the camera
// (position and target, or orbit angles around a target), the light (direction, elevation and
// azimuth, or position) and the light's size at a time, interpolated in between. Read from a JSON
// file (`--path FILE`), from a scene's "paths" object, or built in per scene (builtinPath). No GL:
// the fuzzing harness compiles this file. The format: docs/stability.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "shadowlab/technique.h"

namespace shadowlab {
// The scene file's camera (scene.h includes this header, so it is declared here).
struct SceneCamera {
    glm::vec3 position{0.0f, 3.0f, 6.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 0.7854f;                      // radians
    float nearPlane = 0.1f;
    float farPlane = 100.0f;
};
} // namespace shadowlab

namespace shadowlab {

struct Scene;

enum class PathInterpolation { Linear, Smooth };   // Smooth: Catmull-Rom through the keyframes

// One animated quantity: values (1 to 3 numbers, by `width`) at increasing times.
struct PathChannel {
    int width = 0;                      // 0: the path does not animate it
    std::vector<double> times;
    std::vector<glm::dvec3> values;
    bool animated() const { return width > 0 && !times.empty(); }
};

struct CameraPath {
    std::string name;
    std::string source;                 // the file or "builtin:<name>", "<scene>: paths.<name>", for messages
    int frames = 0;                     // frames rendered, evenly spaced from the first time to the last
    PathInterpolation interpolation = PathInterpolation::Linear;
    // Camera: position + target, or orbit = (azimuth, elevation, distance) in degrees around target.
    enum class CameraForm { None, LookAt, Orbit } cameraForm = CameraForm::None;
    PathChannel cameraPosition;         // LookAt: the eye
    PathChannel cameraOrbit;            // Orbit: azimuth, elevation (degrees), distance
    PathChannel cameraTarget;
    // Light: a direction it travels along (unit after interpolation), (elevation, azimuth) in
    // degrees, or a position (spot and point lights).
    enum class LightForm { None, Direction, Angles, Position } lightForm = LightForm::None;
    PathChannel light;
    PathChannel lightSize;              // degrees for directional lights, world units otherwise
    double startTime = 0.0, endTime = 0.0;

    double frameTime(int frame) const;
};

// What a path sets at one time; unset members leave the scene's value.
struct PathState {
    std::optional<glm::vec3> cameraPosition, cameraTarget;
    std::optional<glm::vec3> cameraOrbit;      // azimuth, elevation (degrees), distance around the target
    std::optional<glm::vec3> lightDirection;   // unit, the light's travel direction
    std::optional<glm::vec3> lightPosition;
    std::optional<float> lightSize;            // degrees for directional lights, world units otherwise
};

PathState samplePath(const CameraPath& path, double time);

// Parses a path object; false with an error that starts with `source` and names the field.
bool parsePath(const nlohmann::json& node, const std::string& source, CameraPath& path, std::string& error);
// The file (a regular file, at most 16 MiB of JSON) into `path`.
bool loadPathFile(const std::string& file, CameraPath& path, std::string& error);
// "" when `path` can drive a scene's light (a position needs a spot or point light, a direction
// or angles a directional or spot light; sizes in range) and every one of its frames, started
// from `camera` and `light`, gives a usable camera and light direction (scene.h's cameraProblem
// and directionProblem: the checks a scene's or a tour step's camera gets), else the problem
// naming the path and the frame.
std::string pathProblem(const CameraPath& path, const std::string& sceneName, const SceneCamera& camera,
                        const LightInfo& light);
// pathProblem from the scene's own camera and light.
std::string pathSceneProblem(const CameraPath& path, const Scene& scene);

// Built-in paths, made from the scene's camera and light:
//   orbit   the camera around its target at its distance and height, 0.5 degrees a frame
//   dolly   camera and target sideways (along the view's right) by texelsPerFrame shadow-map
//           texels of texelWorldSize each per frame: sub-texel motion, the shimmer case
//   sweep   the light from the zenith to 2 degrees of elevation at the scene's azimuth
//   walk    the eye 1.7 above the largest object (the ground, the forest's hills) walking at
//           1.4 m/s along the view direction from the camera's target
//   static  the scene's camera and light held (temporal noise of stochastic techniques)
struct BuiltinPathOptions {
    int frames = 0;                     // 0: each path's default
    double texelWorldSize = 0.0;        // dolly: world size of one shadow-map texel (0: 1/2048 of the scene)
    double texelsPerFrame = 0.25;
    // Start from this view and light instead of the scene's (a stress case's overrides).
    std::optional<SceneCamera> camera;
    std::optional<LightInfo> light;
};
const std::vector<std::string>& builtinPathNames();
bool builtinPath(const std::string& name, const Scene& scene, const BuiltinPathOptions& options, CameraPath& path,
                 std::string& error);

// `--path TEXT`: a file when TEXT names one (or ends in .json or holds a '/'), else a path of the
// scene's "paths", else a built-in path. Errors name the option and what was looked for.
bool resolvePath(const std::string& text, const Scene& scene, const BuiltinPathOptions& options, CameraPath& path,
                 std::string& error);

// Applies a sampled state to a camera (keeping its field of view and planes) and a light.
void applyPathState(const PathState& state, SceneCamera& camera, LightInfo& light);

} // namespace shadowlab
