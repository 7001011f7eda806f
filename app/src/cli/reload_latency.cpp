// `shadowlab reload-latency`: the hot-reload latency of a plugin library.
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

// Hot-reload latency: the plugin library is rewritten on disk (as a rebuild does) and the time to
// the end of the first frame drawn with the new library is measured, `trials` times.
int commandReloadLatency(const CommonOptions& common, int trials) {
    App app;
    if (int code = startApp(app, common, false)) return code;
    const std::string technique = common.technique.empty() ? "shadowmap" : common.technique;
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info || info->library.empty()) return fail("--technique '" + technique + "': no plugin library", kExitBadInput);
    std::string error;
    std::ifstream in(info->library, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<double> latencies;
    for (int trial = 0; trial < trials; ++trial) {
        for (int i = 0; i < 5; ++i)
            if (!app.renderFrame(technique, error)) return fail(error, kExitFailure);
        glFinish();
        {
            std::ofstream out(info->library, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), std::streamsize(bytes.size()));
        }
        const auto start = std::chrono::steady_clock::now();
        bool reloaded = false;
        while (!reloaded && std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
            if (!app.renderFrame(technique, error)) return fail(error, kExitFailure);
            reloaded = std::find(app.lastReloaded().begin(), app.lastReloaded().end(), technique) != app.lastReloaded().end();
        }
        glFinish();   // the frame drawn with the new library has completed
        if (!reloaded) return fail("the rewritten library was not reloaded within 5 s", kExitFailure);
        latencies.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    const TimingSummary s = summarize(latencies);
    std::printf("hot reload of %s: median %.1f ms, p5 %.1f, p95 %.1f over %d trials (file written -> first frame drawn "
                "with it; polling every 50 ms and waiting for two equal polls)\n",
                technique.c_str(), s.median, s.p5, s.p95, trials);
    return 0;
}

class ReloadLatencyCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* reload = cli.add_subcommand("reload-latency", "measure hot-reload latency of a plugin library");
        reload->add_option("--trials", trials_, "number of reloads (default 10)")->check(CLI::Range(1, 1000));
        return reload;
    }
    int run(const CommonOptions& common) override { return commandReloadLatency(common, trials_); }
    std::vector<Unused> unusedCommonOptions() const override {
        const std::string nothing = "it times the reload of the library, and traces no reference";
        return {{"--set", "it times the reload of the library with the technique's defaults"},
                {"--translucent-layers", nothing},
                {"--reference-device", nothing}};
    }

private:
    int trials_ = 10;
};

} // namespace

std::unique_ptr<Command> reloadLatencyCommand() { return std::make_unique<ReloadLatencyCommand>(); }

} // namespace shadowlab::cli
