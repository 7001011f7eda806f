// `shadowlab eval`: accuracy against the ray-traced reference, with the frame timing of the same run.
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
#include "bench/accuracy_columns.h"
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

std::string describeParams(App& app, const TechniqueInfo& info) {
    std::string text;
    const auto& values = app.params().values(info);
    for (size_t i = 0; i < info.params.size(); ++i) {
        if (!text.empty()) text += " ";
        text += info.params[i].id + "=" + formatParamValue(info.params[i], values[i]);
    }
    return text;
}

// One reference's lines of the human-readable report.
void printAccuracy(const std::string& name, const nlohmann::json& metrics) {
    std::printf("  vs %s reference (%s model): MAE %.4f  RMSE %.4f  false shadow %.3f%%  false light %.3f%%  "
                "MAE penumbra %.4f  MAE elsewhere %.4f  noise %.4f  compared %.1f%% of pixels\n",
                name.c_str(), metrics["model"].get<std::string>().c_str(), metrics["mae"].get<double>(), metrics["rmse"].get<double>(),
                100.0 * metrics["falseShadowRate"].get<double>(), 100.0 * metrics["falseLightRate"].get<double>(),
                metrics["maePenumbra"].get<double>(), metrics["maeOutsidePenumbra"].get<double>(),
                metrics["noiseEnergy"].get<double>(), 100.0 * metrics["comparedFraction"].get<double>());
    const auto& thirds = metrics["maeByViewDepth"];
    const auto& thirdPixels = metrics["comparedPixelsByViewDepth"];
    std::printf("    MAE by view depth (thirds of near..far): near %.4f (%zu px)  mid %.4f (%zu px)  far %.4f (%zu px)\n",
                thirds[0].get<double>(), thirdPixels[0].get<size_t>(), thirds[1].get<double>(),
                thirdPixels[1].get<size_t>(), thirds[2].get<double>(), thirdPixels[2].get<size_t>());
    if (metrics.contains("translucent_receivers")) {
        const auto& t = metrics["translucent_receivers"];
        const auto& channel = t["maePerChannel"];
        std::printf("    translucent receivers (%zu layers, %zu px): MAE %.4f  (r %.4f g %.4f b %.4f)  false shadow %.3f%%  "
                    "false light %.3f%%;  by layer:",
                    t["layers"].size(), t["comparedPixels"].get<size_t>(), t["mae"].get<double>(),
                    channel[0].get<double>(), channel[1].get<double>(), channel[2].get<double>(),
                    100.0 * t["falseShadowRate"].get<double>(), 100.0 * t["falseLightRate"].get<double>());
        for (const auto& layer : t["layers"])
            std::printf(" %.4f (%zu px)", layer["mae"].get<double>(), layer["comparedPixels"].get<size_t>());
        std::printf("\n");
    }
    if (metrics.contains("contact_false_light"))
        std::printf("    contact band (shadow ray meets a caster within %.2f units; %zu px): false light %.3f%%\n",
                    double(kContactBandDistance), metrics["contact_band_pixels"].get<size_t>(),
                    100.0 * metrics["contact_false_light"].get<double>());
    if (metrics.contains("edge_band_mae"))
        std::printf("    edge band (within %d px of a hard edge; %zu px): MAE %.4f;  off the band: MAE %.4f\n", kEdgeBandRadius,
                    metrics["edge_band_pixels"].get<size_t>(), metrics["edge_band_mae"].get<double>(),
                    metrics["off_edge_mae"].get<double>());
    if (metrics.contains("reference_floor"))
        std::printf("    soft reference: %d rays per pixel%s (%.1f%% of pixels refined), traced in %.2f s; its own "
                    "penumbra error (floor) %.4f\n",
                    metrics["reference_rays"].get<int>(), metrics["reference_adaptive"].get<bool>() ? ", adaptive" : "",
                    100.0 * metrics["reference_refined_fraction"].get<double>(),
                    metrics["trace_seconds"].get<double>(), metrics["reference_floor"].get<double>());
}

