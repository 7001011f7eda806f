// Benchmark sweeps: a base configuration plus lists to permute (a test matrix, not loops in
// C++). Every combination of scene, scene parameters, output size, technique and technique
// parameters is measured (warm-up frames, then N timed frames: median, p5, p95 per pass), with
// memory, the technique's own statistics and, optionally, accuracy against the reference.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace shadowlab {

class App;

struct BenchSpec {
    std::string tag;                         // copied into every row as "spec" (which sweep it came from)
    std::vector<std::string> techniques;     // empty: every technique except the reference
    std::vector<std::string> scenes{"cube"};
    std::vector<glm::ivec2> sizes{{1280, 720}};
    // Lists to permute. Keys: a technique parameter ("resolution", or "pcf.kernel" for one
    // technique), a scene parameter ("scene.count"), or the light size ("light.size").
    std::map<std::string, std::vector<std::string>> sweeps;
    std::vector<std::string> base;           // key=value set before every combination
    int warmupFrames = 20;
    int frames = 200;
    bool accuracy = false;
    std::string reference = "auto";          // hard | soft | both | auto
    int referenceSamples = 64;
    bool depthFloor = false;                 // add "depth-floor" rows (bare depth pass per resolution)
};

// "--sweep resolution=512,1024,2048" into spec.sweeps.
bool addSweep(BenchSpec& spec, const std::string& text, std::string& error);
// A spec from JSON: {"techniques": [...], "scenes": [...], "sizes": ["1280x720"], "frames": 200,
// "warmup": 20, "base": {"key": value}, "sweep": {"key": [values]}, "accuracy": true, ...}.
bool parseBenchSpec(const nlohmann::json& json, BenchSpec& spec, std::string& error);
bool loadBenchSpec(const std::filesystem::path& file, BenchSpec& spec, std::string& error);

// Runs the sweep on `app`; every row is a flat JSON object (see docs/benchmarks.md). Rows are
// also passed to `onRow` as they complete (progress output).
bool runBench(App& app, const BenchSpec& spec, std::vector<nlohmann::json>& rows, std::string& error,
              const std::function<void(const nlohmann::json&)>& onRow = {});

// Writes rows as CSV (.csv) or JSON (anything else); CSV columns are the union of row keys.
bool writeBenchResults(const std::filesystem::path& file, const std::vector<nlohmann::json>& rows, std::string& error);

// "resolution=2048 count=400": a row's technique and scene parameters, for tables and logs.
std::string rowSettings(const nlohmann::json& row);
// One aligned line per row on stdout (the header first), as bench and report print progress.
void printBenchHeader();
void printBenchRow(const nlohmann::json& row);

// Machine and build description carried by every row: gpu, driver, backend, date, commit.
nlohmann::json benchEnvironment(App& app);

} // namespace shadowlab
