// The application (see app.h). A frame, top to bottom:
//   poll hot reload -> camera and light into the frame uniforms -> (camera pre-pass)
//   -> technique.renderShadows() -> (depth pre-pass) -> host main pass with the technique's
//   shadowTerm() -> present -> (UI) -> swap
// Timed frames write the lit colour only; a frame measured for accuracy re-runs its main pass
// with the accuracy targets, untimed.
#include "util/strings.h"
#include "app.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "groundtruth/reference_technique.h"
#include "plugin/assignments.h"
#include "render/light_space.h"
#include "shadowlab/kit/depth_map_shared.h"
#include "render/render_limits.h"
#include "util/log.h"
#include "util/progress.h"
#include "util/paths.h"

namespace shadowlab {

App::~App() {
    // GL objects go while the context still exists.
    if (techniques_) techniques_->unloadAll();
    techniques_.reset();
    shadowMapViews_.release();
    depthRange_.reset();
    gpuReference_.reset();
    renderer_.reset();
    timer_.reset();
    shaders_.reset();
    backend_.reset();
}

bool App::init(const AppOptions& options, bool windowed, std::string& error, bool& badInput) {
    badInput = false;
    options_ = options;
    // The scene first: a bad scene file is the user's error and needs no GL to report.
    try {
        scene_ = std::make_unique<Scene>(shadowlab::loadScene(options.scene.empty() ? defaultSceneName() : options.scene,
                                                             options.sceneParameters));
    } catch (const SceneError& e) {
        error = e.what();
        badInput = true;
        return false;
    }
    const BackendKind kind = windowed ? BackendKind::Glfw : options.backend.value_or(BackendKind::Egl);
    windowed_ = windowed;
    backend_ = createBackend(kind, options.size, "shadowlab", true, error);
    if (!backend_) return false;
    if (!initGl(backend_->loader(), false, error)) {
        error = std::string(backendName(kind)) + " backend: " + error;
        return false;
    }
    logInfo("OpenGL " + glVersionString() + " | " + glRendererString() + " | " + backend_->description());
    shaders_ = std::make_unique<ShaderLibrary>();
    timer_ = std::make_unique<GpuTimer>();
    renderer_ = std::make_unique<Renderer>(*shaders_);
    if (!renderer_->init(error)) return false;
    if (!shadowMapViews_.init(*shaders_, error)) return false;
    const glm::ivec2 size = windowed ? backend_->framebufferSize() : options.size;
    if (!checkRenderTargets(size, options.msaaSamples, sceneGeometryBytes(*scene_), error)) {
        badInput = true;   // more than the device or the budget allows: say what it supports
        return false;
    }
    if (!renderer_->resize(size, options.msaaSamples, error)) {
        error += " (" + describeRenderLimits() + ")";
        return false;
    }
    renderer_->setBvhSource([this] { return sceneBvhFor(sceneGeneration_); });
    renderer_->setScene(*scene_);
    camera_.reset(scene_->camera);
    setCameraFloor();
    light_ = scene_->light;
    applyLightOverrides();
    if (options.depthPrepass) setDepthPrepassMode(*options.depthPrepass);
    translucentLayers_ = options.translucentLayers;
    referenceDevice_ = options.referenceDevice;
    techniques_ = std::make_unique<TechniqueManager>(HostContext{*renderer_, *shaders_, *timer_, backend_->loader()}, pluginDir());
    techniques_->scan({referenceDescriptor().id});
    techniques_->registerBuiltin(copyDescriptor(referenceDescriptor(), {}), [this] {
        return std::make_unique<ReferenceTechnique>(
            [this](const GBufferView& gbuffer, const ReferenceOptions& options, std::vector<glm::vec3>& visibility,
                   std::string& error) { return traceReference(gbuffer, options, visibility, error); },
            &sceneGeneration_);
    });
    if (techniques_->techniques().size() <= 1) {
        // The folder is the user's setting (SHADOWLAB_PLUGIN_DIR) or an unbuilt tree: bad input.
        error = "no technique plugins found in " + pluginDir().string() +
                " (build the project, or set SHADOWLAB_PLUGIN_DIR to the folder of the plugins)";
        badInput = true;
        return false;
    }
    return true;
}

// The orbit camera stays above the receivers' lowest point (not the scene camera's own height:
// a scene may start below it, and then the floor is under the camera).
void App::setCameraFloor() {
    const Bounds receivers = scene_->worldBounds(DrawSet::Receivers);
    if (receivers.min.y > receivers.max.y) return;
    camera_.setFloor(std::min(receivers.min.y, scene_->camera.position.y));
}

void App::applyLightOverrides() {
    if (options_.lightDirection && glm::length(*options_.lightDirection) > 0.0f) {
        light_.direction = glm::normalize(*options_.lightDirection);
    }
    if (options_.lightSize) {
        light_.size = light_.type == LightType::Directional ? glm::radians(*options_.lightSize) : *options_.lightSize;
    }
}

bool App::loadScene(const std::string& nameOrPath, const std::map<std::string, double>& parameters, std::string& error) {
    try {
        auto scene = std::make_unique<Scene>(shadowlab::loadScene(nameOrPath, parameters));
        {
            // A trace of another thread (the window's measurement, joined before a scene change)
            // would make this wait rather than read a scene being replaced.
            std::unique_lock lock(groundTruthMutex_);
            // Techniques keep screen- and scene-dependent resources; they rebuild on next use.
            scene_ = std::move(scene);
            ++sceneGeneration_;
        }
        depthPrepassRule_.reset();   // another scene, another depth complexity
        renderer_->setScene(*scene_);
        camera_.reset(scene_->camera);
        setCameraFloor();
        light_ = scene_->light;
        applyLightOverrides();
        return true;
    } catch (const SceneError& e) {
        error = e.what();   // the current scene stays loaded
        return false;
    }
}

std::string App::firstTechnique() const {
    const auto& all = techniques_->techniques();
    return all.empty() ? std::string() : all.front().id;
}

bool App::applyAssignments(const std::vector<std::string>& assignments, const std::string& technique, std::string& error) {
    return shadowlab::applyAssignments(params_, techniques_->techniques(), assignments, technique, error);
}

namespace {

// A different 32-bit seed every frame (splitmix64 of the frame index): stochastic techniques.
uint32_t frameSeed(uint64_t frameIndex) {
    uint64_t z = frameIndex + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return uint32_t((z ^ (z >> 31)) >> 16);
}

} // namespace

bool App::renderFrame(const std::string& technique, std::string& error, FrameOutputs outputs) {
    // Ctrl-C is checked here, between frames, for every frame loop at once (bench rows, paths,
    // stress cells, eval, tours): each stops at its next frame and writes what it has done.
    if (interrupted()) {
        error = "interrupted (Ctrl-C)";
        return false;
    }
    // May wait for the GPU to finish the frame 4 back (when it is the bottleneck); that wait is
    // not host work, so the CPU clock starts after it.
    timer_->beginFrame();
    const auto cpuStart = std::chrono::steady_clock::now();
    shaders_->pollForChanges();
    lastReloaded_ = techniques_->pollForChanges(params_);
    LoadedTechnique* loaded = techniques_->get(technique, error);
    if (!loaded) {
        timer_->endFrame();
        return false;
    }
    const std::vector<double>& values = params_.values(loaded->info());
    const ParamValues params(values.data(), uint32_t(values.size()));

    // The frame context: the window runs on the wall clock, headless runs on fixed 1/60 s steps
    // (so renders and paths are reproducible).
    const uint64_t index = framesRendered_++;
    const bool first = index == 0;
    const glm::mat4 previous = frame_.camera.viewProjection;
    const float time = windowed_ ? std::chrono::duration<float>(std::chrono::steady_clock::now() - startTime_).count()
                                 : float(index) / 60.0f;
    frame_.deltaTime = first ? 1.0f / 60.0f : time - frame_.time;
    frame_.frameIndex = index;
    frame_.time = time;
    frame_.randomSeed = frameSeed(index);
    frame_.camera = camera_.info(renderer_->size());
    frame_.previousViewProjection = first ? frame_.camera.viewProjection : previous;
    frame_.light = light_;

    renderer_->setView(frame_.camera, light_);
    // The flags this frame's parameter values allow (csm asks for the pre-pass only for sdsm).
    const uint32_t flags = loaded->info().flagsFor(values);
    loaded->host().setFrameFlags(flags);
    cameraPrepassFor(flags);
    renderer_->applyDefaultState();
    loaded->host().beginFrame();
    loaded->technique().renderShadows(frame_, params);
    decideDepthPrepass();
    const bool passes = runMainPasses(*loaded, frame_, params, outputs, true, error);
    timer_->endFrame();
    if (!passes) return false;
    lastTechnique_ = technique;
    lastFrameEnd_ = std::chrono::steady_clock::now();
    lastCpuFrameMs_ = std::chrono::duration<double, std::milli>(lastFrameEnd_ - cpuStart).count();
    return true;
}

void App::beginSharedView(const std::vector<std::string>& techniques) {
    sharedView_ = {};
    sharedView_.active = true;
    for (const std::string& id : techniques)
        if (const TechniqueInfo* info = techniques_->find(id)) sharedView_.flags |= info->flagsFor(params_.values(*info));
}

void App::cameraPrepassFor(uint32_t flags) {
    constexpr uint32_t kPrepassFlags = kTechniqueNeedsCameraPrepass | kTechniqueNeedsCameraDepth;
    // Contact shadows march through the camera's depth: the depth-only pre-pass when the technique
    // asks for none, timed apart so that its cost is the contact shadows', not the technique's.
    const bool forContactOnly = contactShadowsOn() && !(flags & kPrepassFlags);
    if (contactShadowsOn()) flags |= kTechniqueNeedsCameraDepth;
    if (!(flags & kPrepassFlags)) return;
    SharedPrepass& shared = sharedView_;
    if (shared.active) {
        const glm::mat4& viewProjection = frame_.camera.viewProjection;
        if (shared.drawn && shared.viewProjection == viewProjection && shared.size == renderer_->size()) return;
        flags |= shared.flags;   // the full pass when any technique of the view needs it
        shared.drawn = true;
        shared.viewProjection = viewProjection;
        shared.size = renderer_->size();
    }
    timer_->begin(forContactOnly ? "contact pre-pass" : "camera pre-pass");
    renderer_->cameraPrepass((flags & kTechniqueNeedsCameraPrepass) ? Renderer::PrepassKind::Full
                                                                    : Renderer::PrepassKind::Depth);
    timer_->end();
}

bool App::renderAccuracyTargets(std::string& error) {
    if (renderer_->accuracyTargetsCurrent()) return true;
    if (lastTechnique_.empty()) {
        error = "no frame has been rendered yet";
        return false;
    }
    LoadedTechnique* loaded = techniques_->get(lastTechnique_, error);
    if (!loaded) return false;
    const std::vector<double>& values = params_.values(loaded->info());
    const ParamValues params(values.data(), uint32_t(values.size()));
    // The technique's maps are those of the frame being measured; only its main pass runs again,
    // with the frame context it had, outside any timer scope.
    renderer_->setView(frame_.camera, frame_.light);
    return runMainPasses(*loaded, frame_, params, FrameOutputs::Accuracy, false, error);
}

bool App::runMainPasses(LoadedTechnique& loaded, const FrameContext& frame, const ParamValues& params,
                        FrameOutputs outputs, bool timed, std::string& error) {
    const std::vector<double>& host = hostValues();
    const float blur = float(host[kHostShadowBlur]);
    auto begin = [&](const char* scope) {
        if (timed) timer_->begin(scope);
    };
    auto end = [&] {
        if (timed) timer_->end();
    };
    GLuint mainProgram = loaded.mainProgram(outputs);
    if (blur > 0.0f) {
        const GLuint term = loaded.eyeBlurTermProgram(error);
        mainProgram = term ? loaded.eyeBlurMainProgram(outputs, error) : 0;
        if (!mainProgram) return false;
        // Seed 002 sec. 9.4.2: an initial pass writes the shadow term (with the technique's own
        // filtering) of the opaque surfaces; a blur shrinking with depth (sec. 6.3) makes the
        // texture the main pass attenuates the light with.
        begin("eye blur term");
        renderer_->eyeBlurTermPass(term, [&] { loaded.technique().bindMainPass(frame, params); });
        end();
        begin("eye blur");
        renderer_->eyeBlur(blur, float(host[kHostShadowBlurDepth]));
        end();
    }
    const bool contact = host[kHostContactShadows] > 0.0;
    if (contact) {
        begin("contact shadows");
        renderer_->contactShadows({float(host[kHostContactShadows]), float(host[kHostContactThickness]),
                                   int(host[kHostContactSteps]), float(host[kHostContactJitter])});
        end();
    }
    // Timed frames count the opaque fragments for the depth pre-pass's auto rule.
    if (timed) renderer_->countOverdrawNextPass();
    if (prepassThisFrame_) {
        begin("depth pre-pass");
        renderer_->mainDepthPrepass(outputs);
        end();
    }
    renderer_->setEyeBlurRead(blur > 0.0f);
    renderer_->setContactRead(contact);
    renderer_->setLighting(int(host[kHostLighting]));
    begin("main");
    // SHADOWLAB_EXT_TRANSLUCENT_DRAWS: the technique's hook before each translucent object; the
    // loop (hooks and draws) is timed as one scope inside "main", as seed 001 sec. 5.3.1 times
    // composited shadows.
    bool translucentScope = false;
    auto translucentHook = [&](uint32_t object) {
        if (object != kTranslucentDrawsDone && !translucentScope) {
            begin("translucent draws");
            translucentScope = true;
        }
        rebindAfterTranslucentHook(loaded, frame, params, mainProgram, object);
        if (object == kTranslucentDrawsDone && translucentScope) {
            end();
            translucentScope = false;
        }
    };
    if (loaded.host().hasTranslucentHook()) renderer_->setTranslucentHook(Renderer::translucentHookFor(translucentHook));
    renderer_->mainPass(mainProgram, outputs, [&] { loaded.technique().bindMainPass(frame, params); });
    renderer_->setTranslucentHook({});
    end();
    renderer_->setEyeBlurRead(false);
    renderer_->setContactRead(false);
    return true;
}

void App::decideDepthPrepass() {
    if (const auto complexity = renderer_->pollOverdraw()) {
        const bool changed = depthPrepassRule_.update(*complexity);
        if (changed && depthPrepassMode() == DepthPrepassMode::Auto) {
            char text[160];
            std::snprintf(text, sizeof text, "depth pre-pass: auto turns it %s (%.2f opaque fragments per pixel)",
                          depthPrepassRule_.autoDecision() ? "on" : "off", *complexity);
            logInfo(text);
        }
    }
    prepassThisFrame_ = depthPrepassRule_.active(depthPrepassMode());
}

void App::rebindAfterTranslucentHook(LoadedTechnique& loaded, const FrameContext& frame, const ParamValues& params,
                                     GLuint program, uint32_t object) {
    loaded.host().beforeTranslucentObject(frame, params, object);
    // The hook may have changed anything: the contract's state, the program, the technique's bindings.
    renderer_->applyDefaultState();
    glUseProgram(program);
    loaded.technique().bindMainPass(frame, params);
    renderer_->resetPipelineState();
}

ViewSelection viewFromName(const std::string& name) {
    if (name == "lit" || name.empty()) return {};
    if (name == "visibility") return {ViewSelection::Kind::Visibility, ""};
    if (name == "error") return {ViewSelection::Kind::ErrorHeatmap, ""};
    if (name == "footprint") return {ViewSelection::Kind::Footprint, ""};
    if (name == "texel-grid") return {ViewSelection::Kind::TexelGrid, ""};
    if (name == "coverage") return {ViewSelection::Kind::MapCoverage, ""};
    if (name == "focus-body") return {ViewSelection::Kind::FocusBody, ""};
    if (name == "kernel") return {ViewSelection::Kind::Kernel, ""};
    return {ViewSelection::Kind::DebugImage, name};
}

std::string viewName(const ViewSelection& view) {
    switch (view.kind) {
    case ViewSelection::Kind::Lit: return "lit";
    case ViewSelection::Kind::Visibility: return "visibility";
    case ViewSelection::Kind::ErrorHeatmap: return "error";
    case ViewSelection::Kind::Footprint: return "footprint";
    case ViewSelection::Kind::TexelGrid: return "texel-grid";
    case ViewSelection::Kind::MapCoverage: return "coverage";
    case ViewSelection::Kind::FocusBody: return "focus-body";
    case ViewSelection::Kind::Kernel: return "kernel";
    case ViewSelection::Kind::DebugImage: return view.debugImage;
    }
    return "lit";
}

bool isHostViewName(const std::string& name) { return viewFromName(name).kind != ViewSelection::Kind::DebugImage; }

const std::vector<std::string>& hostViewNames() {
    static const std::vector<std::string> names = {"lit",       "visibility", "error",      "footprint",
                                                   "texel-grid", "coverage",   "focus-body", "kernel"};
    return names;
}

KernelProbe App::probeKernel(const std::string& technique, std::string& error) {
    KernelProbe none;
    LoadedTechnique* loaded = techniques_->get(technique, error);
    if (!loaded) {
        none.problem = error;
        return none;
    }
    const FilterFootprint& footprint = loaded->host().filterFootprint();
    const std::vector<ShadowMapInfo>& maps = loaded->host().shadowMaps();
    if (footprint.kernel == FilterKernel::None || maps.empty()) {
        none.problem = technique + " reports no filter kernel (pcf, adaptive-pcf and pcss do, with a 2D map)";
        return none;
    }
    if (!probePixel_) {
        none.kernel = footprint.kernel;
        none.problem = "no pixel probed: move the mouse over the view, or --probe X,Y";
        return none;
    }
    const glm::ivec2 size = renderer_->size();
    const glm::ivec2 pixel(probePixel_->x, size.y - 1 - probePixel_->y);   // GL rows from the bottom
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= size.x || pixel.y >= size.y) {
        none.problem = "the probed pixel is outside the view";
        return none;
    }
    if (!renderAccuracyTargets(error)) {
        none.problem = error;
        return none;
    }
    // The 2x2 quad's positions and normals (a coherent early out is decided per quad).
    ProbeQuad quad;
    quad.origin = {pixel.x & ~1, pixel.y & ~1};
    for (int q = 0; q < 4; ++q) {
        const glm::ivec2 p = quad.origin + glm::ivec2(q % 2, q / 2);
        quad.position[q] = glm::vec4(0.0f);
        quad.normal[q] = glm::vec3(0.0f, 0.0f, 1.0f);
        if (p.x >= size.x || p.y >= size.y) continue;
        glm::vec4 normal(0.0f);
        glGetTextureSubImage(renderer_->target(MainTarget::Position), 0, p.x, p.y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT,
                             sizeof(glm::vec4), &quad.position[q]);
        glGetTextureSubImage(renderer_->target(MainTarget::Normal), 0, p.x, p.y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT,
                             sizeof(glm::vec4), &normal);
        quad.normal[q] = glm::vec3(normal);
    }
    const int resolution = int(footprint.lightDepth.w);
    GLint width = 0, height = 0;
    if (footprint.depthTexture && glIsTexture(footprint.depthTexture)) {
        glGetTextureLevelParameteriv(footprint.depthTexture, 0, GL_TEXTURE_WIDTH, &width);
        glGetTextureLevelParameteriv(footprint.depthTexture, 0, GL_TEXTURE_HEIGHT, &height);
    }
    if (width != resolution || height != resolution) {
        none.problem = "the reported depth texture is not the map's size";
        return none;
    }
    probeDepths_.resize(size_t(width) * size_t(height));
    glGetTextureImage(footprint.depthTexture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(probeDepths_.size() * sizeof(float)),
                      probeDepths_.data());
    const DepthFetch fetch = [&](int x, int y) { return probeDepths_[size_t(y) * size_t(width) + size_t(x)]; };
    return shadowlab::probeKernel(footprint, maps.front(), quad, pixel, fetch);
}

