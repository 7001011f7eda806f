// Accuracy of the last frame against the ray-traced reference (App::evaluate and its two halves,
// see app.h): captureEvaluation() on the GL thread reads the frame's accuracy targets and its
// translucent layers; evaluateCapture() traces the reference for them and computes the metrics,
// from CPU data only, so the window can run it on a worker thread (ui/async_measurement.h) while
// its frame loop keeps drawing. evaluate() is the two at once, as eval and bench use it.
#include "app.h"

#include <algorithm>
#include <chrono>
#include <mutex>

#include "groundtruth/reference_technique.h"
#include "util/log.h"

namespace shadowlab {
namespace {

bool hasSurface(const std::vector<glm::vec4>& positions) {
    return std::any_of(positions.begin(), positions.end(), [](const glm::vec4& p) { return p.w != 0.0f; });
}

// The shadow term, position and normal of one image through `reader`; `texture` names the
// targets (the main pass's or a translucent layer's).
template <typename TextureOf>
void readAccuracyTargets(TextureReader& reader, size_t pixels, EvaluationInput::Targets& into, TextureOf&& texture) {
    const size_t bytes = pixels * sizeof(glm::vec4);
    for (auto [target, image] : {std::pair{MainTarget::Position, &into.positions}, std::pair{MainTarget::Normal, &into.normals},
                                 std::pair{MainTarget::Visibility, &into.visibility}}) {
        image->resize(pixels);
        reader.read(texture(target), GL_RGBA, GL_FLOAT, bytes, image->data());
    }
}

std::vector<glm::vec3> clampedTerm(const std::vector<glm::vec4>& visibility) {
    std::vector<glm::vec3> term(visibility.size());
    for (size_t i = 0; i < visibility.size(); ++i) term[i] = glm::clamp(glm::vec3(visibility[i]), 0.0f, 1.0f);
    return term;
}

} // namespace

size_t EvaluationInput::bytesFor(glm::ivec2 size, int layers) {
    return size_t(std::max(size.x, 0)) * size_t(std::max(size.y, 0)) * sizeof(glm::vec4) * 3 * size_t(1 + std::max(layers, 0));
}

bool App::evaluate(const ReferenceOptions& options, Evaluation& out, std::string& error, const EvaluationParts& parts) {
    EvaluationInput input;
    ImmediateReader reader;
    const auto start = std::chrono::steady_clock::now();
    if (!captureEvaluation(input, reader, error)) return false;
    const double renderSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!evaluateCapture(input, options, out, error, parts)) return false;
    out.renderSeconds = renderSeconds;   // evaluateCapture() starts `out` afresh
    return true;
}

bool App::captureEvaluation(EvaluationInput& input, TextureReader& reader, std::string& error) {
    if (!renderAccuracyTargets(error)) return false;
    LoadedTechnique* loaded = techniques_->get(lastTechnique_, error);
    if (!loaded) return false;
    const glm::ivec2 size = renderer_->size();
    input = EvaluationInput{};
    input.size = size;
    input.light = light_;
    input.camera = camera_.info(size);
    input.frame = frame_;
    input.sceneGeneration = sceneGeneration_;
    input.shadowMaps = loaded->host().shadowMaps();
    for (ShadowMapInfo& map : input.shadowMaps) {
        // The plugin's pointers are valid during its report only; the footprint needs neither.
        map.label = nullptr;
        map.focusBodyEdges = nullptr;
        map.focusBodyEdgeCount = 0;
    }
    const size_t pixels = size_t(size.x) * size_t(size.y);
    readAccuracyTargets(reader, pixels, input.opaque, [&](MainTarget target) { return renderer_->target(target); });
    return captureTranslucentLayers(*loaded, input, reader, error);
}

// The translucent receivers (seed 001 sec. 5.3.3): the translucent surfaces in front of the opaque
// ones peeled from the camera, each with the technique's shadow term, position and normal.
bool App::captureTranslucentLayers(LoadedTechnique& loaded, EvaluationInput& input, TextureReader& reader, std::string& error) {
    // The built-in reference draws a screen texture traced from the opaque surfaces: it has no
    // shadow term of its own for a translucent layer to compare.
    if (translucentLayers_ <= 0 || lastTechnique_ == referenceDescriptor().id) return true;
    if (renderer_->msaaSamples() > 0) {
        // The peel reads the single-sample opaque depth, which a multisampled main pass leaves unwritten.
        if (!warnedLayersUnderMsaa_ &&
            std::any_of(scene_->materials.begin(), scene_->materials.end(), [](const Material& m) { return m.translucent(); })) {
            logWarning("translucent receivers are not measured with MSAA on (--msaa 0 measures them)");
            warnedLayersUnderMsaa_ = true;
        }
        return true;
    }
    const GLuint program = loaded.translucentLayerProgram(error);
    if (!program) return false;
    const std::vector<double>& values = params_.values(loaded.info());
    const ParamValues params(values.data(), uint32_t(values.size()));
    const size_t pixels = size_t(input.size.x) * size_t(input.size.y);
    renderer_->setView(frame_.camera, frame_.light);
    auto translucentHook = [&](uint32_t object) { rebindAfterTranslucentHook(loaded, frame_, params, program, object); };
    input.layers.reserve(size_t(translucentLayers_));
    for (int k = 0; k < translucentLayers_; ++k) {
        if (loaded.host().hasTranslucentHook()) renderer_->setTranslucentHook(Renderer::translucentHookFor(translucentHook));
        const bool drawn = renderer_->translucentLayer(k, program, [&] { loaded.technique().bindMainPass(frame_, params); });
        renderer_->setTranslucentHook({});
        if (!drawn) break;
        EvaluationInput::Targets& layer = input.layers.emplace_back();
        readAccuracyTargets(reader, pixels, layer, [&](MainTarget target) { return renderer_->layerTarget(target); });
        // Read at once, the peel stops at the first empty layer; read later (the window), every
        // layer is peeled and evaluateCapture() stops there instead.
        if (reader.immediate() && !hasSurface(layer.positions)) {
            input.layers.pop_back();
            break;
        }
    }
    renderer_->applyDefaultState();
    return true;
}

