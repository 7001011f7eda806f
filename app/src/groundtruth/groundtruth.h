// Ray-traced ground truth: the light visibility a shadow technique should have produced, for each
// pixel of the exact view the rasteriser drew. The host reads back its main pass's G-buffer
// (world positions and normals), hands it to trace(), and compares what the technique rendered
// with the result (metrics.h).
//
// The implementation (Embree 3 on the CPU, app/src/groundtruth/embree/embree_groundtruth.cpp) is a module,
// libshadowlab_groundtruth.so, opened on demand by loadGroundTruth(): the host starts, and times
// techniques, on machines without Embree. Nothing in this header names an Embree type.
//
// Bump SHADOWLAB_GROUNDTRUTH_ABI_VERSION whenever anything in this file (or in scene.h, which the
// module reads through setScene) changes layout or meaning.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

#define SHADOWLAB_GROUNDTRUTH_ABI_VERSION 4u
#define SHADOWLAB_GROUNDTRUTH_ENTRY_SYMBOL "shadowlab_create_groundtruth"
#define SHADOWLAB_GROUNDTRUTH_MODULE "libshadowlab_groundtruth.so"

namespace shadowlab {

// A G-buffer as the host reads it back (or as tracePrimary() makes it). Row-major, width * height
// texels, row 0 first; rows are treated uniformly, so GL's bottom-up order needs no flip.
struct GBufferView {
    int width = 0;
    int height = 0;
    const glm::vec4* positions = nullptr; // world space; w = 1 where geometry was drawn, 0 background
    const glm::vec4* normals = nullptr;   // world-space unit shading normals (xyz; w ignored)
};

// Progress and cancellation of a trace that runs on another thread than its caller's UI (the
// window's "Measure accuracy", issue 32). The module adds the rows it plans to rowsTotal when a
// pass starts (the adaptive soft reference has two passes over the image) and 1 to rowsDone per
// row finished; once `cancel` is set its threads take no new row and trace() returns early with
// an incomplete image, which the caller must drop (App::traceReference never caches it).
// tracesDone is the host's: traces finished of a measurement that runs several.
struct TraceControl {
    std::atomic<uint64_t> rowsDone{0};
    std::atomic<uint64_t> rowsTotal{0};
    std::atomic<bool> cancel{false};
    std::atomic<int> tracesDone{0};
    bool cancelled() const { return cancel.load(std::memory_order_relaxed); }
};

struct ReferenceOptions {
    // Hard: one shadow ray per pixel, to the light's centre (size ignored).
    // Soft: samplesPerPixel stratified rays over the emitter (disc of radius light.size, or a
    //       cone of angular radius light.size for directional lights); visibility is the visible
    //       fraction of the emitter's area (solid angle for directional lights), unweighted by
    //       cosine or distance, i.e. what PCSS-like techniques estimate. The N samples are a
    //       jittered nx x ny grid of strata (nx = floor(sqrt N), the N - nx*ny left over uniform);
    //       the jitter of stratum k at pixel p is a hash of (p, seed, k), so any subset of the
    //       strata, traced in any order, gives the same samples.
    enum class Mode { Hard, Soft } mode = Mode::Hard;
    int samplesPerPixel = 64;
    uint32_t seed = 1;         // with the pixel index, fixes every sample: same image for any thread count
    // What translucent casters do to a shadow ray (TranslucencyModel in technique.h): the product
    // over the translucent caster surfaces crossed of crossingFactor(model, alpha, t), 0 at the
    // first opaque one. Opaque: every caster, translucent or not, blocks. eval and bench trace
    // Physical always, and the technique's own model where it differs (docs/benchmarks.md).
    TranslucencyModel model = TranslucencyModel::Opaque;
    int threads = 0;           // 0 = std::thread::hardware_concurrency()