std::optional<glm::ivec2> App::shadowEdgePixel(const std::string& technique) {
    std::string error;
    if (!renderFrame(technique, error, FrameOutputs::Accuracy)) return std::nullopt;
    const glm::ivec2 size = renderer_->size();
    const std::vector<glm::vec4> term = renderer_->readTarget(MainTarget::Visibility);
    const std::vector<glm::vec4> position = renderer_->readTarget(MainTarget::Position);
    auto at = [&](int x, int y) { return size_t(y) * size_t(size.x) + size_t(x); };
    auto drawn = [&](int x, int y) { return position[at(x, y)].w > 0.5f; };
    std::optional<glm::ivec2> best;
    float bestDistance = 1e30f;
    const glm::vec2 centre = 0.5f * glm::vec2(size);
    // Two pixels in from the border, so the kernel's footprint around it stays in the image.
    for (int y = 2; y + 2 < size.y; ++y)
        for (int x = 2; x + 2 < size.x; ++x) {
            if (!drawn(x, y) || !drawn(x + 1, y) || !drawn(x, y + 1)) continue;
            const float v = term[at(x, y)].x;
            const bool edge = (v > 0.1f && v < 0.9f) || std::abs(v - term[at(x + 1, y)].x) > 0.5f ||
                              std::abs(v - term[at(x, y + 1)].x) > 0.5f;
            const float distance = glm::distance(glm::vec2(x, y), centre);
            if (edge && distance < bestDistance) {
                bestDistance = distance;
                best = glm::ivec2(x, size.y - 1 - y);   // rows are bottom-up
            }
        }
    return best;
}

