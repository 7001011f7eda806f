// Benchmark specs: what a sweep measures, read from the command line or a JSON file, and checked
// as a whole before the first frame, so that a bad value in the last row fails at once instead of
// after an hour of measuring. No GL here: the checks need only technique descriptors and scenes
// (checkScene), which is also what the fuzzer (tests/fuzz) drives.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "plugin/host_params.h"
#include "plugin/params.h"

namespace shadowlab {

struct BenchSpec {
    std::string tag;                         // copied into every row as "spec" (which sweep it came from)
    std::vector<std::string> techniques;     // empty: every technique except the reference
    std::vector<std::string> scenes{"cube"};
    std::vector<glm::ivec2> sizes{{1280, 720}};
    // Lists to permute. Keys: a technique parameter ("resolution", or "pcf.kernel" for one
    // technique), a scene parameter ("scene.count"), the light size ("light.size"), or the host's
    // depth pre-pass ("host.depth_prepass": auto, on or off; 0 and 1 as off and on) or another host
    // parameter ("host.shadow_blur", plugin/host_params.h).
    std::map<std::string, std::vector<std::string>> sweeps;
    std::vector<std::string> base;           // key=value set before every combination
    int warmupFrames = 20;
    int frames = 200;
    // Stop a row's timing before `frames` once its GPU frame median is known to within this
    // fraction (util/stats.h TimingStop, "stableWithin"); 0: time every frame. minFrames at least.
    double stableWithin = 0.0;
    int minFrames = 10;
    bool minFramesGiven = false;             // minFrames without stableWithin means nothing: refused
    bool accuracy = false;
    std::string reference = "auto";          // hard | soft | both | auto
    // Soft reference: N rays per pixel, sampled adaptively (ReferenceOptions::adaptive: a first
    // batch of 32 everywhere, all N where the batch disagrees nearby). 1024 adaptive keeps the
    // reference's own penumbra error (its floor) at 0.0012 to 0.0017 on contact and dragon-like
    // (0.009 to 0.012 at 64 uniform rays) for 0.8x to 1.4x the CPU time of 64 uniform rays
    // (docs/benchmarks.md, "The soft reference's own error and adaptive sampling").
    int referenceSamples = 1024;
    bool referenceAdaptive = true;
    bool depthFloor = false;                 // add "depth-floor" rows (bare depth pass per resolution)
    bool contactBand = false;                // hard_contact_* columns (one more shadow ray a pixel)
    // "sweptOnly": leave out the techniques that declare none of the swept technique parameters
    // (`none`, the main-pass floor, stays): a group that extends another group's sweep (more
    // resolutions) without measuring its other techniques again.
    bool sweptOnly = false;
    // A row's evaluation beside the next row's timed frames (bench.cpp, PendingEvaluation); not
    // a spec key: --overlap-accuracy off of bench and report, to compare timings without it.
    bool overlapAccuracy = true;
    // "path": every frame of a camera and light path timed per technique, scene and combination of
    // the technique parameters swept (the rows of `bench --path`, tagged); "pathFrames": 0 is the
    // path's own count. One size, no scene, light or host sweeps; accuracy (the temporal metrics)
    // with the hard or soft reference.
    std::string path;
    int pathFrames = 0;
    bool fromCommandLine = false;            // errors name options (--sweep) rather than fields (sweep)
    // The file it was read from ("spec.json", or "spec.json: spec 2" in an array): checkBenchSpec's
    // errors start with it, so a bad technique in a file does not read like a command-line error.
    std::string source;
};

constexpr int kMaxBenchFrames = 100000;
constexpr int kMinStableFrames = 6;          // fewer: the median's confidence ranks leave the set
constexpr double kMaxStableWithin = 0.5;
constexpr int kMaxReferenceSamples = 4096;
constexpr int kMinRenderSize = 16;
constexpr int kMaxRenderSize = 16384;

// "WIDTHxHEIGHT", both 16 to 16384 and nothing else ("64x64junk" is an error).
bool parseSize(const std::string& text, glm::ivec2& size, std::string& error, const std::string& option = "--size");
// A finite number and nothing else ("5abc", "nan" and "1e400" are errors).
std::optional<double> parseNumberText(const std::string& text);

// A spec value as a setting's text: strings as they are, numbers and the rest as JSON.
std::string specValueText(const nlohmann::json& value);

// "on" or "off" (also true/false, 1/0) for `option`; otherwise false and "OPTION 'TEXT': expected on or off".
bool parseOnOff(const std::string& text, bool& value, std::string& error, const std::string& option);

// "--sweep resolution=512,1024,2048" into spec.sweeps.
bool addSweep(BenchSpec& spec, const std::string& text, std::string& error);
// A spec from JSON: {"techniques": [...], "scenes": [...], "sizes": ["1280x720"], "frames": 200,
// "warmup": 20, "base": {"key": value}, "sweep": {"key": [values]}, "accuracy": true, ...}.
// Types and ranges are checked here; names and values against techniques and scenes by checkBenchSpec.
bool parseBenchSpec(const nlohmann::json& json, BenchSpec& spec, std::string& error);
// A spec file holding one spec object or an array of them (run one after the other).
bool loadBenchSpecs(const std::filesystem::path& file, std::vector<BenchSpec>& specs, std::string& error);

// Everything a sweep would use, checked before it runs: technique ids; every sweep and base key
// means something; every value parses as the parameter of each technique that declares it; scene
// parameters are numbers; light sizes are in range for each scene's light; every scene loads with
// every combination of its swept parameters (checkScene: fields and budget, no meshes made);
// reference mode, samples, frames. `lightSize` is a --light-size given for every scene.
// The first problem, naming the option or field and the value.
bool checkBenchSpec(const BenchSpec& spec, const std::vector<TechniqueInfo>& techniques, std::string& error,
                    std::optional<double> lightSize = std::nullopt);

// Shared by the check and the run.
inline bool isSceneKey(const std::string& key) { return key.rfind("scene.", 0) == 0; }
inline bool isLightKey(const std::string& key) { return key == "light.size"; }
// The host's depth pre-pass, or one of its parameters (plugin/host_params.h: host.shadow_blur, ...).
inline bool isHostKey(const std::string& key) {
    return key.rfind("host.", 0) == 0 && hostParams().findParam(key.substr(5));
}
// The parameter id `key` names for `info`: "resolution" if it declares it, "pcf.kernel" for pcf; "" if none.
std::string benchParamFor(const TechniqueInfo& info, const std::string& key);
using BenchSetting = std::pair<std::string, std::string>;
using BenchSettingLists = std::vector<std::pair<std::string, std::vector<std::string>>>;
std::vector<std::vector<BenchSetting>> benchCombinations(const BenchSettingLists& lists);
// The techniques a spec measures (all but the reference when it names none); nullopt and an
// error for an unknown id.
std::optional<std::vector<const TechniqueInfo*>> benchTechniques(const BenchSpec& spec,
                                                                 const std::vector<TechniqueInfo>& techniques,
                                                                 std::string& error);

} // namespace shadowlab