    // Soft, adaptive: every pixel first traces `firstBatch` of the N strata (half on the emitter's
    // rim, half spread over its area). A pixel whose first-batch rays all agree keeps that value
    // unless some pixel within `refineRadius` pixels (a square window) disagreed; every other
    // pixel traces all N strata, exactly as the uniform reference does, so a refined pixel equals
    // the uniform N-ray pixel bit for bit. Ignored (uniform) when firstBatch >= N or N < 4. The
    // rule and the case it can miss are explained in the module (embree_groundtruth.cpp).
    bool adaptive = false;
    int firstBatch = 32;
    int refineRadius = 2;

    // Progress and cancellation (TraceControl); null: neither. Not part of what is traced.
    TraceControl* control = nullptr;
};

// What a trace did, and how far the soft reference is from its own limit (N -> infinity).
struct ReferenceStats {
    int samplesPerPixel = 1;        // N of the estimate: 1 for hard, the rays of a refined (or uniform) pixel
    bool adaptive = false;          // adaptive sampling was used (ReferenceOptions::adaptive and applicable)
    int firstBatch = 0;             // rays of the first batch (adaptive only)
    size_t tracedPixels = 0;        // pixels facing the light (compareMask)
    size_t refinedPixels = 0;       // of those, the ones traced with all N strata (uniform: all)
    uint64_t shadowRays = 0;        // emitter samples traced (below the horizon not counted), first batches included
    // Soft only (else empty), per pixel: the expected |error| of the pixel's own sampling,
    // sqrt(2/pi) * an estimate of its standard error (collapsed strata: the pixel's strata in
    // adjacent pairs, the smaller of the row-wise and the column-wise pairing); 0 for a pixel
    // that stopped after a unanimous first batch. penumbraMean() (metrics.h) averages it over the
    // penumbra pixels: the reference's own penumbra MAE, the floor under soft metrics.
    std::vector<float> sampleError;
};

class IGroundTruth {
public:
    virtual ~IGroundTruth() = default;

    // Builds the BVH of `scene` (all objects; those with castsShadow = false are seen by primary
    // rays only). Call once per scene and keep the instance across frames and techniques; a
    // second call replaces the BVH. The scene is copied: it may be destroyed afterwards.
    // Throws std::runtime_error on an invalid scene or an Embree failure.
    virtual void setScene(const Scene& scene) = 0;

    // Visibility of `light` for every texel of `gbuffer`, resized to width * height: grey
    // (v, v, v) in [0, 1], or the rgb transmittance of options.model. Texels outside
    // compareMask() (background, N.L <= 0, outside a spot cone) are 0.
    // With `stats`, also what was traced and the per-pixel sampling error (ReferenceStats).
    virtual void trace(const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
                       std::vector<glm::vec3>& visibility, ReferenceStats* stats = nullptr) = 0;

    // A CPU G-buffer of the view: one ray per pixel centre from cameraPos through the point that
    // inverse(viewProjection) maps the pixel to (row 0 = bottom, as GL). Positions as GBufferView
    // (w = 0 where the ray escapes); normals are the interpolated vertex normals, as the main
    // pass writes them. For tests, benchmarks and for checking the rasteriser's G-buffer.
    virtual void tracePrimary(const glm::mat4& viewProjection, glm::vec3 cameraPos, int width, int height,
                              std::vector<glm::vec4>& positions, std::vector<glm::vec4>& normals) = 0;

