// The application: one GL context, one scene, the techniques found in the plugin folder, and the
// frame that ties them together. main.cpp turns command lines into calls on this class.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "camera.h"
#include "groundtruth/groundtruth.h"
#include "groundtruth/metrics.h"
#include "groundtruth/reference_cache.h"
#include "groundtruth/texel_footprint.h"
#include "plugin/host_params.h"
#include "plugin/params.h"
#include "plugin/technique_runtime.h"
#include "render/gpu_reference.h"
#include "render/gpu_timer.h"
#include "render/renderer.h"
#include "render/shadow_map_views.h"
#include "render/shader_library.h"
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
    bool depthPrepass = false;                          // host depth pre-pass, then main pass EQUAL
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
    Image heatmap() const;              // errorHeatmap() as an RGBA image
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
    bool loadScene(const std::string& nameOrPath, const std::map<std::string, double>& parameters, std::string& error);

    // "--set key=value" for `technique` (keys may also name another technique: "pcf.kernel=5").
    bool applyAssignments(const std::vector<std::string>& assignments, const std::string& technique, std::string& error);

    // One frame of `technique` into the main targets; timers advance. Timed frames write the
    // colour target only; FrameOutputs::Accuracy adds visibility, position and normal.
    bool renderFrame(const std::string& technique, std::string& error, FrameOutputs outputs = FrameOutputs::Colour);
    // The last frame's main pass again, same frame context and shadow maps, writing the accuracy
    // targets; not timed. evaluate() and the visibility view call it when the frame had none.
    bool renderAccuracyTargets(std::string& error);
    // Host depth pre-pass before every main pass (main pass with depth test EQUAL, no depth write).
    void setDepthPrepass(bool on) { depthPrepass_ = on; }
    bool depthPrepass() const { return depthPrepass_; }
    // Translucent layers evaluate() peels and measures (0 = the opaque surfaces only).
    void setTranslucentLayers(int count) { translucentLayers_ = count; }
    int translucentLayers() const { return translucentLayers_; }
    // After the technique's shadow pass, everything up to and including the main pass: the depth
    // pre-pass when on, the eye-space blur's term and blur passes when host.shadow_blur > 0 (seed
    // 002 sec. 6.3, 9.4.2; render/renderer.h), then the main pass (reading the blurred term when
    // blurred), with host.lighting. `timed`: each pass in its timer scope ("depth pre-pass", "eye
    // blur term", "eye blur", "main"). path_run.cpp uses it for its untimed passes too.
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
    bool measure(const std::string& technique, int warmupFrames, int frames, Measurement& out, std::string& error);
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
    // (re-rendering that frame with the accuracy targets when it was a timed frame).
    bool evaluate(const ReferenceOptions& options, Evaluation& out, std::string& error);
    // Which tracer evaluate() and the reference views use (--reference-device): Embree on the CPU
    // (the default ground truth) or the GPU tracer of issue 27 (render/gpu_reference.h).
    void setReferenceDevice(ReferenceDevice device) { referenceDevice_ = device; }
    ReferenceDevice referenceDevice() const { return referenceDevice_; }
    // Traces the current scene and light for `gbuffer` (loads the Embree module on first use).
    bool traceReference(const GBufferView& gbuffer, const ReferenceOptions& options, std::vector<glm::vec3>& visibility,
                        std::string& error, ReferenceStats* stats = nullptr);
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
    const FrameContext& lastFrame() const { return frame_; }

private:
    void applyLightOverrides();

    AppOptions options_;
    std::unique_ptr<GlBackend> backend_;
    std::unique_ptr<ShaderLibrary> shaders_;
    std::unique_ptr<GpuTimer> timer_;
    std::unique_ptr<Renderer> renderer_;
    ShadowMapViews shadowMapViews_;
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
    bool depthPrepass_ = false;
    int translucentLayers_ = 4;
    bool warnedLayersUnderMsaa_ = false;   // said once per run, not once per measured row
    bool evaluateTranslucentLayers(const ReferenceOptions& options, Evaluation& out, std::string& error);
    // After the technique's translucent-draws hook (SHADOWLAB_EXT_TRANSLUCENT_DRAWS): the state
    // contract, `program` bound, bindMainPass again.
    void rebindAfterTranslucentHook(LoadedTechnique& loaded, const FrameContext& frame, const ParamValues& params,
                                    GLuint program, uint32_t object);
    bool windowed_ = false;
    std::chrono::steady_clock::time_point startTime_ = std::chrono::steady_clock::now();
    double lastCpuFrameMs_ = 0.0;
    std::vector<std::string> lastReloaded_;
    GroundTruthPtr groundTruth_;
    ReferenceDevice referenceDevice_ = ReferenceDevice::Cpu;
    std::unique_ptr<GpuReference> gpuReference_;   // made on first use with the GPU device
    ReferenceCache referenceCache_;
    uint64_t sceneGeneration_ = 0;         // bumped when the scene changes
    uint64_t groundTruthGeneration_ = ~0ull;
};

} // namespace shadowlab