// A technique's debug image at its true aspect ratio, letterboxed in the view (a square map was
// stretched to 16:9), a depth map's values stretched from the nearest to the farthest depth it
// holds (render/depth_range.h).
void App::presentDebugImage(const DebugImage& image, GLuint fbo, glm::ivec2 size) {
    glm::ivec2 texels(0);
    glGetTextureLevelParameteriv(image.texture, 0, GL_TEXTURE_WIDTH, &texels.x);
    glGetTextureLevelParameteriv(image.texture, 0, GL_TEXTURE_HEIGHT, &texels.y);
    glm::ivec2 rect = size, origin(0);
    if (texels.x > 0 && texels.y > 0) {
        const float scale = std::min(float(size.x) / float(texels.x), float(size.y) / float(texels.y));
        rect = glm::max(glm::ivec2(glm::round(glm::vec2(texels) * scale)), glm::ivec2(1));
        origin = (size - rect) / 2;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, size.x, size.y);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.09f, 0.09f, 0.11f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glm::vec2 range(0.0f, 1.0f);
    if (image.kind == DebugImageKind::Depth) {
        if (!depthRange_) depthRange_ = std::make_unique<DepthRange>();
        if (inWindowLoop_) depthRange_->update(image.texture);
        else depthRange_->measureNow(image.texture);
        range = depthRange_->range(image.texture);
    }
    const PresentMode mode = image.kind == DebugImageKind::Depth     ? PresentMode::Depth
                             : image.kind == DebugImageKind::Moments ? PresentMode::Moments
                                                                     : PresentMode::Color;
    renderer_->present(mode, image.texture, fbo, rect, range, origin);
}