// eval's detail of one evaluation beside the bench columns: the metrics as metricsToJson names
// them, the translucent receivers together and layer by layer, the trace time and, soft, the
// reference's own figures.
nlohmann::json evaluationJson(const AccuracyPass& pass, const Evaluation& evaluation) {
    nlohmann::json out = nlohmann::json::parse(metricsToJson(evaluation.metrics));
    out["model"] = translucencyModelName(pass.model);
    out["trace_seconds"] = evaluation.traceSeconds;
    if (!evaluation.translucentLayers.empty()) {
        nlohmann::json receivers = nlohmann::json::parse(metricsToJson(evaluation.translucentMetrics));
        for (const TranslucentLayerEvaluation& layer : evaluation.translucentLayers)
            receivers["layers"].push_back(nlohmann::json::parse(metricsToJson(layer.metrics)));
        out["translucent_receivers"] = receivers;
    }
    if (!evaluation.contactBand.empty()) {
        out["contact_false_light"] = evaluation.metrics.contactFalseLightRate;
        out["contact_band_pixels"] = evaluation.metrics.contactBandPixels;
    }
    if (pass.mode == ReferenceOptions::Mode::Hard) {
        out["edge_band_mae"] = evaluation.metrics.maeEdgeBand;
        out["off_edge_mae"] = evaluation.metrics.maeOffEdgeBand;
        out["edge_band_pixels"] = evaluation.metrics.edgeBandPixels;
    }
    if (pass.mode == ReferenceOptions::Mode::Soft) {
        // The reference's own penumbra error: soft figures below about 4x it are not resolved.
        const ReferenceStats& r = evaluation.referenceStats;
        out["reference_rays"] = r.samplesPerPixel;
        out["reference_adaptive"] = r.adaptive;
        out["reference_floor"] = evaluation.referenceFloor;
        out["reference_refined_fraction"] = r.tracedPixels ? double(r.refinedPixels) / double(r.tracedPixels) : 0.0;
        out["reference_shadow_rays"] = r.shadowRays;
    }
    return out;
}

// The human-readable report of eval's JSON.
void printEval(const nlohmann::json& out) {
    std::printf("scene %s, technique %s (%s), %dx%d, %s\n", out["scene"].get<std::string>().c_str(),
                out["technique"].get<std::string>().c_str(), out["parameters"].get<std::string>().c_str(),
                out["width"].get<int>(), out["height"].get<int>(), out["renderer"].get<std::string>().c_str());
    for (const auto& [pass, summary] : out["gpu_ms"].items())
        std::printf("  GPU %-20s median %8.3f ms  (p5 %.3f, p95 %.3f)\n", pass.c_str(), summary["median"].get<double>(),
                    summary["p5"].get<double>(), summary["p95"].get<double>());
    std::printf("  host CPU per frame   median %8.3f ms;  GPU memory %.2f MiB\n", out["cpu_ms"]["median"].get<double>(),
                double(out["gpu_bytes"].get<size_t>()) / 1048576.0);
    if (out.contains("texel_footprint")) {
        // Seed 002 eq. 8.1's dp/ds: pixels one shadow-map texel covers along its worst direction.
        const auto& f = out["texel_footprint"];
        const auto& t = f["medianByViewDepth"];
        std::printf("  texel footprint m (pixels per texel, worst direction; > 1 undersampled): median %.3f  p95 %.3f  "
                    "max %.3g  undersampled %.1f%% of pixels  median by view-depth third %.3f / %.3f / %.3f  "
                    "projection cos(a)/cos(b) median %.3f p95 %.3f  (%zu maps, %zu px uncovered)\n",
                    f["median"].get<double>(), f["p95"].get<double>(), f["max"].get<double>(),
                    100.0 * f["undersampledFraction"].get<double>(), t[0].get<double>(), t[1].get<double>(),
                    t[2].get<double>(), f["projectionMedian"].get<double>(), f["projectionP95"].get<double>(),
                    f["maps"].get<size_t>(), f["uncoveredPixels"].get<size_t>());
    }
    for (const auto& [name, metrics] : out["accuracy"].items()) printAccuracy(name, metrics);
}

