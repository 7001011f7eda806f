// The application: one GL context, one scene, the techniques found in the plugin folder, and the
// frame that ties them together. main.cpp turns command lines into calls on this class.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "camera.h"
#include "groundtruth/contact_band.h"
#include "groundtruth/edge_band.h"
#include "groundtruth/groundtruth.h"
#include "groundtruth/metrics.h"
#include "groundtruth/reference_cache.h"
#include "groundtruth/texel_footprint.h"
#include "plugin/host_params.h"
#include "plugin/params.h"
#include "plugin/technique_runtime.h"
#include "render/depth_prepass_rule.h"
#include "render/gpu_reference.h"
#include "render/gpu_timer.h"
#include "render/renderer.h"
#include "render/depth_range.h"
#include "render/shadow_map_views.h"
#include "render/shader_library.h"
#include "render/texture_readback.h"
#include "scene/scene.h"
#include "util/image.h"
#include "util/stats.h"

namespace shadowlab {

struct InteractiveOptions;   // ui/session.h

struct AppOptions {
    std::string scene;                                  // built-in name or path; empty = default
    std::map<std::string, double> sceneParameters;      // --scene-param count=500
    std::optional<BackendKind> backend;                 // empty = default for this machine
    glm::ivec2 size{1280, 720};
    int msaaSamples = 0;
    std::optional<glm::vec3> lightDirection;            // overrides the scene's (travel direction)
    std::optional<float> lightSize;                     // scene units (degrees for directional)
    std::optional<DepthPrepassMode> depthPrepass;       // --depth-prepass: host.depth_prepass (default auto)
    int translucentLayers = 4;                          // evaluation: translucent receivers peeled, 0-8
    ReferenceDevice referenceDevice = ReferenceDevice::Cpu; // the ground truth: Embree (cpu) or the GPU tracer
};

// One translucent layer of an evaluation (Evaluation::translucentLayers).
struct TranslucentLayerEvaluation {
    std::vector<glm::vec3> technique;   // the technique's shadow term on the layer's surfaces
    std::vector<glm::vec3> reference;
    std::vector<uint8_t> mask;          // compared pixels of the layer
    std::vector<glm::vec4> positions;   // world positions (w = 1 where the layer has a surface)
    AccuracyMetrics metrics;
};

// Which image a frame shows: the lit scene, the shadow term, or one of the technique's debug images.
struct ViewSelection {
    // Footprint, TexelGrid and MapCoverage: the host's views of the maps the technique reported
    // (render/shadow_map_views.h).
    // FocusBody: B's edges (seed 002 eq. 4.2); Kernel: the filter kernel's footprint around the
    // probed pixel (App::setProbePixel, render/kernel_probe.h).
    enum class Kind { Lit, Visibility, DebugImage, ErrorHeatmap, Footprint, TexelGrid, MapCoverage, FocusBody, Kernel } kind = Kind::Lit;
    // Whether showing it needs the accuracy targets (shadow term, position, normal) of the frame.
    bool needsAccuracyTargets() const {
        return kind == Kind::Visibility || kind == Kind::Footprint || kind == Kind::TexelGrid || kind == Kind::MapCoverage ||
               kind == Kind::FocusBody || kind == Kind::Kernel;
    }
    std::string debugImage;
};

// View names as the command line (`render --view`), tours and sessions write them: lit,
// visibility, footprint, texel-grid, coverage, focus-body, kernel, error (the heatmap); any other
// name is a debug image.
ViewSelection viewFromName(const std::string& name);
std::string viewName(const ViewSelection& view);
// Whether `name` is one of the host's own views (not a technique's debug image).
bool isHostViewName(const std::string& name);
// The host's own views, every one, in the order messages list them.
const std::vector<std::string>& hostViewNames();

struct Measurement {
    std::map<std::string, TimingSummary> gpuMs;   // per pass, plus "frame"
    TimingSummary cpuMs;                          // host CPU time per frame (submission, no wait)
    TimingSummary cpuWaitMs;                      // CPU time per frame spent waiting for the GPU
    int framesWaited = 0;                         // frames in which that wait was not zero
    size_t gpuBytes = 0;
    int frames = 0;
    // The GPU frame median's relative 95% half-width (util/stats.h; infinity under 6 frames).
    double frameMedianHalfWidth = 0.0;
    int depthPrepassFrames = 0;                   // timed frames that ran the host depth pre-pass
    std::optional<double> depthComplexity;        // the newest count at the end (DepthPrepassRule)
};

// Accuracy of the last rendered frame against the ray-traced reference.
struct Evaluation {
    AccuracyMetrics metrics;
    std::vector<glm::vec3> technique;   // the technique's shadow term per pixel
    std::vector<glm::vec3> reference;
    std::vector<uint8_t> mask;          // compared pixels
    std::vector<glm::vec4> positions;   // the frame's world positions (w = 1 where drawn): temporal metrics
    int width = 0;
    int height = 0;
    double traceSeconds = 0.0;
    // Where an evaluation's wall time goes (bench rows' seconds_* columns): the untimed re-render
    // with the accuracy targets and its readbacks, the reference (cached or traced), the metrics
    // and the translucent layers.
    double renderSeconds = 0.0;
    double metricsSeconds = 0.0;
    double layersSeconds = 0.0;
    ReferenceStats referenceStats;      // rays, refined pixels, per-pixel sampling error of the reference
    double referenceFloor = 0.0;        // soft: the reference's own penumbra MAE (penumbraMean of its sampleError)
    TexelFootprint footprint;           // m per pixel from the maps the technique reported (none: 0 maps)
    // Translucent receivers (seed 001 sec. 5.3.3, Fig. 5.3.3.A): the translucent surfaces in front
    // of the opaque ones, peeled from the camera (layer 0 nearest), each traced with the same
    // options and compared like the opaque image above, which holds the opaque surfaces only.
    // Empty when the scene has no translucent receiver in view (or MSAA is on). translucentMetrics
    // compares all layers at once (their images stacked); comparedPixels 0 when there are none.
    std::vector<TranslucentLayerEvaluation> translucentLayers;
    AccuracyMetrics translucentMetrics;
    // Against the hard reference only (issue 30; groundtruth/contact_band.h): each compared pixel's
    // class (1 in the contact band, 2 far from contact, 0 between; empty with a soft reference);
    // the band's false-light rate is in metrics.
    std::vector<uint8_t> contactBand;
    Image heatmap() const;              // errorHeatmap() as an RGBA image
};

// The optional parts of an Evaluation (App::evaluateCapture): footprint and positions.
struct EvaluationParts {
    bool footprint = true;
    bool positions = true;
    bool contactBand = true;   // hard passes: the contact band's false light (groundtruth/contact_band.h)
};

// What an evaluation reads from the GPU and the frame (App::captureEvaluation): everything the
// reference and the metrics need, as CPU data, so that App::evaluateCapture may run on another
// thread (the window's measurement, ui/async_measurement.h).
struct EvaluationInput {
    struct Targets {   // one image's accuracy targets, width * height texels each, GL's row order
        std::vector<glm::vec4> positions, normals, visibility;
    };
    glm::ivec2 size{0};
    Targets opaque;
    // The translucent layers peeled, nearest the camera first (read later, empty layers may
    // follow the last one with a surface: evaluateCapture stops at the first empty one).
    std::vector<Targets> layers;
    LightInfo light;                         // App::light() when captured: what the reference is traced for
    CameraInfo camera;                       // the camera at the render size (view-depth thirds)
    FrameContext frame;                      // the frame's camera and light (texel footprint)
    std::vector<ShadowMapInfo> shadowMaps;   // what the technique reported (its label and edge pointers dropped)
    uint64_t sceneGeneration = 0;            // the scene it was drawn from (App::loadScene bumps it)
    // Bytes of the targets of one image of `size` and `layers` translucent layers.
    static size_t bytesFor(glm::ivec2 size, int layers);
};

class App {
public:
    App() = default;
    ~App();
    App(const App&) = delete;
    App& operator=(const App&) = delete;