std::string App::debugViewsOf(const std::string& technique) {
    std::string error, views;
    LoadedTechnique* loaded = techniques_->get(technique, error);
    if (!loaded) return views;
    const PluginHost& host = loaded->host();
    if (!host.shadowMaps().empty()) views = "footprint, texel-grid, coverage";
    for (const auto& edges : host.focusBodyEdges())
        if (!edges.empty()) {
            appendListItem(views, "focus-body");
            break;
        }
    if (host.filterFootprint().kernel != FilterKernel::None) appendListItem(views, "kernel");
    for (const DebugImage& image : host.debugImages()) appendListItem(views, "'" + image.name + "'");
    return views;
}

std::string App::viewProblem(const std::string& technique, const std::string& view,
                             const std::vector<std::string>& extraViews) {
    if (isHostViewName(view) || std::find(extraViews.begin(), extraViews.end(), view) != extraViews.end()) return "";
    std::string error;
    LoadedTechnique* loaded = techniques_->get(technique, error);
    if (loaded && loaded->host().debugImages().empty() && renderFrame(technique, error)) loaded = techniques_->get(technique, error);
    std::string names;
    for (const std::string& name : hostViewNames()) appendListItem(names, name);
    for (const std::string& name : extraViews) appendListItem(names, name);
    if (loaded) {
        for (const DebugImage& image : loaded->host().debugImages()) {
            if (image.name == view) return "";
            appendListItem(names, "'" + image.name + "'");
        }
    }
    return "view '" + view + "': " + technique + " has no such view (views: " + names + ")" +
           (loaded ? std::string() : "; " + error);
}

