// `shadowlab bench`: sweeps of techniques, scenes and parameters timed (and measured) into CSV or
// JSON; with --path, every frame of a camera and light path timed.
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
#include "util/progress.h"
#include "util/stats.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab::cli {
namespace {

int commandBench(const CommonOptions& common, std::vector<BenchSpec> specs, const std::string& out) {
    // Everything checked before a context exists or a frame is drawn: techniques from their
    // descriptors (no GL), scenes with checkScene. The device's limits come right after.
    {
        PluginScan scan = scanPlugins(pluginDir(), {referenceDescriptor().id});
        scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));
        std::string error;
        for (size_t i = 0; i < specs.size(); ++i) {
            if (!checkBenchSpec(specs[i], scan.techniques, error, lightSizeOption(common))) {
                return fail(error, kExitBadInput);   // a spec file's errors name the file and the spec
            }
        }
    }
    App app;
    if (int code = startApp(app, common, false)) return code;
    for (const BenchSpec& spec : specs) {
        for (const glm::ivec2 size : spec.sizes) {
            std::string error;
            if (!checkRenderTargets(size, app.renderer().msaaSamples(), 0, error)) return fail(error, kExitBadInput);
        }
        // A path group's path resolved on each of its scenes before the first frame of any group.
        for (const std::string& scene : spec.path.empty() ? std::vector<std::string>{} : spec.scenes) {
            std::string error;
            CameraPath path;
            try {
                if (resolvePath(spec.path, loadScene(scene), BuiltinPathOptions{}, path, error)) continue;
            } catch (const SceneError& e) {
                error = e.what();
            }
            return fail(spec.source + ": path '" + spec.path + "' on scene '" + scene + "': " + error, kExitBadInput);
        }
    }
    std::vector<nlohmann::json> rows;
    std::string error;
    // The file is rewritten after every row, so a run cut short keeps what it measured.
    std::vector<nlohmann::json> written;
    printBenchHeader();
    auto onRow = [&](const nlohmann::json& row) {
        printBenchRow(row);
        written.push_back(row);
        std::string writeError;
        if (!writeBenchResults(out, written, writeError)) logWarning(writeError);
    };
    for (const BenchSpec& spec : specs) {
        if (runBench(app, spec, rows, error, onRow)) continue;
        if (!interrupted()) return fail(error, kExitBadInput);
        // Ctrl-C: the rows measured so far are the results (the row in progress is dropped).
        if (!writeBenchResults(out, written, error)) return fail(error, kExitFailure);
        return fail("interrupted (Ctrl-C): the " + std::to_string(written.size()) + " rows measured so far written to " + out,
                    kExitInterrupted);
    }
    if (!writeBenchResults(out, rows, error)) return fail(error, kExitFailure);
    logInfo("wrote " + std::to_string(rows.size()) + " rows to " + out);
    return 0;
}

// `bench --path`: every frame of a path timed per technique and scene (docs/stability.md).
int commandBenchPath(const CommonOptions& common, const PathBenchOptions& options, const std::string& out) {
    {
        // The scenes are checked before a context exists.
        for (const std::string& scene : options.scenes) {
            try {
                checkScene(scene);
            } catch (const SceneError& e) {
                return fail(std::string("--scenes: ") + e.what(), kExitBadInput);
            }
        }
    }
    App app;
    if (int code = startApp(app, common, false)) return code;
    std::string error;
    for (const std::string& scene : options.scenes.empty() ? std::vector<std::string>{app.scene().name} : options.scenes) {
        // Each scene's path resolved up front, so a bad --path fails before the first frame.
        Scene loaded = loadScene(scene);
        CameraPath path;
        BuiltinPathOptions pathOptions;
        pathOptions.frames = options.frames;
        if (!resolvePath(options.path, loaded, pathOptions, path, error)) return fail(error, kExitBadInput);
    }
    std::vector<nlohmann::json> rows;
    auto onRow = [&](const nlohmann::json& row) {
        std::printf("%-12s %-20s path %-8s %4d frames  frame ms p5 %.3f  p50 %.3f  p95 %.3f  max %.3f (frame %d)%s\n",
                    row["scene"].get<std::string>().c_str(), row["technique"].get<std::string>().c_str(),
                    row["path"].get<std::string>().c_str(), row["frames"].get<int>(), row["frame_ms_p5"].get<double>(),
                    row["frame_ms_p50"].get<double>(), row["frame_ms_p95"].get<double>(), row["frame_ms_max"].get<double>(),
                    row["frame_ms_max_frame"].get<int>(),
                    row.contains("flicker_mean")
                        ? ("  flicker " + std::to_string(row["flicker_mean"].get<double>()) + "  popping " +
                           std::to_string(row["popping"].get<double>())).c_str()
                        : "");
        std::string writeError;
        if (!writeBenchResults(out, rows, writeError)) logWarning(writeError);
    };
    if (int code = benchPath(app, options, rows, onRow, error)) {
        if (!interrupted()) return fail(error, code);
        // Ctrl-C: the rows so far, the last one with the frames timed before it (marked "interrupted").
        if (!writeBenchResults(out, rows, error)) return fail(error, kExitFailure);
        return fail("interrupted (Ctrl-C): " + std::to_string(rows.size()) + " rows written to " + out, kExitInterrupted);
    }
    if (!writeBenchResults(out, rows, error)) return fail(error, kExitFailure);
    logInfo("wrote " + std::to_string(rows.size()) + " rows to " + out);
    return 0;
}

class BenchCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* bench = cli.add_subcommand("bench", "measure sweeps of techniques, scenes and parameters into CSV or JSON");
        bench->add_option("--techniques", techniques_, "comma-separated technique ids (default: all but the reference)");
        bench->add_option("--scenes", scenes_, "comma-separated scenes (default: cube)");
        bench->add_option("--sweep", sweeps_, "key=v1,v2,...: technique parameter, scene.<param> or light.size (repeatable)");
        bench->add_option("--size", sizes_, "output size WxH (repeatable; default 1280x720)");
        bench->add_option("--frames", spec_.frames, "timed frames per combination (default 200)")->check(CLI::Range(1, 100000));
        bench->add_option("--warmup", spec_.warmupFrames, "warm-up frames (default 20)")->check(CLI::Range(0, 100000));
        bench->add_option("--stable-within", spec_.stableWithin,
                          "stop timing a combination once its GPU frame median is known to within this fraction (95%; "
                          "e.g. 0.01), after --min-frames; default: time every --frames frame");
        bench->add_option("--min-frames", spec_.minFrames, "with --stable-within: frames timed at least (default 10)");
        bench->add_flag("--accuracy", spec_.accuracy, "add the ground-truth metrics of each combination's last frame");
        bench->add_option("--reference", reference_, "with --accuracy: hard | soft | both | auto");
        bench->add_option("--samples", samples_, "soft reference rays per pixel (default 1024)");
        bench->add_option("--reference-adaptive", adaptive_,
                          "soft reference: a first batch everywhere, all --samples rays only near penumbrae: on | off (default on)");
        bench->add_flag("--depth-floor", spec_.depthFloor, "add a bare depth-only pass per shadow-map resolution");
        bench->add_flag("--contact-band", spec_.contactBand,
                        "with --accuracy: the contact band's false light (hard_contact_*; one more shadow ray a pixel)");
        bench->add_option("--overlap-accuracy", overlap_,
                          "with --accuracy: evaluate a row beside the next row's timed frames: on | off (default on; "
                          "off to compare timings without it)");
        bench->add_option("--spec", specFile_, "JSON spec (one object or an array), which says everything the lists below would");
        bench->add_option("--out,-o", out_, "results file: .csv or .json")->required();
        bench->add_option("--path", path_,
                          "time every frame along a camera and light path (a JSON file, a path of the scene or built-in: "
                          "orbit, dolly, sweep, walk, static): p5/p50/p95/max per technique and scene; --accuracy adds the "
                          "temporal metrics");
        bench->add_option("--path-frames", pathFrames_, "with --path: frames along it (default: the path's own)")
            ->check(CLI::Range(1, 100000));
        declareExclusions(*bench);
        command_ = bench;
        return bench;
    }
    int run(const CommonOptions& common) override {
        auto given = [&](const char* name) { return command_->get_option(name)->count() > 0; };
        if (!specFile_.empty() && !common.sets.empty())
            return fail("--set: the spec (--spec) sets its parameters itself (its \"base\")", kExitBadInput);
        for (const char* option : {"--reference", "--samples", "--reference-adaptive", "--contact-band"})
            if (given(option) && !spec_.accuracy)
                return fail(std::string(option) + ": only --accuracy traces the reference", kExitBadInput);
        std::string error;
        if (!outputProblem("--out", out_, false, error)) return fail(error, kExitBadInput);
        return path_.empty() ? runSweep(common) : runPath(common);
    }
    std::vector<Unused> unusedCommonOptions() const override {
        std::vector<Unused> unused{{"--technique", "use --techniques"}};
        if (specFile_.empty() && !spec_.accuracy)
            for (const char* option : {"--translucent-layers", "--reference-device"})
                unused.push_back({option, "only --accuracy traces the reference"});
        if (path_.empty() || !scenes_.empty()) {
            unused.push_back({"--scene", "use --scenes"});
            unused.push_back({"--scene-param", "sweep scene parameters: --sweep scene.NAME=V"});
        }
        return unused;
    }

