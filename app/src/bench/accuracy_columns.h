// The accuracy fields of one frame, named as bench rows name them (docs/benchmarks.md): one
// function measures them for both `bench --accuracy` (into the row) and `eval --json` (its
// "bench_columns" object), so the two report the same keys with the same values for the same
// frame (issue 32; test eval_bench_columns).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app.h"

namespace shadowlab {

// "hard" | "soft" | "both" | "auto" (hard for the hard and baseline techniques, else both), the
// meaning of bench's and eval's --reference; false for anything else.
// The one rule for which reference a technique is judged against by default (tour pages, the
// report's heatmaps, the window's "Measure accuracy"): hard for hard and baseline techniques, soft
// for filtered, soft, coloured and reference ones, whose model is a penumbra.
ReferenceOptions::Mode ownReferenceMode(const TechniqueInfo& info);
bool referenceModesFor(const std::string& reference, const TechniqueInfo& info, std::vector<ReferenceOptions::Mode>& modes);

struct AccuracyRequest {
    std::vector<ReferenceOptions::Mode> modes;
    int samples = 1024;      // soft reference rays per pixel
    bool adaptive = true;    // soft reference sampled adaptively
    // The contact band's false light (hard passes, groundtruth/contact_band.h): a shadow ray a
    // pixel more, so bench rows have it only where their spec asks ("contactBand").
    bool contactBand = true;
    int threads = 0;         // the reference's threads (0: every core; ReferenceOptions::threads)
};

// An evaluation as it is measured: its column prefix ("hard_", "soft_own_"), mode and model.
struct AccuracyPass {
    std::string prefix;
    ReferenceOptions::Mode mode;
    TranslucencyModel model;
};

// Evaluates the last frame (App::evaluate) against each mode of `request` and each model the
// technique is judged by (judgedModels: physical, then its own where it differs and the scene has
// a translucent caster), adding the columns to `columns`: translucency_model; per pass <prefix>mae,
// _rmse, _false_shadow, _false_light, _mae_penumbra, _mae_outside_penumbra, _compared_fraction,
// _noise, _mae_r/g/b, the translucent receivers' _translucent_* where the frame has some; for
// the physical passes the view-depth thirds, technique_penumbra_fraction, the texel footprint
// (first pass only) and, soft, the reference's rays and floor. `each` sees every evaluation
// (eval adds its per-layer and per-bin details).
bool addAccuracyColumns(App& app, const TechniqueInfo& info, const AccuracyRequest& request, nlohmann::json& columns,
                        std::string& error,
                        const std::function<void(const AccuracyPass&, const Evaluation&)>& each = {});

// addAccuracyColumns in its two halves, so that a bench row's evaluation can run beside the next
// row's timed frames (bench.cpp): the GL half reads the frame back (GL thread; the frame and the
// app's state are the row's), the CPU half traces and measures it (any thread with the CPU
// reference device, never across App::loadScene; App::evaluateCapture).
struct AccuracyCapture {
    EvaluationInput input;
    std::vector<TranslucencyModel> models;   // judgedModels() when captured
};
bool captureAccuracy(App& app, const TechniqueInfo& info, AccuracyCapture& capture, nlohmann::json& columns,
                     std::string& error);
bool evaluateAccuracy(App& app, const AccuracyRequest& request, const AccuracyCapture& capture, nlohmann::json& columns,
                      std::string& error, const std::function<void(const AccuracyPass&, const Evaluation&)>& each = {});

} // namespace shadowlab