bool App::presentView(const std::string& technique, const ViewSelection& view, GLuint framebuffer, glm::ivec2 viewport,
                      std::string& error) {
    const bool toDisplay = framebuffer == ~0u;
    const GLuint fbo = toDisplay ? renderer_->displayFramebuffer() : framebuffer;
    const glm::ivec2 size = toDisplay ? renderer_->size() : viewport;
    switch (view.kind) {
    case ViewSelection::Kind::Lit:
        renderer_->present(PresentMode::Lit, renderer_->target(MainTarget::Color), fbo, size);
        return true;
    case ViewSelection::Kind::Visibility:
        if (!renderAccuracyTargets(error)) return false;
        renderer_->present(PresentMode::Visibility, renderer_->target(MainTarget::Visibility), fbo, size);
        return true;
    case ViewSelection::Kind::ErrorHeatmap:
        // Computed on the CPU by a measurement, already in the display texture.
        if (!toDisplay) renderer_->present(PresentMode::Color, renderer_->displayTexture(), fbo, size);
        return true;
    case ViewSelection::Kind::Footprint:
    case ViewSelection::Kind::TexelGrid:
    case ViewSelection::Kind::MapCoverage:
    case ViewSelection::Kind::FocusBody:
    case ViewSelection::Kind::Kernel: {
        if (!renderAccuracyTargets(error)) return false;
        LoadedTechnique* loaded = techniques_->get(technique, error);
        if (!loaded) return false;
        const ShadowMapView kind = view.kind == ViewSelection::Kind::Footprint   ? ShadowMapView::Footprint
                                   : view.kind == ViewSelection::Kind::TexelGrid ? ShadowMapView::TexelGrid
                                   : view.kind == ViewSelection::Kind::FocusBody ? ShadowMapView::FocusBody
                                   : view.kind == ViewSelection::Kind::Kernel    ? ShadowMapView::Kernel
                                                                                 : ShadowMapView::Coverage;
        if (kind == ShadowMapView::Kernel) {
            std::string problem;
            lastProbe_ = probeKernel(technique, problem);
            if (!lastProbe_.valid && lastProbe_.problem.empty()) lastProbe_.problem = problem;
        }
        shadowMapViews_.draw(*renderer_, kind, loaded->host().shadowMaps(), fbo, size, &loaded->host().focusBodyEdges(),
                             &lastProbe_);
        return true;
    }
    case ViewSelection::Kind::DebugImage: {
        LoadedTechnique* loaded = techniques_->get(technique, error);
        if (!loaded) return false;
        std::string names;
        for (const DebugImage& image : loaded->host().debugImages()) {
            if (image.name == view.debugImage) {
                presentDebugImage(image, fbo, size);
                return true;
            }
            appendListItem(names, image.name);
        }
        error = "technique '" + technique + "' has no debug image '" + view.debugImage +
                "' (views: lit, visibility" + (names.empty() ? "" : ", " + names) + ")";
        return false;
    }
    }
    return false;
}

