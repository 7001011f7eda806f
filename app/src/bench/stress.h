// The failure suite (`shadowlab stress`, issue 12): named cases where shadow techniques are known
// to fail, each a scene with a view or a path, the metric that shows the failure, a threshold and
// the literature's claim, run for every technique into a table (technique x case: number and
// verdict), a chart and the worst frame of each cell. Cases are data: assets/stress/cases.json
// (docs/stability.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "groundtruth/groundtruth.h"
#include "plugin/params.h"
#include "scene/camera_path.h"

namespace shadowlab {

class App;

// ContactFalseLight: the false-light rate in the contact band (groundtruth/contact_band.h; hard
// reference), where maps leak at a caster's foot and contact shadows should close the gap.
enum class StressMetric { FalseShadow, FalseLight, Mae, MaeNearThird, MaeFarThird, Flicker, Popping, Noise, ContactFalseLight };

struct StressCase {
    std::string id, title;
    std::string scene;                       // built-in name, or a file relative to the cases file
    std::optional<std::string> requires_;    // a file that must exist (a shared test model), else skipped
    // View overrides of the scene's camera: position, target, near, far.
    std::optional<glm::vec3> cameraPosition, cameraTarget;
    std::optional<float> cameraNear, cameraFar;
    // Light overrides: elevation and azimuth in degrees (directional), size in degrees.
    std::optional<glm::vec2> lightAngles;
    std::optional<float> lightSize;
    std::string path;                        // a built-in path name, "" for one still frame
    int frames = 1;
    double texelsPerFrame = 0.25;            // dolly
    std::vector<std::string> sets;           // key=value, applied to techniques that declare key
    ReferenceOptions::Mode reference = ReferenceOptions::Mode::Hard;
    int referenceSamples = 64;
    // Pixels counted: all compared ones, those within `regionRadius` of `regionCentre`, or those on
    // the object named `regionObject` (its world bounds, the bottom 2% of its height left out).
    std::optional<glm::vec3> regionCentre;
    float regionRadius = 0.0f;
    std::string regionObject;
    StressMetric metric = StressMetric::Mae;
    double threshold = 0.0;                  // pass: value <= threshold
    std::vector<std::string> expectedToFail; // technique ids the claim says fail here
    std::vector<std::string> expectedToPass; // technique ids the claim says do better (must pass)
    std::string claim, source;
    bool footprint = false;                  // the page shows the texel footprint m beside the cell
};

struct StressSuite {
    std::string file;
    glm::ivec2 size{160, 120};
    std::vector<StressCase> cases;
};

// Reads and checks a cases file (every field; an unknown one is an error naming it).
bool parseStressSuite(const nlohmann::json& node, const std::string& source, StressSuite& suite, std::string& error);
bool loadStressSuite(const std::filesystem::path& file, StressSuite& suite, std::string& error);
std::filesystem::path defaultStressCases();
const char* stressMetricName(StressMetric metric);

struct StressCell {
    std::string technique, caseId;
    bool skipped = false;
    std::string skipReason;
    double value = 0.0;
    bool pass = false;
    bool expectedFail = false;               // the literature's claim for this technique
    bool expectedPass = false;               // named by the claim as one that does not fail
    int worstFrame = 0;
    std::string image;                       // worst frame's error image, relative to the output folder
    std::string settings;                    // the parameters it ran with
    // Details beside the cell's metric.
    double mae = 0, falseShadow = 0, falseLight = 0, maeNear = 0, maeFar = 0, flicker = 0, popping = 0, noise = 0;
    double contactFalseLight = 0;
    size_t contactBandPixels = 0;
    size_t pixels = 0;
    // Texel footprint m (texel_footprint.h) over the region's pixels, worst frame: the median over
    // all of them and over the nearest third of the visible depth range (the thirds of maeNear).
    // Only where the technique reported its maps (footprintPixels > 0).
    double footprintMedian = 0, footprintNear = 0;
    size_t footprintPixels = 0;
};

struct StressOptions {
    std::vector<std::string> techniques;     // empty: every technique found
    std::vector<std::string> cases;          // empty: every case
    std::vector<std::string> sets;           // --set, as in bench (technique.key=value or key=value where declared)
    std::filesystem::path outDir;            // empty: no files (tests)
    std::optional<glm::ivec2> size;
    bool quiet = false;
};

// Everything runStress is asked for, checked against the techniques `found` (their descriptors:
// no GL needed, so the command checks it before the context exists): the techniques, the cases
// with their scenes and cameras, and every --set (a key no technique measured declares would be
// dropped unseen). 0, or 2 with `error`; `techniques` and `cases` are what will run.
int checkStressRequest(const std::vector<TechniqueInfo>& found, const StressSuite& suite, const StressOptions& options,
                       std::vector<std::string>& techniques, std::vector<const StressCase*>& cases, std::string& error);

// Runs one case for one technique on `app` (the scene is loaded when it differs). The cell's image
// is written only with options.outDir.
bool runStressCell(App& app, const StressSuite& suite, const StressCase& stressCase, const std::string& technique,
                   const StressOptions& options, StressCell& cell, std::string& error);

// The whole suite: results.json/.csv, README.md with the table, claims and images, a chart.
// Returns the exit code (0, 1 machine, 2 bad input) with `error` set.
int runStress(App& app, const StressSuite& suite, const StressOptions& options, std::vector<StressCell>& cells,
              std::string& error);

} // namespace shadowlab
