// The report (see report.h).
#include "bench/report.h"
#include "util/strings.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <map>
#include <optional>
#include <algorithm>
#include <set>

#include "app.h"
#include "bench/accuracy_columns.h"
#include "bench/report_page.h"
#include "util/log.h"
#include "util/parallel.h"
#include "util/paths.h"
#include "util/progress.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

// PNG files of one scene, encoded on every core once its techniques are drawn: encoding is most
// of the images phase's time on a fast GPU (two 1080p files a technique).
bool writePngs(std::vector<std::pair<std::filesystem::path, Image>>& pending, std::string& error) {
    std::vector<std::string> errors(pending.size());
    forEachChunk(pending.size(), 1, [&](size_t i, size_t, size_t) { writePng(pending[i].first, pending[i].second, errors[i]); });
    pending.clear();
    for (const std::string& e : errors)
        if (!e.empty()) {
            error = e;
            return false;
        }
    return true;
}

// The report's images: a screenshot and an error heatmap per technique and scene of the first
// spec, at its first size and the technique's defaults. The sweep's rows at those settings give
// them as they are measured (ImageCollector::onEvaluation); writeImages() draws the rest.
class ImageCollector {
public:
    ImageCollector(App& app, const BenchSpec& spec, std::filesystem::path dir)
        : app_(app), spec_(spec), dir_(std::move(dir)), host_(app.hostValues()) {}

    // BenchHooks::onCapture, GL thread: a row at the defaults not yet shown, its lit frame kept.
    bool onCapture(const TechniqueInfo& info) {
        const std::string scene = app_.scene().name;
        if (done_.count({scene, info.id}) || !atDefaults(info)) return false;
        std::string error;
        if (!app_.presentView(info.id, {}, ~0u, {}, error)) return false;   // the row's frame, lit
        captured_[{scene, info.id}] = app_.readDisplay();
        return true;
    }
    // BenchHooks::onEvaluation: its heatmap against its own reference's physical model.
    void onEvaluation(const TechniqueInfo& info, const AccuracyPass& pass, const Evaluation& e) {
        if (pass.model != TranslucencyModel::Physical || pass.mode != ownReferenceMode(info)) return;
        const std::string scene = app_.scene().name;
        auto frame = captured_.find({scene, info.id});
        if (frame == captured_.end() || !done_.insert({scene, info.id}).second) return;
        ReportImage entry{scene, info.id, info.displayName, scene + "-" + info.id + ".png", scene + "-" + info.id + "-error.png",
                          pass.mode == ReferenceOptions::Mode::Hard ? "hard" : "soft", e.metrics};
        pending.emplace_back(dir_ / entry.image, std::move(frame->second));
        pending.emplace_back(dir_ / entry.heatmap, e.heatmap());
        captured_.erase(frame);
        images.push_back(entry);
    }
    bool has(const std::string& scene, const std::string& technique) const { return done_.count({scene, technique}) > 0; }

    std::vector<ReportImage> images;
    std::vector<std::pair<std::filesystem::path, Image>> pending;

private:
    bool atDefaults(const TechniqueInfo& info) {
        if (app_.renderer().size() != spec_.sizes.front() || app_.hostValues() != host_ ||
            app_.light().size != app_.scene().light.size)
            return false;
        const std::vector<double>& values = app_.params().values(info);
        for (size_t i = 0; i < info.params.size(); ++i)
            if (values[i] != info.params[i].defaultValue) return false;
        return std::find(spec_.scenes.begin(), spec_.scenes.end(), app_.scene().name) != spec_.scenes.end();
    }
    App& app_;
    const BenchSpec& spec_;
    std::filesystem::path dir_;
    std::vector<double> host_;
    std::set<std::pair<std::string, std::string>> done_;
    std::map<std::pair<std::string, std::string>, Image> captured_;   // lit frames awaiting their evaluation
};