namespace {

// Warm-up lasts at least this long as well as the frames asked for: after a CPU-side step (a
// reference trace between benchmark rows) an idle GPU has lowered its clocks, and ten 0.8 ms
// frames do not bring them back (the H200 run of 2026-12-01 measured `none` at 4.6 ms instead of
// 0.8 ms right after a trace). After a short pause (the previous row's metrics, under half a
// second) a shorter warm-up is enough: the clocks have not dropped yet, and a sweep of hundreds
// of rows would otherwise spend a quarter second on each (issue 32). Capped so a broken timer
// cannot spin forever.
constexpr double kMinWarmupSeconds = 0.25;
constexpr double kMinWarmupSecondsAfterShortPause = 0.05;
constexpr double kLongPauseSeconds = 0.5;
constexpr int kMaxWarmupFrames = 5000;

template <typename RenderOne>
bool warmUp(int warmupFrames, double minSeconds, RenderOne&& renderOne) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kMaxWarmupFrames; ++i) {
        const bool enoughTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= minSeconds;
        if (i >= warmupFrames && (enoughTime || warmupFrames == 0)) break;
        if (!renderOne()) return false;
    }
    return true;
}

} // namespace

double App::warmupSeconds() const {
    const double pause = std::chrono::duration<double>(std::chrono::steady_clock::now() - lastFrameEnd_).count();
    return pause >= kLongPauseSeconds ? kMinWarmupSeconds : kMinWarmupSecondsAfterShortPause;
}