bool App::evaluateCapture(const EvaluationInput& input, const ReferenceOptions& options, Evaluation& out, std::string& error,
                          const EvaluationParts& parts) {
    const glm::ivec2 size = input.size;
    const GBufferView gbuffer{size.x, size.y, input.opaque.positions.data(), input.opaque.normals.data()};
    out = Evaluation{};
    out.width = size.x;
    out.height = size.y;
    out.technique = clampedTerm(input.opaque.visibility);
    out.mask = compareMask(gbuffer, input.light);
    const auto start = std::chrono::steady_clock::now();
    if (!traceReferenceFor(gbuffer, input.light, input.sceneGeneration, options, out.reference, error, &out.referenceStats))
        return false;
    out.traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto metricsStart = std::chrono::steady_clock::now();
    out.metrics = compareVisibility(out.technique, out.reference, out.mask, size.x, size.y);
    addViewDepthThirds(out.metrics, out.technique, out.reference, out.mask, input.opaque.positions.data(), size.x, size.y,
                       input.camera.view, input.camera.nearPlane, input.camera.farPlane);
    if (parts.footprint) out.footprint = measureTexelFootprint(gbuffer, out.mask, input.frame.camera, input.frame.light, input.shadowMaps);
    if (parts.positions) out.positions = input.opaque.positions;
    if (parts.contactBand && options.mode == ReferenceOptions::Mode::Hard) {
        if (const auto bvh = contactBvhFor(input.sceneGeneration)) {
            out.contactBand = contactBand(*bvh, gbuffer, out.mask, input.light);
            const ContactBandMetrics contact = contactBandMetrics(out.contactBand, out.technique, out.reference);
            out.metrics.contactFalseLightRate = contact.falseLightRate;
            out.metrics.contactBandPixels = contact.bandPixels;
        }
    }
    if (options.mode == ReferenceOptions::Mode::Hard) {
        // Issue 28: the error near the hard reference's edges and away from them (groundtruth/edge_band.h).
        const EdgeBandMetrics edges =
            edgeBandMetrics(edgeBand(out.reference, out.mask, size.x, size.y), out.technique, out.reference, out.mask);
        out.metrics.maeEdgeBand = edges.mae;
        out.metrics.maeOffEdgeBand = edges.maeOff;
        out.metrics.edgeBandPixels = edges.bandPixels;
    }
    out.referenceFloor = out.referenceStats.sampleError.empty()
                             ? 0.0
                             : penumbraMean(out.referenceStats.sampleError, out.reference, out.mask, size.x, size.y);
    out.metricsSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - metricsStart).count();
    const auto layersStart = std::chrono::steady_clock::now();
    const bool layers = evaluateLayers(input, options, out, error);
    out.layersSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - layersStart).count();
    return layers;
}

// Each captured translucent layer traced with the same options and compared like the opaque
// image, up to the first empty one; all of them together in translucentMetrics.
bool App::evaluateLayers(const EvaluationInput& input, const ReferenceOptions& options, Evaluation& out, std::string& error) {
    const glm::ivec2 size = input.size;
    // All layers stacked into one image for the combined metrics (a penumbra neighbourhood may
    // reach across the seam between two layers: one row each, negligible).
    std::vector<glm::vec3> allTechnique, allReference;
    std::vector<uint8_t> allMask;
    for (const EvaluationInput::Targets& captured : input.layers) {
        if (!hasSurface(captured.positions)) break;
        const GBufferView gbuffer{size.x, size.y, captured.positions.data(), captured.normals.data()};
        TranslucentLayerEvaluation layer;
        layer.technique = clampedTerm(captured.visibility);
        layer.mask = compareMask(gbuffer, input.light);
        if (!traceReferenceFor(gbuffer, input.light, input.sceneGeneration, options, layer.reference, error)) return false;
        layer.metrics = compareVisibility(layer.technique, layer.reference, layer.mask, size.x, size.y);
        allTechnique.insert(allTechnique.end(), layer.technique.begin(), layer.technique.end());
        allReference.insert(allReference.end(), layer.reference.begin(), layer.reference.end());
        allMask.insert(allMask.end(), layer.mask.begin(), layer.mask.end());
        layer.positions = captured.positions;
        out.translucentLayers.push_back(std::move(layer));
    }
    if (!out.translucentLayers.empty())
        out.translucentMetrics = compareVisibility(allTechnique, allReference, allMask, size.x,
                                                   size.y * int(out.translucentLayers.size()));
    return true;
}

