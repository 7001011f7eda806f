// The report's two pages over the same content (bench/report.h): README.md (Markdown) and
// index.html, one self-contained HTML page with no script and nothing fetched from a network, its
// images relative links to the PNG files beside it in the report folder (charts/, images/), so the
// page works wherever the folder is opened. Both have the machine and commit, the column
// definitions, the charts, the results table (one row per measured row) and each technique's
// image beside its error heatmap.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench.h"
#include "groundtruth/metrics.h"

namespace shadowlab {

// One technique's picture on the pages: its image, its error heatmap and what the caption says.
struct ReportImage {
    std::string scene;
    std::string technique;
    std::string displayName;
    std::string image;            // <scene>-<technique>.png in images/
    std::string heatmap;          // <scene>-<technique>-error.png; "" for the reference
    std::string reference;        // "hard" or "soft"
    AccuracyMetrics metrics;
};

// What both pages show.
struct ReportContent {
    nlohmann::json environment;          // gpu, driver, backend, date, commit (a row's, or benchEnvironment)
    const std::vector<BenchSpec>* specs = nullptr;
    const std::vector<nlohmann::json>* rows = nullptr;
    std::vector<std::string> charts;     // file names in charts/
    std::vector<ReportImage> images;
    size_t imageFiles = 0;               // PNG files in images/
};

std::string reportMarkdown(const ReportContent& content);
std::string reportHtml(const ReportContent& content);

} // namespace shadowlab