int commandEval(const CommonOptions& common, const std::string& reference, int samples, bool adaptive, int frames,
                bool json) {
    if (int code = techniqueOptionsProblem(common.technique, common.sets)) return code;
    App app;
    if (int code = startApp(app, common, false)) return code;
    const std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
    std::string error;
    AccuracyRequest request{{}, samples, adaptive};
    if (!referenceModes(reference, *info, request.modes, error)) return fail(error, kExitBadInput);
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    Measurement m;
    if (!app.measure(technique, 5, frames, m, error)) return fail(error, kExitFailure);

    nlohmann::json out = {{"scene", app.scene().name}, {"technique", technique}, {"parameters", describeParams(app, *info)},
                          {"width", app.renderer().size().x}, {"height", app.renderer().size().y},
                          {"renderer", glRendererString()}, {"gpu_bytes", m.gpuBytes}};
    for (const auto& [pass, summary] : m.gpuMs)
        out["gpu_ms"][pass] = {{"median", summary.median}, {"p5", summary.p5}, {"p95", summary.p95}};
    out["cpu_ms"] = {{"median", m.cpuMs.median}, {"p5", m.cpuMs.p5}, {"p95", m.cpuMs.p95}};
    out["translucency_model"] = translucencyModelName(info->translucencyModel);
    out["reference_device"] = referenceDeviceName(app.referenceDevice());
    // Against the physical model ("hard", "soft") and, where it differs, the technique's own
    // ("hard_own", "soft_own"): docs/benchmarks.md, "Translucency models". "bench_columns" holds
    // what a bench row of this frame holds, measured by the same function.
    nlohmann::json columns = nlohmann::json::object();
    const bool measured = addAccuracyColumns(app, *info, request, columns, error, [&](const AccuracyPass& pass, const Evaluation& e) {
        out["accuracy"][pass.prefix.substr(0, pass.prefix.size() - 1)] = evaluationJson(pass, e);
        if (!out.contains("texel_footprint") && e.footprint.maps > 0)
            out["texel_footprint"] = nlohmann::json::parse(footprintToJson(e.footprint));
    });
    if (!measured) return fail(error, kExitFailure);
    out["bench_columns"] = columns;
    if (json) std::cout << out.dump(2) << "\n";
    else printEval(out);
    return 0;
}

class EvalCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* eval = cli.add_subcommand("eval", "accuracy against the ray-traced reference, with the frame timing of the same run");
        eval->add_option("--reference", reference_, "hard | soft | both | auto (default: hard for hard techniques, else both)");
        samplesOption_ =
            eval->add_option("--samples", samples_, "soft reference: rays per pixel (default 1024)")->check(CLI::Range(1, 4096));
        adaptiveOption_ = eval->add_option("--reference-adaptive", adaptive_,
                         "soft reference: a first batch everywhere, all --samples rays only near penumbrae: on | off (default on)");
        eval->add_option("--frames", frames_, "timed frames (default 50)")->check(CLI::Range(1, 100000));
        eval->add_flag("--json", json_, "machine-readable output");
        return eval;
    }
    int run(const CommonOptions& common) override {
        bool adaptive = true;
        std::string error;
        if (!parseOnOff(adaptive_, adaptive, error, "--reference-adaptive")) return fail(error, kExitBadInput);
        // The soft reference's options mean nothing to the hard one (one ray a pixel): refused, not ignored.
        for (const CLI::Option* option : {samplesOption_, adaptiveOption_})
            if (reference_ == "hard" && option->count() > 0)
                return fail(option->get_name() + ": only the soft reference has it (--reference hard traces one ray a pixel)",
                            kExitBadInput);
        return commandEval(common, reference_, samples_, adaptive, frames_, json_);
    }

private:
    std::string reference_ = "auto", adaptive_ = "on";
    int samples_ = BenchSpec{}.referenceSamples, frames_ = 50;
    bool json_ = false;
    CLI::Option* samplesOption_ = nullptr;
    CLI::Option* adaptiveOption_ = nullptr;
};

} // namespace

std::unique_ptr<Command> evalCommand() { return std::make_unique<EvalCommand>(); }

} // namespace shadowlab::cli
