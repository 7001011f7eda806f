// `shadowlab stress`: the failure suite (assets/stress/cases.json; docs/stability.md).
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

int commandStress(const CommonOptions& common, const std::string& casesFile, const std::string& sizeText, StressOptions options) {
    StressSuite suite;
    std::string error;
    if (!loadStressSuite(casesFile.empty() ? defaultStressCases() : std::filesystem::path(casesFile), suite, error))
        return fail(error, kExitBadInput);
    if (!sizeText.empty()) {
        glm::ivec2 size;
        if (!parseSize(sizeText, size, error, "--stress-size")) return fail(error, kExitBadInput);
        options.size = size;
    }
    if (!outputProblem("--out", options.outDir, true, error)) return fail(error, kExitBadInput);
    // The request checked from the descriptors first: a refused option costs no GL context.
    std::vector<std::string> techniques;
    std::vector<const StressCase*> cases;
    if (checkStressRequest(describedTechniques(), suite, options, techniques, cases, error)) return fail(error, kExitBadInput);
    App app;
    if (int code = startApp(app, common, false)) return code;
    std::vector<StressCell> cells;
    const int code = runStress(app, suite, options, cells, error);
    return code ? fail(error, code) : 0;
}

class StressCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* stress = cli.add_subcommand("stress", "the failure suite: named cases where techniques fail, table, chart and images");
        stress->add_option("--techniques", techniques_, "comma-separated technique ids (default: every technique found)");
        stress->add_option("--cases", cases_, "comma-separated case ids (default: all)");
        stress->add_option("--cases-file", casesFile_, "cases file (default assets/stress/cases.json)");
        stress->add_option("--out,-o", out_, "output folder (default out/stress)");
        stress->add_option("--stress-size", size_, "render size WIDTHxHEIGHT (default: the cases file's, 160x120)");
        return stress;
    }
    int run(const CommonOptions& common) override {
        StressOptions options;
        std::string error;
        if (!optionList(techniques_, "--techniques", options.techniques, error) || !optionList(cases_, "--cases", options.cases, error))
            return fail(error, kExitBadInput);
        options.sets = common.sets;
        options.outDir = out_;
        options.quiet = common.quiet;
        return commandStress(common, casesFile_, size_, options);
    }

    std::vector<Unused> unusedCommonOptions() const override {
        const std::string cases = "each case of the cases file names its scene, view and light; see --cases-file";
        return {{"--technique", "use --techniques"}, {"--scene", cases}, {"--scene-param", cases}, {"--light-dir", cases},
                {"--light-size", cases}, {"--size", "use --stress-size"}};
    }

private:
    std::string techniques_, cases_, casesFile_, out_ = "out/stress", size_;
};

} // namespace

std::unique_ptr<Command> stressCommand() { return std::make_unique<StressCommand>(); }

} // namespace shadowlab::cli
