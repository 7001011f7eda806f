// The accuracy columns shared by bench rows and eval --json (see accuracy_columns.h).
#include "bench/accuracy_columns.h"

#include <chrono>

#include "render/texture_readback.h"

namespace shadowlab {
namespace {

constexpr const char* kChannels[] = {"r", "g", "b"};
constexpr const char* kThirds[] = {"near", "mid", "far"};

// The columns of one evaluation.
void addPassColumns(const AccuracyPass& pass, const Evaluation& evaluation, nlohmann::json& row) {
    const std::string& prefix = pass.prefix;
    const AccuracyMetrics& a = evaluation.metrics;
    row[prefix + "mae"] = a.mae;
    row[prefix + "rmse"] = a.rmse;
    row[prefix + "false_shadow"] = a.falseShadowRate;
    row[prefix + "false_light"] = a.falseLightRate;
    row[prefix + "mae_penumbra"] = a.maePenumbra;
    row[prefix + "mae_outside_penumbra"] = a.maeOutsidePenumbra;
    row[prefix + "compared_fraction"] = a.comparedFraction;
    row[prefix + "noise"] = a.noiseEnergy;
    // Per channel on the opaque receivers, and the translucent receivers (peeled layers; seed 001
    // sec. 5.3.3) where the frame has some in view.
    for (int c = 0; c < 3; ++c) row[prefix + "mae_" + kChannels[c]] = a.maePerChannel[c];
    if (!evaluation.translucentLayers.empty()) {
        const AccuracyMetrics& t = evaluation.translucentMetrics;
        row[prefix + "translucent_mae"] = t.mae;
        for (int c = 0; c < 3; ++c) row[prefix + "translucent_mae_" + kChannels[c]] = t.maePerChannel[c];
        row[prefix + "translucent_false_shadow"] = t.falseShadowRate;
        row[prefix + "translucent_false_light"] = t.falseLightRate;
        row[prefix + "translucent_noise"] = t.noiseEnergy;
        row[prefix + "translucent_pixels"] = t.comparedPixels;
        row[prefix + "translucent_layers"] = evaluation.translucentLayers.size();
    }
    if (pass.model != TranslucencyModel::Physical) return;
    // By view-depth third (perspective aliasing: seed 002 sec. 3.1).
    for (size_t t = 0; t < 3; ++t) row[prefix + "mae_" + kThirds[t]] = a.maeByViewDepth[t];
    if (evaluation.footprint.maps > 0 && !row.contains("footprint_median")) {
        const TexelFootprint& f = evaluation.footprint;
        row["footprint_median"] = f.median;
        row["footprint_p95"] = f.p95;
        row["footprint_max"] = f.max;
        row["footprint_undersampled"] = f.undersampledFraction;
        for (size_t t = 0; t < 3; ++t) row[std::string("footprint_") + kThirds[t]] = f.medianByViewDepth[t];
        row["projection_ratio_median"] = f.projectionMedian;
        row["shadow_maps"] = f.maps;
    }
    row["technique_penumbra_fraction"] = a.techniquePenumbraFraction;
    if (!evaluation.contactBand.empty()) {
        // Issue 30: the false light within kContactBandDistance of a caster (groundtruth/contact_band.h).
        row[prefix + "contact_false_light"] = a.contactFalseLightRate;
        row[prefix + "contact_band_pixels"] = a.contactBandPixels;
    }
    if (pass.mode == ReferenceOptions::Mode::Hard) {
        // Issue 28: the error near hard edges and away from them (groundtruth/edge_band.h).
        row[prefix + "edge_band_mae"] = a.maeEdgeBand;
        row[prefix + "off_edge_mae"] = a.maeOffEdgeBand;
        row[prefix + "edge_band_pixels"] = a.edgeBandPixels;
    }
    if (pass.mode == ReferenceOptions::Mode::Soft) {
        // The soft reference's own error: soft figures (and differences between them) below
        // about 4x the floor are not resolved.
        const ReferenceStats& r = evaluation.referenceStats;
        row["soft_reference_rays"] = r.samplesPerPixel;
        row["soft_reference_adaptive"] = r.adaptive;
        row["soft_reference_floor"] = evaluation.referenceFloor;
        row["soft_reference_refined_fraction"] = r.tracedPixels ? double(r.refinedPixels) / double(r.tracedPixels) : 0.0;
    }
}

} // namespace

ReferenceOptions::Mode ownReferenceMode(const TechniqueInfo& info) {
    const bool hard = info.category == "hard" || info.category == "baseline";
    return hard ? ReferenceOptions::Mode::Hard : ReferenceOptions::Mode::Soft;
}

bool referenceModesFor(const std::string& reference, const TechniqueInfo& info, std::vector<ReferenceOptions::Mode>& modes) {
    using Mode = ReferenceOptions::Mode;
    if (reference == "hard") modes = {Mode::Hard};
    else if (reference == "soft") modes = {Mode::Soft};
    else if (reference == "both") modes = {Mode::Hard, Mode::Soft};
    else if (reference == "auto")
        modes = ownReferenceMode(info) == Mode::Hard ? std::vector<Mode>{Mode::Hard} : std::vector<Mode>{Mode::Hard, Mode::Soft};
    else return false;
    return true;
}

bool captureAccuracy(App& app, const TechniqueInfo& info, AccuracyCapture& capture, nlohmann::json& columns,
                     std::string& error) {
    // Physical in the plain columns (hard_mae, ...), the technique's own model where it differs
    // in hard_own_* / soft_own_* (docs/benchmarks.md, "Translucency models").
    columns["translucency_model"] = translucencyModelName(info.translucencyModel);
    capture.models = judgedModels(info.translucencyModel, app.scene());
    // One re-render and readback serves every pass: the passes differ in the reference only.
    ImmediateReader reader;
    const auto captureStart = std::chrono::steady_clock::now();
    if (!app.captureEvaluation(capture.input, reader, error)) return false;
    columns["seconds_accuracy_render"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - captureStart).count();
    return true;
}

bool evaluateAccuracy(App& app, const AccuracyRequest& request, const AccuracyCapture& capture, nlohmann::json& columns,
                      std::string& error, const std::function<void(const AccuracyPass&, const Evaluation&)>& each) {
    bool footprintDone = false;
    for (const ReferenceOptions::Mode mode : request.modes) {
        for (const TranslucencyModel model : capture.models) {
            ReferenceOptions options;
            options.mode = mode;
            options.samplesPerPixel = request.samples;
            options.adaptive = request.adaptive;
            options.model = model;
            options.threads = request.threads;
            Evaluation evaluation;
            // The footprint depends on the capture only; addPassColumns reads it from the
            // first physical pass.
            const bool withFootprint = !footprintDone && model == TranslucencyModel::Physical;
            if (!app.evaluateCapture(capture.input, options, evaluation, error, {withFootprint, false, request.contactBand}))
                return false;
            footprintDone = footprintDone || withFootprint;
            // Where the evaluation's wall time went (docs/benchmarks.md, seconds_row).
            columns["seconds_reference"] = columns.value("seconds_reference", 0.0) + evaluation.traceSeconds;
            columns["seconds_metrics"] = columns.value("seconds_metrics", 0.0) + evaluation.metricsSeconds;
            columns["seconds_translucent_layers"] =
                columns.value("seconds_translucent_layers", 0.0) + evaluation.layersSeconds;
            const AccuracyPass pass{std::string(mode == ReferenceOptions::Mode::Hard ? "hard_" : "soft_") +
                                        (model == TranslucencyModel::Physical ? "" : "own_"),
                                    mode, model};
            addPassColumns(pass, evaluation, columns);
            if (each) each(pass, evaluation);
        }
    }
    return true;
}

bool addAccuracyColumns(App& app, const TechniqueInfo& info, const AccuracyRequest& request, nlohmann::json& columns,
                        std::string& error, const std::function<void(const AccuracyPass&, const Evaluation&)>& each) {
    AccuracyCapture capture;
    return captureAccuracy(app, info, capture, columns, error) && evaluateAccuracy(app, request, capture, columns, error, each);
}

} // namespace shadowlab
