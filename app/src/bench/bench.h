// Benchmark sweeps: a base configuration plus lists to permute (a test matrix, not loops in
// C++). Every combination of scene, scene parameters, output size, technique and technique
// parameters is measured (warm-up frames, then N timed frames: median, p5, p95 per pass), with
// memory, the technique's own statistics and, optionally, accuracy against the reference.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <functional>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "bench/accuracy_columns.h"
#include "bench/bench_spec.h"

namespace shadowlab {

class App;

// Runs the sweep on `app`; every row is a flat JSON object (see docs/benchmarks.md). Rows are
// also passed to `onRow` as they complete (progress output). The whole spec is checked first
// (checkBenchSpec), so a bad value fails before the first frame.
// A row's evaluation may run beside the next row's timed frames (BenchSpec::overlapAccuracy), so
// the report, which keeps the images of the rows at the defaults instead of drawing them again,
// sees a row twice: onCapture on the GL thread right after its accuracy capture (the frame and the
// app's state are still the row's; true: keep its evaluations), then onEvaluation for each of them
// on the GL thread when the row completes.
using BenchEvaluationHook = std::function<void(const TechniqueInfo&, const AccuracyPass&, const Evaluation&)>;
struct BenchHooks {
    std::function<void(const nlohmann::json&)> onRow;
    std::function<bool(const TechniqueInfo&)> onCapture;
    BenchEvaluationHook onEvaluation;
};
bool runBench(App& app, const BenchSpec& spec, std::vector<nlohmann::json>& rows, std::string& error,
              const std::function<void(const nlohmann::json&)>& onRow = {}, const BenchHooks& images = {});

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