bool App::measure(const std::string& technique, int warmupFrames, int frames, Measurement& out, std::string& error,
                  const TimingStop& stop) {
    // Silent unless it takes a while (200 frames of the forest on llvmpipe: half a minute).
    Progress progress("measuring " + technique, uint64_t(warmupFrames) + uint64_t(frames), "frames (warm-up included)");
    uint64_t warmed = 0;
    auto warmFrame = [&] {
        const bool drawn = renderFrame(technique, error);
        progress.step(std::min(++warmed, uint64_t(warmupFrames)));   // warm-up may run longer than its frames
        return drawn;
    };
    if (!warmUp(warmupFrames, warmupSeconds(), warmFrame)) return false;
    // Auto decides from a frame already drawn: at least one before the timed ones (the drain
    // below finishes its count, which the first timed frame reads).
    if (depthPrepassMode() == DepthPrepassMode::Auto && !depthPrepassRule_.measured() && warmupFrames == 0 &&
        !renderFrame(technique, error))
        return false;
    timer_->drain();
    timer_->clearHistory();
    std::vector<double> cpu;
    cpu.reserve(size_t(frames));
    int prepassFrames = 0;
    int timed = 0;
    std::optional<double> stoppedHalfWidth;
    static const std::vector<double> kNoFrames;
    while (timed < frames) {
        if (!renderFrame(technique, error)) return false;
        cpu.push_back(lastCpuFrameMs_);
        prepassFrames += prepassThisFrame_ ? 1 : 0;
        progress.step(uint64_t(warmupFrames) + uint64_t(++timed));
        // The frame times resolved so far (the timer reads queries some frames late, without
        // waiting): the frames still in flight are drained below and count too.
        const auto frameTimes = timer_->history().find("frame");
        const std::vector<double>& resolved = frameTimes == timer_->history().end() ? kNoFrames : frameTimes->second;
        if (stop.reached(resolved)) {
            stoppedHalfWidth = medianRelativeHalfWidth95(resolved);
            break;
        }
    }
    timer_->drain();
    out = {};
    out.stoppedHalfWidth = stoppedHalfWidth;
    for (const auto& [pass, samples] : timer_->history()) {
        out.gpuMs[pass] = summarize(samples);
        if (pass == "frame") out.frameMedianHalfWidth = medianRelativeHalfWidth95(samples);
    }
    out.cpuMs = summarize(cpu);
    out.cpuWaitMs = summarize(timer_->waitHistory());
    for (double wait : timer_->waitHistory()) out.framesWaited += wait > 0.0 ? 1 : 0;
    LoadedTechnique* loaded = techniques_->get(technique, error);
    out.gpuBytes = loaded ? loaded->host().gpuBytes() : 0;
    out.frames = timed;
    out.depthPrepassFrames = prepassFrames;
    out.depthComplexity = depthPrepassRule_.complexity();
    return true;
}