    // World-space distance shadow-ray origins are pushed off the surface (see the module).
    virtual float rayOffset() const = 0;
};

// Deletes the instance inside the module, then drops its reference to the module handle, so the
// library outlives every instance it created.
struct GroundTruthDeleter {
    std::shared_ptr<void> module;
    void operator()(IGroundTruth* groundTruth) const noexcept { delete groundTruth; }
};
using GroundTruthPtr = std::unique_ptr<IGroundTruth, GroundTruthDeleter>;

// Opens libshadowlab_groundtruth.so: beside the executable, then beside the plugin directory
// (pluginDir()/..), then by plain name (LD_LIBRARY_PATH). Null with `error` set when it is
// missing, fails to load or was built for another ABI version.
GroundTruthPtr loadGroundTruth(std::string& error);

// ---------------------------------------------------------------------------------------------
// Translucency models (TranslucencyModel, technique.h), shared by the module and the host.

// "opaque", "coverage", "physical", "modified", "ignore": names in bench columns, eval and the UI.
inline const char* translucencyModelName(TranslucencyModel model) {
    switch (model) {
    case TranslucencyModel::Opaque: return "opaque";
    case TranslucencyModel::Coverage: return "coverage";
    case TranslucencyModel::Physical: return "physical";
    case TranslucencyModel::ModifiedTranslucent: return "modified";
    case TranslucencyModel::Ignore: return "ignore";
    }
    return "opaque";
}

// What one translucent surface of coverage `alpha` and transmission colour `t` lets through
// (both clamped to [0, 1]), per model. Seed 001: stochastic shadow maps keep a caster's fragment
// with probability alpha (sec. 2.1.2), so 1 - a of the light passes; CSSM2 stops a photon of
// channel c with probability p = a (1 - t) (sec. 2.1.3), so 1 - p = (1 - a) + a t passes; the
// modified translucent shadows write (1 - a) t (sec. 4.2.1), which is not 1 as a -> 0.
inline glm::vec3 crossingFactor(TranslucencyModel model, float alpha, glm::vec3 t) {
    const float a = alpha < 0.0f ? 0.0f : (alpha > 1.0f ? 1.0f : alpha);
    t = glm::clamp(t, 0.0f, 1.0f);
    switch (model) {
    case TranslucencyModel::Opaque: return glm::vec3(0.0f);
    case TranslucencyModel::Coverage: return glm::vec3(1.0f - a);
    case TranslucencyModel::Physical: return (1.0f - a) + a * t;
    case TranslucencyModel::ModifiedTranslucent: return (1.0f - a) * t;
    case TranslucencyModel::Ignore: return glm::vec3(1.0f);
    }
    return glm::vec3(0.0f);
}

// True when some shadow caster of `scene` is translucent: only then do the models differ.
inline bool hasTranslucentCaster(const Scene& scene) {
    for (const SceneObject& object : scene.objects)
        if (object.castsShadow && object.material < scene.materials.size() && scene.materials[object.material].translucent())
            return true;
    return false;
}

// The references a technique declaring `own` is judged against, first the one reported in the
// plain columns: Physical always, then `own` where it differs and the scene has a translucent
// caster (without one, every model traces the same image).
inline std::vector<TranslucencyModel> judgedModels(TranslucencyModel own, const Scene& scene) {
    std::vector<TranslucencyModel> models{TranslucencyModel::Physical};
    if (own != TranslucencyModel::Physical && hasTranslucentCaster(scene)) models.push_back(own);
    return models;
}

// ---------------------------------------------------------------------------------------------
// Which pixels have a defined answer, shared by the module (which traces only these) and the
// metrics (which compare only these).

// Unit vector from `p` towards the light's centre.
inline glm::vec3 directionToLight(const LightInfo& light, glm::vec3 p) {
    if (light.type == LightType::Directional) return -light.direction;
    const glm::vec3 toLight = light.position - p;
    const float length = glm::length(toLight);
    return length > 0.0f ? toLight / length : -light.direction;
}

// Drawn geometry whose (unflipped) normal faces the light, inside the cone of a spot light.
inline bool facesLight(const glm::vec4& position, const glm::vec4& normal, const LightInfo& light) {
    if (position.w == 0.0f) return false;
    // A non-finite position or normal (a G-buffer texel no pass wrote, or NaN from a shader) would
    // become a NaN shadow ray, on which Embree's robust traversal was seen to spin forever
    // (`point-light`, lispsm after csm): such a pixel faces no light and traces no ray.
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(position[c]) || !std::isfinite(normal[c])) return false;
    const glm::vec3 p(position);
    const glm::vec3 l = directionToLight(light, p);
    if (glm::dot(glm::vec3(normal), l) <= 0.0f) return false;
    if (light.type == LightType::Spot && glm::dot(-l, light.direction) <= std::cos(light.spotOuterAngle))
        return false;
    return true;
}

} // namespace shadowlab

// The module's only export. Returns null for a mismatched abiVersion.
//   extern "C" shadowlab::IGroundTruth* shadowlab_create_groundtruth(uint32_t abiVersion);
