// The report (see report.h).
#include "bench/report.h"
#include "util/strings.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <map>
#include <set>

#include "app.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/progress.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {


// One technique's picture on the page: its image, its error heatmap and what the caption says.
struct ReportImage {
    std::string scene;
    std::string technique;
    std::string displayName;
    std::string image;            // images/<scene>-<technique>.png
    std::string heatmap;          // images/<scene>-<technique>-error.png; "" for the reference
    std::string reference;        // "hard" or "soft"
    AccuracyMetrics metrics;
};

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

// The parameters a sweep changes: for each technique, the param.* and scene.* keys whose value
// differs between two of its rows. The others are its defaults or the spec's base, said once.
std::map<std::string, std::set<std::string>> changingSettings(const std::vector<nlohmann::json>& rows) {
    std::map<std::string, std::map<std::string, std::set<std::string>>> seen;
    for (const auto& row : rows)
        for (const auto& [key, value] : row.items())
            if (key.rfind("param.", 0) == 0 || key.rfind("scene.", 0) == 0)
                seen[row.value("technique", "")][key].insert(value.dump());
    std::map<std::string, std::set<std::string>> changing;
    for (const auto& [technique, keys] : seen)
        for (const auto& [key, values] : keys)
            if (values.size() > 1) changing[technique].insert(key);
    return changing;
}

std::string changedSettings(const nlohmann::json& row, const std::set<std::string>& keys) {
    std::string text;
    for (const std::string& key : keys) {
        if (!row.contains(key)) continue;
        if (!text.empty()) text += ' ';
        const auto& value = row[key];
        text += key.substr(key.find('.') + 1) + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
    }
    return text.empty() ? "defaults" : text;
}

std::string percent(const nlohmann::json& row, const std::string& key) {
    return row.contains(key) ? fixed(100.0 * row[key].get<double>(), 2) + "%" : "-";
}