    // Creates the context, loads GL, scans plugins, loads the scene. Sets `badInput` when the
    // failure is the user's input (scene file), so callers can exit with 2 rather than 1.
    bool init(const AppOptions& options, bool windowed, std::string& error, bool& badInput);
    // GL thread. A trace another thread runs for the old scene (evaluateCapture) should be
    // cancelled and joined first: the scene is swapped under the ground truth's exclusive lock,
    // so it would wait for that trace, which then fails ("the scene changed").
    bool loadScene(const std::string& nameOrPath, const std::map<std::string, double>& parameters, std::string& error);

    // "--set key=value" for `technique` (keys may also name another technique: "pcf.kernel=5").
    bool applyAssignments(const std::vector<std::string>& assignments, const std::string& technique, std::string& error);

    // One frame of `technique` into the main targets; timers advance. Timed frames write the
    // colour target only; FrameOutputs::Accuracy adds visibility, position and normal.
    bool renderFrame(const std::string& technique, std::string& error, FrameOutputs outputs = FrameOutputs::Colour);
    // A side-by-side comparison: the frames rendered from beginSharedView(techniques) to
    // endSharedView() show one camera and scene, so they share one camera pre-pass. The first of
    // them that needs one draws the kind the union of their flags asks for (the full pass when any
    // needs it, else depth only) and the later ones reuse it; each technique's extension still
    // shows only what it asked for. SharedView (below) ends it at the end of a scope.
    void beginSharedView(const std::vector<std::string>& techniques);
    void endSharedView() { sharedView_ = {}; }
    // The last frame's main pass again, same frame context and shadow maps, writing the accuracy
    // targets; not timed. evaluate() and the visibility view call it when the frame had none.
    bool renderAccuracyTargets(std::string& error);
    // The host depth pre-pass (main pass with depth test EQUAL, no depth write): off, on, or auto
    // (render/depth_prepass_rule.h), stored as the host parameter host.depth_prepass.
    void setDepthPrepassMode(DepthPrepassMode mode) { params_.values(hostParams())[kHostDepthPrepass] = double(mode); }
    DepthPrepassMode depthPrepassMode() { return DepthPrepassMode(int(hostValues()[kHostDepthPrepass])); }
    // host.contact_shadows > 0: the frame runs the camera depth pre-pass and the contact march.
    bool contactShadowsOn() { return hostValues()[kHostContactShadows] > 0.0; }
    // Whether the last frame ran the pre-pass (what `auto` decided, or what on/off imposed).
    bool depthPrepassActive() const { return prepassThisFrame_; }
    // The depth complexity measured so far and auto's decision (updated in every renderFrame()).
    const DepthPrepassRule& depthPrepassRule() const { return depthPrepassRule_; }
    // Translucent layers evaluate() peels and measures (0 = the opaque surfaces only).
    void setTranslucentLayers(int count) { translucentLayers_ = count; }
    int translucentLayers() const { return translucentLayers_; }
    // After the technique's shadow pass, everything up to and including the main pass: the depth
    // pre-pass when on, the eye-space blur's term and blur passes when host.shadow_blur > 0 (seed
    // 002 sec. 6.3, 9.4.2; render/renderer.h), the contact shadows' march when
    // host.contact_shadows > 0 (issue 30), then the main pass (reading the blurred term when
    // blurred, taking the minimum with the contact term when on), with host.lighting. `timed`: each
    // pass in its timer scope ("depth pre-pass", "eye blur term", "eye blur", "contact shadows",
    // "main"). path_run.cpp uses it for its untimed passes too.
    bool runMainPasses(LoadedTechnique& loaded, const FrameContext& frame, const ParamValues& params, FrameOutputs outputs,
                       bool timed, std::string& error);
    // The host's parameters (plugin/host_params.h) as stored: host.shadow_blur, ...
    const std::vector<double>& hostValues() { return params_.values(hostParams()); }
    // Shows `view` of the last frame in the display texture (or the window when framebuffer = 0).
    bool presentView(const std::string& technique, const ViewSelection& view, GLuint framebuffer, glm::ivec2 viewport,
                     std::string& error);
    Image readDisplay() { return renderer_->readDisplay(); }
    // The pixel the kernel view probes, in main-target pixels from the top left (as images and
    // the mouse count); none: nothing probed. The probe is measured when the view is drawn.
    void setProbePixel(std::optional<glm::ivec2> pixel) { probePixel_ = pixel; }
    // A pixel worth probing when none is given: of a frame of `technique`, the drawn pixel on a
    // shadow edge (shadow term between 0.1 and 0.9, or a hard step of more than half to a
    // neighbour) nearest the image's centre, from the top left; none when the frame has no edge.
    // Reads the frame back (a slide's set-up, never the frame loop).
    std::optional<glm::ivec2> shadowEdgePixel(const std::string& technique);
    std::optional<glm::ivec2> probePixel() const { return probePixel_; }
    // The footprint of the last kernel view drawn (valid = false with its problem otherwise).
    const KernelProbe& lastProbe() const { return lastProbe_; }
    // Measures the kernel of `technique`'s last frame at the probed pixel (accuracy targets current).
    KernelProbe probeKernel(const std::string& technique, std::string& error);
    // The host views that apply to `technique` after its last frame, by what it reported: the
    // map views, focus-body, kernel, and its debug images ("footprint, texel-grid, ...").
    std::string debugViewsOf(const std::string& technique);
    // The one check of a view name for `render --view`, tours and sessions: "" when `view` is a
    // host view or one of `technique`'s debug images (a frame of it is drawn first when it has
    // drawn none, since plugins register their images when they create them), else
    // "view 'X': T has no such view (views: <every host view>, <every debug image of T>)".
    // `extraViews` are views only the caller has (render's "reference").
    std::string viewProblem(const std::string& technique, const std::string& view,
                            const std::vector<std::string>& extraViews = {});
    // Warm-up frames, then `frames` timed frames; waits for the GPU only at the end.
    // `stop`: stop timing early once the GPU frame time is stable (bench specs' stableWithin).
    bool measure(const std::string& technique, int warmupFrames, int frames, Measurement& out, std::string& error,
                 const TimingStop& stop = {});
    // The classroom window (ui/session.cpp): in the GLFW window, or with a headless backend in
    // an offscreen framebuffer of the same layout (then options.frames must be > 0). Returns the
    // exit code: 0, or 1 when a screenshot asked for could not be written.
    int runInteractive(const InteractiveOptions& options);
    // Headless: a new size for the main targets (the camera's aspect follows).
    bool setRenderSize(glm::ivec2 size, std::string& error);
    // Ids hot-reloaded during the last renderFrame() (for reload-latency measurement).
    const std::vector<std::string>& lastReloaded() const { return lastReloaded_; }
    // The floor a shadow pass is measured against: a bare depth-only pass of the same casters,
    // from the host's fitted light space, at resolution x resolution (no bias, no culling).
    bool measureDepthFloor(int resolution, int warmupFrames, int frames, Measurement& out, std::string& error);
    // Compares the last frame's shadow term with the reference traced from its own G-buffer
    // (re-rendering that frame with the accuracy targets when it was a timed frame):
    // captureEvaluation() with an ImmediateReader, then evaluateCapture().
    bool evaluate(const ReferenceOptions& options, Evaluation& out, std::string& error, const EvaluationParts& parts = {});
    // The GL half, GL thread: the last frame's accuracy targets (re-rendered when it was timed),
    // its translucent layers peeled, and the frame's light, camera and reported maps, read through
    // `reader` into `input` (ImmediateReader: filled on return; PixelBufferReadback: once its
    // fence has signalled and it delivered, with every layer up to translucentLayers() peeled).
    bool captureEvaluation(EvaluationInput& input, TextureReader& reader, std::string& error);
    // The CPU half: the reference traced for `input` (options.control reports progress and can
    // cancel) and the metrics. With the CPU reference device any thread may call it while the GL
    // thread draws, but never across loadScene() (the window joins its measurement first); with
    // the GPU device, the GL thread only.
    // `parts` leaves out what a caller does not read (bench rows: the footprint after the first
    // pass, since it depends on the capture and not on the reference; the positions' copy).
    bool evaluateCapture(const EvaluationInput& input, const ReferenceOptions& options, Evaluation& out, std::string& error,
                         const EvaluationParts& parts = {});
    // The traces evaluateCapture() will run for `input` (the opaque image and each layer with a
    // surface): the window's progress counts them.
    static size_t plannedTraces(const EvaluationInput& input);
    // Which tracer evaluate() and the reference views use (--reference-device): Embree on the CPU
    // (the default ground truth) or the GPU tracer of issue 27 (render/gpu_reference.h).
    void setReferenceDevice(ReferenceDevice device) { referenceDevice_ = device; }
    ReferenceDevice referenceDevice() const { return referenceDevice_; }
    // Traces the current scene and light for `gbuffer` (loads the Embree module on first use).
    bool traceReference(const GBufferView& gbuffer, const ReferenceOptions& options, std::vector<glm::vec3>& visibility,
                        std::string& error, ReferenceStats* stats = nullptr);
    // The same for a light and scene generation captured earlier (EvaluationInput). Thread-safe
    // with the CPU device: the ground truth is loaded and its BVH built under an exclusive lock,
    // traces share it, the cache has its own lock; a cancelled trace (options.control) fails
    // with "cancelled" and is not cached.
    bool traceReferenceFor(const GBufferView& gbuffer, const LightInfo& light, uint64_t sceneGeneration,
                           const ReferenceOptions& options, std::vector<glm::vec3>& visibility, std::string& error,
                           ReferenceStats* stats = nullptr);
    // The traces of this run, shared by every technique measured on the same G-buffer, light and
    // options (groundtruth/reference_cache.h); `enabled = false` traces every time.
    ReferenceCache& referenceCache() { return referenceCache_; }

