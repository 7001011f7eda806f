// Measuring a side of the classroom window against the reference (see session.h); the window's
// frame loop itself is App::runInteractive in app_window.cpp.
#include "ui/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include <GLFW/glfw3.h>

#include "app_paths.h"
#include "ui/tour_player.h"
#include "ui/ui.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/text_file.h"

namespace shadowlab {

MeasurementKey currentMeasurementKey(App& app, const std::string& technique) {
    MeasurementKey key;
    key.scene = app.scene().name;
    key.technique = technique;
    if (const TechniqueInfo* info = app.techniques().find(technique)) key.params = app.params().values(*info);
    key.size = app.renderer().size();
    key.viewProjection = app.camera().info(key.size).viewProjection;
    key.lightDirection = app.light().direction;
    key.lightSize = app.light().size;
    return key;
}

bool describeSide(App& app, const std::string& technique, SideMeasurement& out, std::string& error) {
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info) {
        error = "no technique '" + technique + "'";
        return false;
    }
    out.technique = technique;
    out.label = technique;
    const auto& values = app.params().values(*info);
    for (size_t i = 0; i < info->params.size(); ++i)
        out.label += " " + info->params[i].id + "=" + formatParamValue(info->params[i], values[i]);
    std::string loadError;
    LoadedTechnique* loaded = app.techniques().get(technique, loadError);
    out.gpuBytes = loaded ? loaded->host().gpuBytes() : 0;
    out.key = currentMeasurementKey(app, technique);
    return true;
}

void fillSideFigures(const Evaluation& evaluation, const Image& lit, SideMeasurement& out) {
    out.metrics = evaluation.metrics;
    out.translucentMetrics = evaluation.translucentMetrics;
    out.translucentLayers = evaluation.translucentLayers.size();
    out.traceSeconds = evaluation.traceSeconds;
    out.heatmap = heatmapOverLit(lit, evaluation.technique, evaluation.reference, evaluation.mask);
}

bool measureSide(App& app, const std::string& technique, const ReferenceOptions& options, SideMeasurement& out,
                 std::string& error) {
    if (!app.techniques().find(technique)) {
        error = "no technique '" + technique + "'";
        return false;
    }
    // This side's own frame: the frame before may have been the other side's technique.
    if (!app.renderFrame(technique, error, FrameOutputs::Accuracy)) return false;
    Evaluation evaluation;
    if (!app.evaluate(options, evaluation, error)) return false;
    if (!app.presentView(technique, {}, ~0u, {}, error)) return false;
    if (!describeSide(app, technique, out, error)) return false;
    fillSideFigures(evaluation, app.readDisplay(), out);
    return true;
}

} // namespace shadowlab