std::shared_ptr<const bvh::Bvh> App::contactBvhFor(uint64_t sceneGeneration) {
    std::lock_guard lock(contactBvhMutex_);
    if (contactBvhGeneration_ != sceneGeneration) {
        // loadScene swaps the scene under the exclusive lock: read it under the shared one. An
        // evaluation of an older scene (the window's worker) gets no band rather than a wrong one.
        std::shared_lock sceneLock(groundTruthMutex_);
        if (sceneGeneration != sceneGeneration_ || !scene_) return nullptr;
        contactBvh_ = std::make_shared<const bvh::Bvh>(bvh::build(*scene_));
        contactBvhGeneration_ = sceneGeneration;
    }
    return contactBvh_;
}

size_t App::plannedTraces(const EvaluationInput& input) {
    size_t traces = 1;
    for (const EvaluationInput::Targets& layer : input.layers) {
        if (!hasSurface(layer.positions)) break;
        ++traces;
    }
    return traces;
}

bool App::traceReference(const GBufferView& gbuffer, const ReferenceOptions& options, std::vector<glm::vec3>& visibility,
                         std::string& error, ReferenceStats* stats) {
    return traceReferenceFor(gbuffer, light_, sceneGeneration_, options, visibility, error, stats);
}

// The ground truth loaded, with the BVH of the scene of `sceneGeneration` (built once per scene).
bool App::groundTruthFor(uint64_t sceneGeneration, std::string& error) {
    std::unique_lock lock(groundTruthMutex_);
    if (!groundTruth_) {
        groundTruth_ = loadGroundTruth(error);
        if (!groundTruth_) return false;
    }
    if (sceneGeneration != sceneGeneration_) {
        error = "the scene changed while the reference was being traced";
        return false;
    }
    if (groundTruthGeneration_ != sceneGeneration) {
        groundTruth_->setScene(*scene_);
        groundTruthGeneration_ = sceneGeneration;
    }
    return true;
}

bool App::traceReferenceFor(const GBufferView& gbuffer, const LightInfo& light, uint64_t sceneGeneration,
                            const ReferenceOptions& options, std::vector<glm::vec3>& visibility, std::string& error,
                            ReferenceStats* stats) {
    TraceControl* control = options.control;
    auto nextTrace = [control](bool finished) {
        if (!control) return;
        control->rowsDone = 0;   // the rows count this trace's
        control->rowsTotal = 0;
        if (finished) ++control->tracesDone;
    };
    nextTrace(false);
    if (referenceDevice_ == ReferenceDevice::Gpu) {
        if (!gpuReference_) gpuReference_ = std::make_unique<GpuReference>(*shaders_);
        const bool traced = gpuReference_->trace(*renderer_, gbuffer, light, options, visibility, stats, error);
        renderer_->applyDefaultState();
        if (!traced) error = "gpu reference: " + error;
        else nextTrace(true);
        return traced;
    }
    try {
        if (!groundTruthFor(sceneGeneration, error)) return false;
        // Every technique of a frame has the same G-buffer: its reference is traced once.
        const ReferenceCache::Key key = ReferenceCache::keyOf(gbuffer, light, options, sceneGeneration);
        {
            std::lock_guard lock(referenceCacheMutex_);
            const ReferenceStats* cachedStats = nullptr;
            if (const auto* cached = referenceCache_.find(key, &cachedStats)) {
                visibility = *cached;
                if (stats) *stats = *cachedStats;
                nextTrace(true);
                return true;
            }
        }
        ReferenceStats traced;
        {
            // Shared: traces of several threads may run at once; setScene waits for them.
            std::shared_lock lock(groundTruthMutex_);
            groundTruth_->trace(gbuffer, light, options, visibility, &traced);
        }
        if (control && control->cancelled()) {
            error = "cancelled";   // an incomplete image: never cached
            return false;
        }
        {
            std::lock_guard lock(referenceCacheMutex_);
            referenceCache_.insert(key, visibility, traced);
        }
        if (stats) *stats = std::move(traced);
        nextTrace(true);
    } catch (const std::exception& e) {
        error = std::string("ground truth: ") + e.what();
        return false;
    }
    return true;
}

Image Evaluation::heatmap() const {
    const auto rgb = errorHeatmap(technique, reference, mask, width, height);
    Image image{width, height, 4, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 255)};
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[i * 4 + size_t(c)] = rgb[i * 3 + size_t(c)];
    return image;
}

} // namespace shadowlab