    GlBackend& backend() { return *backend_; }
    Renderer& renderer() { return *renderer_; }
    ShaderLibrary& shaders() { return *shaders_; }
    TechniqueManager& techniques() { return *techniques_; }
    ParamStore& params() { return params_; }
    GpuTimer& timer() { return *timer_; }
    const Scene& scene() const { return *scene_; }
    LightInfo& light() { return light_; }
    CameraController& camera() { return camera_; }
    const AppOptions& options() const { return options_; }
    std::string firstTechnique() const;
    double lastCpuFrameMs() const { return lastCpuFrameMs_; }
    // The least warm-up time before timed frames: longer after a pause in which the GPU may have
    // lowered its clocks (app.cpp, kLongPauseSeconds).
    double warmupSeconds() const;
    const FrameContext& lastFrame() const { return frame_; }

private:
    void applyLightOverrides();
    void setCameraFloor();
    void presentDebugImage(const DebugImage& image, GLuint fbo, glm::ivec2 size);
    // The camera pre-pass this frame's flags ask for, timed, or the shared view's (beginSharedView).
    void cameraPrepassFor(uint32_t flags);
    struct SharedPrepass {
        bool active = false;
        uint32_t flags = 0;                // the union of the shared techniques' flags
        bool drawn = false;                // the pre-pass of the union is in the targets
        glm::mat4 viewProjection{0.0f};    // of the frame that drew it (reused only for the same)
        glm::ivec2 size{0};
    } sharedView_;