// The images the sweep did not give (techniques measured without accuracy or away from their
// defaults, the reference), drawn after it; all of them in scene and technique order.
bool writeImages(App& app, const BenchSpec& spec, ImageCollector& collected, std::vector<ReportImage>& images,
                 const std::filesystem::path& dir, std::string& error) {
    std::vector<std::pair<std::filesystem::path, Image>> pending = std::move(collected.pending);
    if (!writePngs(pending, error)) return false;
    std::map<std::string, size_t> sceneOrder;
    for (const auto& sceneArgument : spec.scenes) {
        if (!app.loadScene(sceneArgument, {}, error)) return false;
        if (!app.setRenderSize(spec.sizes.front(), error)) return false;
        const std::string scene = app.scene().name;
        sceneOrder.emplace(scene, sceneOrder.size());
        for (const auto& info : app.techniques().techniques()) {
            if (collected.has(scene, info.id)) continue;
            app.params().resetToDefaults(info);
            for (int frame = 0; frame < 3; ++frame)
                if (!app.renderFrame(info.id, error)) return false;
            if (!app.presentView(info.id, {}, ~0u, {}, error)) return false;
            ReportImage entry{scene, info.id, info.displayName, scene + "-" + info.id + ".png", "", "", {}};
            pending.emplace_back(dir / entry.image, app.readDisplay());
            if (info.id != "reference") {   // the ray-traced ground truth itself; area-reference is measured
                ReferenceOptions options;
                options.mode = ownReferenceMode(info);
                const bool hard = options.mode == ReferenceOptions::Mode::Hard;
                options.samplesPerPixel = spec.referenceSamples;
                options.adaptive = spec.referenceAdaptive;
                options.model = TranslucencyModel::Physical;   // the heatmap shows the error against the physical model
                Evaluation evaluation;
                if (!app.evaluate(options, evaluation, error, {.footprint = false, .positions = false, .contactBand = false})) return false;
                entry.heatmap = scene + "-" + info.id + "-error.png";
                entry.reference = hard ? "hard" : "soft";
                entry.metrics = evaluation.metrics;
                pending.emplace_back(dir / entry.heatmap, evaluation.heatmap());
            }
            collected.images.push_back(entry);
        }
        if (!writePngs(pending, error)) return false;
    }
    // The page's order: scenes as the spec lists them, techniques as the build has them.
    auto rank = [&](const ReportImage& image) {
        const auto& all = app.techniques().techniques();
        const auto t = std::find_if(all.begin(), all.end(), [&](const TechniqueInfo& info) { return info.id == image.technique; });
        const auto s = sceneOrder.find(image.scene);
        return std::pair{s == sceneOrder.end() ? sceneOrder.size() : s->second, size_t(t - all.begin())};
    };
    images = std::move(collected.images);
    std::stable_sort(images.begin(), images.end(), [&](const ReportImage& a, const ReportImage& b) { return rank(a) < rank(b); });
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
    using Clock = std::chrono::steady_clock;
    auto secondsSince = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    const auto started = Clock::now();
    std::vector<nlohmann::json> rows;
    printBenchHeader();
    std::optional<ImageCollector> collector;
    if (!specs.empty()) collector.emplace(app, specs.front(), outDir / "images");
    for (const BenchSpec& spec : specs) {
        BenchHooks keepImages;
        if (&spec == &specs.front()) {
            keepImages.onCapture = [&](const TechniqueInfo& info) { return collector->onCapture(info); };
            keepImages.onEvaluation = [&](const TechniqueInfo& info, const AccuracyPass& pass, const Evaluation& e) {
                collector->onEvaluation(info, pass, e);
            };
        }
        if (runBench(app, spec, rows, error, printBenchRow, keepImages)) continue;
        if (!interrupted()) return 2;
        // Ctrl-C: the rows measured so far are written (no images, charts or page for a partial sweep).
        if (!writeBenchResults(outDir / "results.csv", rows, error) || !writeBenchResults(outDir / "results.json", rows, error))
            return 1;
        error = "interrupted (Ctrl-C): the " + std::to_string(rows.size()) + " rows measured so far written to " +
                (outDir / "results.json").string();
        return kExitInterrupted;
    }
    if (!writeBenchResults(outDir / "results.csv", rows, error) || !writeBenchResults(outDir / "results.json", rows, error))
        return 1;

    const double sweepSeconds = secondsSince(started);
    const auto imagesStarted = Clock::now();
    std::vector<ReportImage> images;
    if (!specs.empty() && !writeImages(app, specs.front(), *collector, images, outDir / "images", error)) return 1;
    size_t imageFiles = 0;
    for (const ReportImage& image : images) imageFiles += image.heatmap.empty() ? 1 : 2;

    const double imagesSeconds = secondsSince(imagesStarted);
    const auto chartsStarted = Clock::now();
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
    // Where the main job's time went (issue 32's targets are for the whole of it).
    std::printf("report: %.0f s in all: sweep %.0f s (%zu rows), images %.0f s, charts and pages %.0f s\n",
                secondsSince(started), sweepSeconds, rows.size(), imagesSeconds, secondsSince(chartsStarted));
    return 0;
}

} // namespace shadowlab