bool App::setRenderSize(glm::ivec2 size, std::string& error) {
    if (!checkRenderTargets(size, renderer_->msaaSamples(), sceneGeometryBytes(*scene_), error)) return false;
    return renderer_->resize(size, renderer_->msaaSamples(), error);
}

bool App::measureDepthFloor(int resolution, int warmupFrames, int frames, Measurement& out, std::string& error) {
    // Created for this measurement only (not in a frame loop): a depth texture, its framebuffer
    // and the shared depth-only program.
    GlTexture depth;
    GlFramebuffer framebuffer;
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    depth.reset(name);
    glTextureStorage2D(name, 1, GL_DEPTH_COMPONENT32F, resolution, resolution);
    glCreateFramebuffers(1, &name);
    framebuffer.reset(name);
    glNamedFramebufferTexture(name, GL_DEPTH_ATTACHMENT, depth.get(), 0);
    glNamedFramebufferDrawBuffer(name, GL_NONE);
    if (glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        error = "depth floor framebuffer incomplete";
        return false;
    }
    const ProgramId program = shaders_->build(hostShaderRequest("depth_only.vert", "", "depth floor"), error);
    if (!program) return false;
    // The depth map's block (the same shader as the techniques' depth passes), from the host's
    // fit around the whole scene.
    GlBuffer uniforms;
    glCreateBuffers(1, &name);
    uniforms.reset(name);
    shared::depth_map::DepthMapUniforms block{};
    block.uShadowMatrix = fitLightSpace(light_, renderer_->bounds(DrawSet::All)).viewProjection;
    glNamedBufferStorage(name, sizeof(block), &block, 0);
    auto depthFrame = [&] {
        timer_->beginFrame();
        renderer_->setView(camera_.info(renderer_->size()), light_);
        renderer_->applyDefaultState();
        timer_->begin("depth floor");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
        glViewport(0, 0, resolution, resolution);
        glClear(GL_DEPTH_BUFFER_BIT);
        glBindBufferBase(GL_UNIFORM_BUFFER, shared::depth_map::DepthMapUniforms::kBinding, uniforms.get());
        renderer_->drawScene(DrawSet::OpaqueCasters, shaders_->program(program));
        timer_->end();
        timer_->endFrame();
        return true;
    };
    warmUp(warmupFrames, warmupSeconds(), depthFrame);
    timer_->drain();
    timer_->clearHistory();
    for (int i = 0; i < frames; ++i) depthFrame();
    timer_->drain();
    lastFrameEnd_ = std::chrono::steady_clock::now();
    out = {};
    for (const auto& [pass, samples] : timer_->history()) {
        out.gpuMs[pass] = summarize(samples);
        if (pass == "frame") out.frameMedianHalfWidth = medianRelativeHalfWidth95(samples);
    }
    out.frames = frames;
    shaders_->release(program);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return true;
}

} // namespace shadowlab
