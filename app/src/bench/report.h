// `shadowlab report`: the default sweep measured, charted and written up. On a headless machine
// it is the main job. Writes into a folder:
//   results.csv, results.json      every benchmark row
//   charts/*.png                   tools/charts.py (matplotlib): speed against accuracy with the
//                                  Pareto front, milliseconds against each swept parameter; beside
//                                  each, <name>.boxes.json (its label, legend and marker boxes)
//   images/<scene>-<technique>.png each technique, lit; images/<scene>-<technique>-error.png its
//                                  error heatmap against the reference
//   README.md                      the page: environment, table, charts, images
//   index.html                     the same as one self-contained HTML page (no script, nothing
//                                  fetched; images by relative links into charts/ and images/)
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench.h"

namespace shadowlab {

// The sweep a report runs: assets/bench/default.json, or quick.json on a software renderer
// (llvmpipe), where the full sweep would take hours.
std::filesystem::path defaultReportSpec(bool softwareRenderer);

// `lightSize` is a --light-size applied to every scene, checked against each scene's light first.
int runReport(App& app, const std::vector<BenchSpec>& specs, const std::filesystem::path& outDir, std::string& error,
              std::optional<double> lightSize = std::nullopt);

} // namespace shadowlab