    AppOptions options_;
    std::unique_ptr<GlBackend> backend_;
    std::unique_ptr<ShaderLibrary> shaders_;
    std::unique_ptr<GpuTimer> timer_;
    std::unique_ptr<Renderer> renderer_;
    ShadowMapViews shadowMapViews_;
    std::unique_ptr<DepthRange> depthRange_;   // the `shadow map` view's stretch (render/depth_range.h)
    bool inWindowLoop_ = false;                // runInteractive: read the depth range without waiting
    std::optional<glm::ivec2> probePixel_;
    KernelProbe lastProbe_;
    std::vector<float> probeDepths_;       // the probed map's depths (read back when the view is drawn)
    std::unique_ptr<TechniqueManager> techniques_;
    std::unique_ptr<Scene> scene_;
    ParamStore params_;
    LightInfo light_{};
    CameraController camera_;
    // What every technique call of a frame is told (shadowlab/technique.h FrameContext).
    FrameContext frame_{};
    uint64_t framesRendered_ = 0;
    std::string lastTechnique_;            // of the last renderFrame() (renderAccuracyTargets)
    DepthPrepassRule depthPrepassRule_;
    bool prepassThisFrame_ = false;        // this frame's decision, kept by its accuracy re-render
    void decideDepthPrepass();             // polls the overdraw count, then decides this frame
    int translucentLayers_ = 4;
    bool warnedLayersUnderMsaa_ = false;   // said once per run, not once per measured row
    bool captureTranslucentLayers(LoadedTechnique& loaded, EvaluationInput& input, TextureReader& reader, std::string& error);
    bool evaluateLayers(const EvaluationInput& input, const ReferenceOptions& options, Evaluation& out, std::string& error);
    bool groundTruthFor(uint64_t sceneGeneration, std::string& error);
    // After the technique's translucent-draws hook (SHADOWLAB_EXT_TRANSLUCENT_DRAWS): the state
    // contract, `program` bound, bindMainPass again.
    void rebindAfterTranslucentHook(LoadedTechnique& loaded, const FrameContext& frame, const ParamValues& params,
                                    GLuint program, uint32_t object);
    bool windowed_ = false;
    std::chrono::steady_clock::time_point startTime_ = std::chrono::steady_clock::now();
    double lastCpuFrameMs_ = 0.0;
    std::chrono::steady_clock::time_point lastFrameEnd_{};   // when the last frame was submitted (warm-up rule)
    std::vector<std::string> lastReloaded_;
    GroundTruthPtr groundTruth_;
    std::shared_mutex groundTruthMutex_;   // exclusive: loading and setScene; shared: traces
    std::mutex referenceCacheMutex_;
    ReferenceDevice referenceDevice_ = ReferenceDevice::Cpu;
    std::unique_ptr<GpuReference> gpuReference_;   // made on first use with the GPU device
    ReferenceCache referenceCache_;
    uint64_t sceneGeneration_ = 0;         // bumped when the scene changes
    uint64_t groundTruthGeneration_ = ~0ull;
    // The casters' BVH for the contact band (groundtruth/contact_band.h), built once per scene.
    std::shared_ptr<const bvh::Bvh> contactBvhFor(uint64_t sceneGeneration);
    std::mutex contactBvhMutex_;
    std::shared_ptr<const bvh::Bvh> contactBvh_;
    uint64_t contactBvhGeneration_ = ~0ull;
};

} // namespace shadowlab