// The Markdown page: the machine, the columns explained, the charts, the results table and the
// images with their heatmaps.
std::string reportPage(const nlohmann::json& environment, const std::vector<BenchSpec>& specs,
                       const std::vector<nlohmann::json>& rows, const std::vector<std::string>& charts,
                       const std::vector<ReportImage>& images, size_t imageFiles) {
    std::ostringstream page;
    page << "# shadowlab report\n\n"
         << "- GPU: " << environment.value("gpu", "") << "\n- driver: " << environment.value("driver", "")
         << "\n- backend: " << environment.value("backend", "") << "\n- date: " << environment.value("date", "")
         << "\n- commit: " << environment.value("commit", "") << "\n\n"
         << "Medians of the timed frames after warm-up (p5 and p95 in results.csv). Timed frames write the lit "
            "colour only; accuracy is measured on a separate, untimed re-render of the last frame with the "
            "accuracy targets.\n\n"
            "Columns of the results table:\n\n"
            "- **scene**, **technique**: the built-in scene and the technique's id.\n"
            "- **parameters**: only those the sweep changes for that technique (every other parameter has its "
            "default, or the spec's base value listed above the table); all of them are in results.csv.\n"
            "- **size**: the output size in pixels.\n"
            "- **frame ms**: GPU time of a whole timed frame.\n"
            "- **passes ms**: the technique's own passes (shadow maps, filtering, the camera pre-pass it asks for).\n"
            "- **shadow term ms**: the technique's main pass minus `none`'s main pass, same view, same run: the "
            "cost of its shadow lookup.\n"
            "- **GPU MiB**: the technique's own GPU memory (its maps and scratch textures), not the host's targets.\n"
            "- **MAE hard**, **MAE soft**: mean absolute error of the shadow term against the ray-traced "
            "reference, on compared pixels (lit side, in the light's cone), against the hard reference (one ray to "
            "the light's centre) and the soft one (rays over the light's area). Hard techniques are measured "
            "against the hard reference, filtered and soft ones against both.\n"
            "- **false shadow hard**, **false shadow soft**: share of compared pixels the reference lights "
            "(>= 0.5) that the technique shadows (< 0.5): acne, over-darkening.\n"
            "- **false light hard**, **false light soft**: share of compared pixels the reference shadows that "
            "the technique lights: leaks, peter panning, light bleeding.\n"
            "- **floors**: `none`'s main pass (no shadow lookup) and the bare depth pass at the technique's "
            "resolution are in results.csv beside every row (floor_main_ms, floor_depth_ms).\n\n";
    if (environment.value("gpu", "").find("llvmpipe") != std::string::npos)
        page << "**Rendered with llvmpipe (CPU): the timings show relative costs on a CPU rasteriser, not GPU "
                "speed.** Speed figures come from the GPU runs in docs/results/.\n\n";
    page << "## Speed against accuracy\n\n";
    for (const auto& chart : charts) page << "![" << chart << "](charts/" << chart << ")\n\n";
    page << "## Results\n\n";
    for (size_t i = 0; i < specs.size(); ++i)
        if (!specs[i].base.empty()) {
            std::string base;
            for (const auto& item : specs[i].base) base += (base.empty() ? "" : ", ") + ("`" + item + "`");
            page << "Set for every row" << (specs.size() > 1 ? " of spec " + std::to_string(i) : std::string()) << ": " << base
                 << ".\n\n";
        }
    page << "| scene | technique | parameters | size | frame ms | passes ms | shadow term ms | GPU MiB | MAE hard | "
            "false shadow hard | false light hard | MAE soft | false shadow soft | false light soft |\n"
         << "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    const auto changing = changingSettings(rows);
    for (const auto& row : rows) {
        const std::string technique = row.value("technique", "");
        const auto keys = changing.find(technique);
        page << "| " << row.value("scene", "") << " | " << technique << " | "
             << changedSettings(row, keys == changing.end() ? std::set<std::string>{} : keys->second) << " | "
             << row.value("width", 0) << "x" << row.value("height", 0) << " | " << fixed(row.value("frame_ms", 0.0), 3)
             << " | " << fixed(row.value("technique_passes_ms", 0.0), 3) << " | "
             << (row.contains("shadow_term_ms") ? fixed(row["shadow_term_ms"].get<double>(), 3) : "-") << " | "
             << fixed(double(row.value("gpu_bytes", size_t(0))) / 1048576.0, 2) << " | "
             << (row.contains("hard_mae") ? fixed(row["hard_mae"].get<double>(), 4) : "-") << " | "
             << percent(row, "hard_false_shadow") << " | " << percent(row, "hard_false_light") << " | "
             << (row.contains("soft_mae") ? fixed(row["soft_mae"].get<double>(), 4) : "-") << " | "
             << percent(row, "soft_false_shadow") << " | " << percent(row, "soft_false_light") << " |\n";
    }
    page << "\n## Images\n\nEach technique with its defaults at " << (specs.empty() ? 0 : specs.front().sizes.front().x) << "x"
         << (specs.empty() ? 0 : specs.front().sizes.front().y)
         << ", and beside it its error heatmap against the ray-traced reference: magenta where it is darker "
            "than the reference (false shadow), green where it is lighter (false light), stronger with the error, "
            "black where it agrees or the pixel is not compared. "
         << imageFiles << " images in images/.\n\n";
    std::string scene;
    for (const ReportImage& image : images) {
        if (image.scene != scene) {
            scene = image.scene;
            page << "### " << scene << "\n\n| technique | image | error heatmap |\n|---|---|---|\n";
        }
        page << "| **" << image.displayName << "** (`" << image.technique << "`)";
        if (image.heatmap.empty()) {
            page << ": the reference itself | ![" << image.image << "](images/" << image.image << ") | - |\n";
            continue;
        }
        page << ": against the " << image.reference << " reference, MAE " << fixed(image.metrics.mae, 4) << ", false shadow "
             << fixed(100.0 * image.metrics.falseShadowRate, 2) << "%, false light "
             << fixed(100.0 * image.metrics.falseLightRate, 2) << "% | ![" << image.image << "](images/" << image.image
             << ") | ![" << image.heatmap << "](images/" << image.heatmap << ") |\n";
    }
    page << "\n";
    return page.str();
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
    for (const BenchSpec& spec : specs) {
        if (runBench(app, spec, rows, error, printBenchRow)) continue;
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

    const nlohmann::json environment = rows.empty() ? benchEnvironment(app) : rows.front();
    const std::string page = reportPage(environment, specs, rows, charts, images, imageFiles);
    if (!writeWholeFile(outDir / "README.md", page, error)) return 1;
    std::printf("report: %zu rows, %zu charts, %zu images (%zu technique images and their error heatmaps) in %s\n", rows.size(),
                charts.size(), imageFiles, images.size(), outDir.string().c_str());
    return 0;
}

} // namespace shadowlab