private:
    // Options that mean nothing with another given (CLI11's excludes and needs: exit 2 naming both):
    // a spec file says everything the command-line lists would, a path is timed frame by frame.
    void declareExclusions(CLI::App& bench) {
        CLI::Option* spec = bench.get_option("--spec");
        CLI::Option* path = bench.get_option("--path");
        for (const char* name : {"--techniques", "--scenes", "--sweep", "--size", "--frames", "--warmup", "--accuracy",
                                 "--reference", "--samples", "--reference-adaptive", "--depth-floor", "--stable-within",
                                 "--min-frames", "--contact-band"})
            bench.get_option(name)->excludes(spec);
        bench.get_option("--min-frames")->needs(bench.get_option("--stable-within"));
        for (const char* name : {"--sweep", "--frames", "--samples", "--reference-adaptive", "--depth-floor", "--stable-within"})
            bench.get_option(name)->excludes(path);
        bench.get_option("--path-frames")->needs(path);
    }

    int runPath(const CommonOptions& common) {
        if (!specFile_.empty()) return fail("--path: with the command line's lists, not --spec", kExitBadInput);
        if (!sweeps_.empty()) return fail("--path: times one setting per technique (no --sweep)", kExitBadInput);
        PathBenchOptions options;
        std::string error;
        if (!optionList(techniques_, "--techniques", options.techniques, error) || !optionList(scenes_, "--scenes", options.scenes, error))
            return fail(error, kExitBadInput);
        options.sets = common.sets;
        options.path = path_;
        options.frames = pathFrames_;
        options.warmupFrames = spec_.warmupFrames;
        options.accuracy = spec_.accuracy;
        if (reference_ == "soft") options.reference = ReferenceOptions::Mode::Soft;
        else if (reference_ != "hard" && reference_ != "auto")
            return fail("--reference '" + reference_ + "': with --path, hard or soft", kExitBadInput);
        if (sizes_.size() > 1) return fail("--path: one --size", kExitBadInput);
        CommonOptions pathCommon = common;
        if (!sizes_.empty()) pathCommon.size = sizes_.front();
        return commandBenchPath(pathCommon, options, out_);
    }
    int runSweep(const CommonOptions& common) {
        std::vector<BenchSpec> specs;
        std::string error;
        if (!parseOnOff(adaptive_, spec_.referenceAdaptive, error, "--reference-adaptive")) return fail(error, kExitBadInput);
        if (!parseOnOff(overlap_, spec_.overlapAccuracy, error, "--overlap-accuracy")) return fail(error, kExitBadInput);
        if (!specFile_.empty()) {
            if (!loadBenchSpecs(specFile_, specs, error)) return fail(error, kExitBadInput);
            for (BenchSpec& spec : specs) spec.overlapAccuracy = spec_.overlapAccuracy;
            return commandBench(common, specs, out_);
        }
        spec_.fromCommandLine = true;
        spec_.reference = reference_;
        spec_.referenceSamples = samples_;
        if (!optionList(techniques_, "--techniques", spec_.techniques, error)) return fail(error, kExitBadInput);
        if (!scenes_.empty() && !optionList(scenes_, "--scenes", spec_.scenes, error)) return fail(error, kExitBadInput);
        for (const auto& sweep : sweeps_)
            if (!addSweep(spec_, sweep, error)) return fail(error, kExitBadInput);
        if (!sizes_.empty()) spec_.sizes.clear();
        for (const auto& text : sizes_) {
            glm::ivec2 size;
            if (!parseSize(text, size, error, "--size")) return fail(error, kExitBadInput);
            spec_.sizes.push_back(size);
        }
        spec_.base = common.sets;
        specs.push_back(spec_);
        return commandBench(common, specs, out_);
    }

    BenchSpec spec_;
    std::string techniques_, scenes_, specFile_, out_, reference_ = "auto", adaptive_ = "on", overlap_ = "on", path_;
    std::vector<std::string> sweeps_, sizes_;
    int samples_ = BenchSpec{}.referenceSamples, pathFrames_ = 0;
    CLI::App* command_ = nullptr;
};

} // namespace

std::unique_ptr<Command> benchCommand() { return std::make_unique<BenchCommand>(); }

} // namespace shadowlab::cli
