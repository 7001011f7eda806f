// The report (see report.h).
#include "bench/report.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <map>
#include <set>

#include "app.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

std::string fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    return text;
}

std::string shellQuote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Screenshot and error heatmap of every technique on each scene of the sweep, at the first size.
bool writeImages(App& app, const BenchSpec& spec, const std::filesystem::path& dir, std::vector<std::string>& images,
                 std::string& error) {
    for (const auto& scene : spec.scenes) {
        if (!app.loadScene(scene, {}, error)) return false;
        if (!app.setRenderSize(spec.sizes.front(), error)) return false;
        for (const auto& info : app.techniques().techniques()) {
            app.params().resetToDefaults(info);
            for (int frame = 0; frame < 3; ++frame)
                if (!app.renderFrame(info.id, error)) return false;
            if (!app.presentView(info.id, {}, ~0u, {}, error)) return false;
            const std::string name = scene + "-" + info.id;
            if (!writePng(dir / (name + ".png"), app.readDisplay(), error)) return false;
            images.push_back(name + ".png");
            if (info.category == "reference") continue;
            ReferenceOptions options;
            options.mode = (info.category == "hard" || info.category == "baseline") ? ReferenceOptions::Mode::Hard
                                                                                     : ReferenceOptions::Mode::Soft;
            options.samplesPerPixel = spec.referenceSamples;
            options.adaptive = spec.referenceAdaptive;
            options.model = TranslucencyModel::Physical;   // the heatmap shows the error against the physical model
            Evaluation evaluation;
            if (!app.evaluate(options, evaluation, error)) return false;
            if (!writePng(dir / (name + "-error.png"), evaluation.heatmap(), error)) return false;
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

    std::vector<std::string> images;
    if (!specs.empty() && !writeImages(app, specs.front(), outDir / "images", images, error)) return 1;

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
    std::ostringstream page;
    page << "# shadowlab report\n\n"
         << "- GPU: " << environment.value("gpu", "") << "\n- driver: " << environment.value("driver", "")
         << "\n- backend: " << environment.value("backend", "") << "\n- date: " << environment.value("date", "")
         << "\n- commit: " << environment.value("commit", "") << "\n\n"
         << "Medians of the timed frames after warm-up (p5 and p95 in results.csv). Timed frames write the lit "
            "colour only; accuracy is measured on a separate, untimed re-render of the last frame with the "
            "accuracy targets.\n\n"
            "- **frame ms**: GPU time of a whole timed frame.\n"
            "- **passes ms**: the technique's own passes (shadow maps, filtering, the camera pre-pass it asks for).\n"
            "- **shadow term ms**: the technique's main pass minus `none`'s main pass, same view, same run: the "
            "cost of its shadow lookup.\n"
            "- **floors**: `none`'s main pass (no shadow lookup) and the bare depth pass at the technique's "
            "resolution are in results.csv beside every row (floor_main_ms, floor_depth_ms).\n"
            "- **MAE**: mean absolute error of the shadow term against the ray-traced reference, on compared "
            "pixels (lit side, in the light's cone). Hard techniques against the hard reference, filtered and "
            "soft ones against both.\n\n";
    if (environment.value("gpu", "").find("llvmpipe") != std::string::npos)
        page << "**Rendered with llvmpipe (CPU): the timings show relative costs on a CPU rasteriser, not GPU "
                "speed.** Speed figures come from the GPU runs in docs/results/.\n\n";
    page << "## Speed against accuracy\n\n";
    for (const auto& chart : charts) page << "![" << chart << "](charts/" << chart << ")\n\n";
    page << "## Results\n\n| scene | technique | parameters | size | frame ms | passes ms | shadow term ms | GPU MiB | MAE hard | MAE soft |\n"
         << "|---|---|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& row : rows) {
        page << "| " << row.value("scene", "") << " | " << row.value("technique", "") << " | " << rowSettings(row) << " | "
             << row.value("width", 0) << "x" << row.value("height", 0) << " | " << fixed(row.value("frame_ms", 0.0), 3)
             << " | " << fixed(row.value("technique_passes_ms", 0.0), 3) << " | "
             << (row.contains("shadow_term_ms") ? fixed(row["shadow_term_ms"].get<double>(), 3) : "-") << " | "
             << fixed(double(row.value("gpu_bytes", size_t(0))) / 1048576.0, 2) << " | "
             << (row.contains("hard_mae") ? fixed(row["hard_mae"].get<double>(), 4) : "-") << " | "
             << (row.contains("soft_mae") ? fixed(row["soft_mae"].get<double>(), 4) : "-") << " |\n";
    }
    page << "\n## Images\n\nEach technique with its defaults, and its error heatmap (magenta: false shadow, "
            "green: false light).\n\n";
    for (const auto& image : images) page << "![" << image << "](images/" << image << ")\n";
    if (!writeWholeFile(outDir / "README.md", page.str(), error)) return 1;
    std::printf("report: %zu rows, %zu charts, %zu images in %s\n", rows.size(), charts.size(), images.size(),
                outDir.string().c_str());
    return 0;
}

} // namespace shadowlab
