// The report (see report.h).
#include "bench/report.h"
#include "util/strings.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <map>
#include <set>

#include "app.h"
#include "bench/report_page.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

// Screenshot and error heatmap of every technique on each scene of the sweep, at the first size.
bool writeImages(App& app, const BenchSpec& spec, const std::filesystem::path& dir, std::vector<ReportImage>& images,
                 std::string& error) {
    for (const auto& scene : spec.scenes) {
        if (!app.loadScene(scene, {}, error)) return false;
        if (!app.setRenderSize(spec.sizes.front(), error)) return false;
        for (const auto& info : app.techniques().techniques()) {
            app.params().resetToDefaults(info);
            for (int frame = 0; frame < 3; ++frame)
                if (!app.renderFrame(info.id, error)) return false;
            if (!app.presentView(info.id, {}, ~0u, {}, error)) return false;
            ReportImage entry{scene, info.id, info.displayName, scene + "-" + info.id + ".png", "", "", {}};
            if (!writePng(dir / entry.image, app.readDisplay(), error)) return false;
            if (info.id != "reference") {   // the ray-traced ground truth itself; area-reference is measured
                const bool hard = info.category == "hard" || info.category == "baseline";
                ReferenceOptions options;
                options.mode = hard ? ReferenceOptions::Mode::Hard : ReferenceOptions::Mode::Soft;
                options.samplesPerPixel = spec.referenceSamples;
                options.adaptive = spec.referenceAdaptive;
                options.model = TranslucencyModel::Physical;   // the heatmap shows the error against the physical model
                Evaluation evaluation;
                if (!app.evaluate(options, evaluation, error)) return false;
                entry.heatmap = scene + "-" + info.id + "-error.png";
                entry.reference = hard ? "hard" : "soft";
                entry.metrics = evaluation.metrics;
                if (!writePng(dir / entry.heatmap, evaluation.heatmap(), error)) return false;
            }
            images.push_back(entry);
        }
    }
    return true;
}

} // namespace

std::filesystem::path defaultReportSpec(bool softwareRenderer) {
    return dataRoot() / "assets" / "bench" / (softwareRenderer ? "quick.json" : "default.json");
}

int runReport(App& app, const std::vector<BenchSpec>& specs, const std::filesystem::path& outDir, std::string& error,
              std::optional<double> lightSize) {
    std::error_code ec;
    std::filesystem::create_directories(outDir / "images", ec);
    std::filesystem::create_directories(outDir / "charts", ec);
    // Every spec checked before the first frame of the first one.
    for (size_t i = 0; i < specs.size(); ++i) {
        if (!checkBenchSpec(specs[i], app.techniques().techniques(), error, lightSize)) {
            error = "benchmark spec " + std::to_string(i) + ": " + error;
            return 2;
        }
    }
    std::vector<nlohmann::json> rows;
    printBenchHeader();
    for (const BenchSpec& spec : specs)
        if (!runBench(app, spec, rows, error, printBenchRow)) return 2;
    if (!writeBenchResults(outDir / "results.csv", rows, error) || !writeBenchResults(outDir / "results.json", rows, error))
        return 1;

    std::vector<ReportImage> images;
    if (!specs.empty() && !writeImages(app, specs.front(), outDir / "images", images, error)) return 1;
    size_t imageFiles = 0;
    for (const ReportImage& image : images) imageFiles += image.heatmap.empty() ? 1 : 2;

    // Charts: matplotlib from Debian (python3-matplotlib) lives with the system interpreter.
    const auto script = dataRoot() / "tools" / "charts.py";
    const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    std::vector<std::string> charts;
    const std::string command = python + " " + shellQuote(script.string()) + " " +
                                shellQuote((outDir / "results.json").string()) + " " + shellQuote((outDir / "charts").string());
    if (FILE* pipe = popen(command.c_str(), "r")) {
        char line[1024];
        while (std::fgets(line, sizeof(line), pipe)) {
            std::string path = line;
            while (!path.empty() && (path.back() == '\n' || path.back() == '\r')) path.pop_back();
            charts.push_back(std::filesystem::path(path).filename().string());
        }
        if (pclose(pipe) != 0) logWarning("charts: " + command + " failed (is python3-matplotlib installed?)");
    }

    ReportContent content{rows.empty() ? benchEnvironment(app) : rows.front(), &specs, &rows, charts, images, imageFiles};
    if (!writeWholeFile(outDir / "README.md", reportMarkdown(content), error) ||
        !writeWholeFile(outDir / "index.html", reportHtml(content), error))
        return 1;
    std::printf("report: %zu rows, %zu charts, %zu images (%zu technique images and their error heatmaps) in %s: "
                "README.md and index.html\n",
                rows.size(), charts.size(), imageFiles, images.size(), outDir.string().c_str());
    return 0;
}

} // namespace shadowlab
