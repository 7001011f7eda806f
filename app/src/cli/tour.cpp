// `shadowlab tour TOUR --out DIR`: every step of a guided tour as a slide with its caption and figures.
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

// `shadowlab tour TOUR --out DIR`: every step of a tour as a slide with its caption and figures.
int commandTour(const CommonOptions& common, const std::string& name, const TourPageOptions& pageOptions) {
    Tour tour;
    std::string error;
    if (!loadTour(name, describedTechniques(), tour, error)) return fail(error, kExitBadInput);
    if (!outputProblem("--out", pageOptions.outDir, true, error)) return fail(error, kExitBadInput);
    CommonOptions first = common;
    first.scene = tour.steps.front().scene;   // loaded once at start, not twice
    App app;
    if (int code = startApp(app, first, false)) return code;
    TourPageOptions options = pageOptions;
    if (!parseSize(common.size, options.size, error)) return fail(error, kExitBadInput);
    const int code = writeTourPages(app, tour, options, error);
    if (code) return fail(error, code);
    size_t expectations = 0;
    for (const TourStep& step : tour.steps) expectations += step.expect.size();
    std::printf("tour: %zu steps written to %s (index.html, README.md), %zu expectations passed\n", tour.steps.size(),
                options.outDir.string().c_str(), expectations);
    return 0;
}

class TourCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* tour = cli.add_subcommand("tour", "render every step of a guided tour into index.html and README.md");
        tour->add_option("tour", name_, "a built-in tour (assets/tours/<name>.json) or a tour file")->required();
        tour->add_option("--out,-o", out_, "output folder")->required();
        tour->add_option("--frames", pages_.frames, "frames drawn before each step's image (default 3)")->check(CLI::Range(1, 1000));
        tour->add_option("--bench-frames", pages_.benchFrames, "timed frames of each technique (default 30)")
            ->check(CLI::Range(1, 100000));
        tour->add_option("--warmup", pages_.warmupFrames, "warm-up frames before them (default 5)")->check(CLI::Range(0, 100000));
        tour->add_option("--samples", pages_.referenceSamples, "soft reference: rays per pixel (default 256)")
            ->check(CLI::Range(1, 4096));
        return tour;
    }
    int run(const CommonOptions& common) override {
        pages_.outDir = out_;
        return commandTour(common, name_, pages_);
    }
    std::vector<Unused> unusedCommonOptions() const override {
        const std::string steps = "each step of the tour names its own; edit the tour file";
        return {{"--scene", steps}, {"--scene-param", steps}, {"--technique", steps}, {"--set", steps}};
    }

private:
    std::string name_, out_;
    TourPageOptions pages_;
};

} // namespace

std::unique_ptr<Command> tourCommand() { return std::make_unique<TourCommand>(); }

} // namespace shadowlab::cli
