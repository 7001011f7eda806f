// Guided tours and saved sessions (issue 14): a tour is a JSON file (assets/tours/<name>.json)
// holding a list of steps; a step is one prepared moment of a lesson: a scene with its
// parameters, the technique (and optionally a second one to compare with), parameter values,
// camera, light, the view and a caption. A saved session is one step with the same schema, so a
// moment saved in class can be pasted into a tour as it is. No GL here: a tour is read and
// checked whole (techniques from their descriptors, scenes with checkScene) before the first
// frame, which is also what the fuzzer drives (tests/fuzz). The format: docs/classroom.md.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "plugin/params.h"
#include "ui/classroom.h"
#include "ui/tour_expect.h"

namespace shadowlab {

struct TourCamera {
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
    float fovDegrees = 45.0f;      // vertical
};

struct TourLight {
    std::optional<glm::vec3> direction;   // travel direction (as --light-dir)
    std::optional<double> size;           // degrees for directional lights, world units otherwise (as --light-size)
};

struct TourStep {
    std::string title;
    std::string scene;                                        // built-in name or path (relative to the tour file)
    std::vector<std::pair<std::string, double>> sceneParameters;
    std::string technique;
    std::string compare;                                      // "": one technique
    CompareLayout layout = CompareLayout::SideBySide;
    float wipe = 0.5f;
    // "param" (of `technique`) or "technique.param" = value text, as --set takes them; checked
    // against the descriptors (name, type, range). Parameters not named keep their defaults.
    std::vector<std::pair<std::string, std::string>> parameters;
    std::optional<TourCamera> camera;                         // none: the scene's camera
    TourLight light;                                          // fields not given: the scene's light
    std::string view = "lit";                                 // lit | visibility | error | footprint | texel-grid | coverage | a debug image's name
    // A camera and light path the step plays (issue 12's paths, scene/camera_path.h): a built-in
    // path (orbit, dolly, sweep, walk, static), one of the scene's "paths", or a JSON file
    // (relative to the tour file). It starts from the step's camera and light; the window loops
    // it (restarting the step starts it again), `tour --out` draws its first, middle and last frame.
    std::string path;                                         // "": no path
    int pathFrames = 0;                                       // 0: the path's own number of frames
    std::string caption;
    // What the caption claims, checked by `shadowlab tour` after measuring (ui/tour_expect.h).
    std::vector<TourExpectation> expect;
};

struct Tour {
    std::string source;            // the file, for messages
    std::string title;
    std::string description;
    std::vector<TourStep> steps;
};

constexpr size_t kMaxTourSteps = 200;
constexpr size_t kMaxCaptionBytes = 4000;

// One step from JSON: types and shapes only (`where` starts every message: "tour.json: steps[2]").
// Scene paths that are relative resolve against `baseDir`.
bool parseTourStep(const nlohmann::json& json, const std::string& where, const std::filesystem::path& baseDir,
                   TourStep& step, std::string& error);
// The JSON of a step, the inverse of parseTourStep (a saved session; numbers round-trip exactly).
nlohmann::json tourStepJson(const TourStep& step);
// A whole tour file: {"title", "description", "steps": [...]} (at least one step).
bool parseTour(const nlohmann::json& json, const std::string& source, const std::filesystem::path& baseDir, Tour& tour,
               std::string& error);

// Everything a step will use, checked before the first frame: technique ids, every parameter's
// name, type and range (for the technique, or the one its key names), the scene and its
// parameters (checkScene, no meshes made), the light's size for the scene's light, a finite
// camera and light. The first problem, prefixed with `where`.
bool checkTourStep(const TourStep& step, const std::string& where, const std::vector<TechniqueInfo>& techniques,
                   std::string& error);
bool checkTour(const Tour& tour, const std::vector<TechniqueInfo>& techniques, std::string& error);

// The built-in tours: the names of assets/tours/*.json.
std::filesystem::path builtinTourDir();
std::vector<std::string> builtinTourNames();
// Reads and checks a tour: a built-in name, or a path to a JSON file. Errors name the file.
bool loadTour(const std::string& nameOrPath, const std::vector<TechniqueInfo>& techniques, Tour& tour, std::string& error);
// A session file: one step object (a tour's step), read and checked like a tour's (with the same
// JSON reader, so a duplicate key is an error too); the window then checks its view as a tour's
// (checkStepView). parseSessionText is the same for text in memory (the fuzzer's entry).
bool loadSession(const std::filesystem::path& file, const std::vector<TechniqueInfo>& techniques, TourStep& step,
                 std::string& error);
bool parseSessionText(const std::string& text, const std::string& source, const std::filesystem::path& baseDir,
                      const std::vector<TechniqueInfo>& techniques, TourStep& step, std::string& error);

// "sessions/<scene>-<technique>-YYYYMMDD-HHMMSS.json" under `folder`, never an existing name.
std::filesystem::path uniqueSessionPath(const std::filesystem::path& folder, const std::string& scene,
                                        const std::string& technique, std::chrono::system_clock::time_point when);

} // namespace shadowlab
