// `shadowlab report`: a sweep measured, charted and written up (also the main job without a display).
#include "cli/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app.h"
#include "bench/bench.h"
#include "bench/path_run.h"
#include "bench/report.h"
#include "bench/stress.h"
#include "groundtruth/reference_technique.h"
#include "render/render_limits.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "bench/tour_pages.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/stats.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab::cli {
namespace {

class ReportCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* report = cli.add_subcommand("report", "run the default sweep and write charts, images and a Markdown page");
        report->add_option("--spec", spec_, "benchmark spec (default assets/bench/default.json; quick.json on llvmpipe)");
        report->add_option("--out,-o", out_, "output folder (default out)");
        report->add_option("--overlap-accuracy", overlap_,
                           "evaluate a row beside the next row's timed frames: on | off (default on; off to compare "
                           "timings without it)");
        return report;
    }
    int run(const CommonOptions& common) override {
        bool overlap = true;
        std::string error;
        if (!parseOnOff(overlap_, overlap, error, "--overlap-accuracy")) return fail(error, kExitBadInput);
        return runReport(common, spec_, out_, "--out", overlap);
    }
    std::vector<Unused> unusedCommonOptions() const override {
        const std::string spec = "the benchmark spec (--spec) names what the report measures: its techniques, base, sweep, scenes and sizes";
        return {{"--technique", spec}, {"--set", spec}, {"--scene", spec}, {"--scene-param", spec}, {"--size", spec}};
    }

private:
    std::string spec_, out_ = "out", overlap_ = "on";
};

} // namespace

// The report: the default sweep measured, charted and written up into `outDir`. Without a display
// this is the main job.
int runReport(const CommonOptions& common, const std::string& specFile, const std::string& outDir, const std::string& outOption,
              bool overlapAccuracy) {
    std::string error;
    std::vector<BenchSpec> specs;
    // The output folder and a given spec are checked before a context exists (the default spec
    // depends on the renderer, so it is read after).
    if (!outputProblem(outOption, outDir, true, error)) return fail(error, kExitBadInput);
    if (!specFile.empty() && !loadBenchSpecs(specFile, specs, error)) return fail(error, kExitBadInput);
    App app;
    if (int code = startApp(app, common, false)) return code;
    const bool software = glRendererString().find("llvmpipe") != std::string::npos;
    const std::filesystem::path spec = specFile.empty() ? defaultReportSpec(software) : std::filesystem::path(specFile);
    if (specFile.empty() && !loadBenchSpecs(spec, specs, error)) return fail(error, kExitBadInput);
    for (BenchSpec& each : specs) each.overlapAccuracy = overlapAccuracy;
    std::printf("shadowlab report: sweep %s on %s\n", spec.string().c_str(), glRendererString().c_str());
    const int code = runReport(app, specs, outDir, error, lightSizeOption(common));
    if (code) return fail(error, code);
    return 0;
}

std::unique_ptr<Command> reportCommand() { return std::make_unique<ReportCommand>(); }

} // namespace shadowlab::cli
