// Running techniques: the host-services table each one gets (with GPU memory accounting and
// clean-up of whatever it leaves behind), lazy loading, and hot reload of rebuilt libraries.
#pragma once

#include <chrono>
#include <functional>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plugin/params.h"
#include "plugin/plugin_library.h"
#include "render/gpu_timer.h"
#include "render/renderer.h"
#include "render/shader_library.h"

namespace shadowlab {

struct HostContext {
    Renderer& renderer;
    ShaderLibrary& shaders;
    GpuTimer& timer;
    GlLoader glLoader;
};

struct DebugImage {
    std::string name;
    GLuint texture;
    DebugImageKind kind;
};

struct TrackedAllocation {
    std::string label;
    size_t bytes;
};

class PluginHost final : public IHost {
public:
    PluginHost(HostContext context, const TechniqueInfo& info);
    ~PluginHost();
    PluginHost(const PluginHost&) = delete;
    PluginHost& operator=(const PluginHost&) = delete;

    GlLoader glLoader() const override { return context_.glLoader; }
    void log(LogLevel level, const char* message) override;
    const void* extension(const char* id) const override;
    uint32_t objectCount() const override { return context_.renderer.objectCount(); }
    const ObjectInfo* objects() const override { return context_.renderer.objects(); }
    Bounds bounds(DrawSet set) const override { return context_.renderer.bounds(set); }
    LightSpace fitLightSpace(const LightInfo& light, const Bounds& bounds) const override;
    LightSpace fitLightSpaceToPoints(const LightInfo& light, const glm::vec3* points, uint32_t count) const override;
    LightSpace fitLightSpaceToFrustumSlice(const LightInfo& light, const CameraInfo& camera, float nearDistance,
                                           float farDistance) const override;
    using IHost::drawScene;
    using IHost::fitLightSpace;
    void drawScene(const DrawRequest& request, uint32_t glProgram) override;
    void drawObject(uint32_t index, uint32_t glProgram) override { context_.renderer.drawObject(index, glProgram); }
    void drawFullscreenTriangle() override { context_.renderer.drawFullscreenTriangle(); }
    ProgramId buildProgram(const ProgramDesc& desc, std::string& error) override;
    uint32_t glProgram(ProgramId id) const override { return context_.shaders.program(id); }
    void destroyProgram(ProgramId id) override;
    void beginGpuPass(const char* name) override {
        if (!muteGpuPasses_) context_.timer.begin(name);
    }
    void endGpuPass() override {
        if (!muteGpuPasses_) context_.timer.end();
    }
    uint32_t createTexture(const TextureDesc& desc) override;
    void destroyTexture(uint32_t texture) override;
    uint32_t createBuffer(size_t bytes, const void* data, uint32_t storageFlags, const char* label) override;
    void destroyBuffer(uint32_t buffer) override;
    uint32_t createFramebuffer(const char* label) override;
    void destroyFramebuffer(uint32_t framebuffer) override;
    bool checkFramebuffer(uint32_t framebuffer, const char* what) override;
    uint32_t sampler(SamplerKind kind) const override { return context_.renderer.sampler(kind); }
    void registerDebugImage(const char* name, uint32_t texture, DebugImageKind kind) override;
    void reportStatistic(const char* name, double value) override { statistics_[name ? name : "?"] = value; }

    size_t gpuBytes() const;
    const std::map<GLuint, TrackedAllocation>& textures() const { return textures_; }
    const std::vector<DebugImage>& debugImages() const { return debugImages_; }
    const std::map<std::string, double>& statistics() const { return statistics_; }
    // The shadow maps the technique reported for its last frame (SHADOWLAB_EXT_SHADOW_MAPS);
    // cleared by beginFrame() before each renderShadows, so a technique that stops reporting has none.
    const std::vector<ShadowMapInfo>& shadowMaps() const { return shadowMaps_; }
    void beginFrame() {
        shadowMaps_.clear();
        focusBodyEdges_.clear();
        filterFootprint_ = {};
    }
    // The focus body B's edges of each reported map (ShadowMapInfo::focusBodyEdges, copied):
    // [i] belongs to shadowMaps()[i], point pairs; empty where the map has none.
    const std::vector<std::vector<glm::vec3>>& focusBodyEdges() const { return focusBodyEdges_; }
    // The filter kernel reported this frame (SHADOWLAB_EXT_FILTER_FOOTPRINT); kernel None: none.
    const FilterFootprint& filterFootprint() const { return filterFootprint_; }
    // The flags that hold this frame (TechniqueInfo::flagsFor the current parameters), set by the
    // frame loop before renderShadows: the camera pre-pass extension answers only when it was
    // rendered for this technique.
    void setFrameFlags(uint32_t flags) { flags_ = flags; }
    uint32_t frameFlags() const { return flags_; }
    // Deletes every tracked object and program still alive; returns how many were left over.
    int releaseAll();
    // SHADOWLAB_EXT_TRANSLUCENT_DRAWS: whether the technique installed a hook, and calling it
    // (objectIndex or kTranslucentDrawsDone) with its GpuPass scopes untimed.
    bool hasTranslucentHook() const { return translucentHook_.beforeObject != nullptr; }
    void beforeTranslucentObject(const FrameContext& frame, const ParamValues& params, uint32_t object);

private:
    HostContext context_;
    std::string techniqueId_;
    uint32_t flags_ = 0;
    std::map<GLuint, TrackedAllocation> textures_, buffers_;
    std::map<GLuint, std::string> framebuffers_;
    std::vector<ProgramId> programs_;
    std::vector<DebugImage> debugImages_;
    std::map<std::string, double> statistics_;
    std::vector<ShadowMapInfo> shadowMaps_;
    std::vector<std::string> shadowMapLabels_;   // the reported labels, copied (they point here)
    std::vector<std::vector<glm::vec3>> focusBodyEdges_;
    FilterFootprint filterFootprint_{};
    ShadowMapReport shadowMapReport_{};
    FilterFootprintReport filterFootprintReport_{};
    TranslucentDraws translucentDraws_{};
    RayTracing rayTracing_{};
    static const RayTracingScene* rayTracingScene(void* context);
    Adjacency adjacency_{};
    static const AdjacencyScene* adjacencyScene(void* context);
    TranslucentDrawHook translucentHook_{};
    bool muteGpuPasses_ = false;
    static void installTranslucentHook(void* context, const TranslucentDrawHook* hook);
    static void receiveShadowMaps(void* context, const ShadowMapInfo* maps, uint32_t count);
    static void receiveFilterFootprint(void* context, const FilterFootprint* footprint);
};

// Size in bytes of a texture described by `desc`, every mip level included.
size_t textureBytes(const TextureDesc& desc);

class LoadedTechnique {
public:
    static std::unique_ptr<LoadedTechnique> load(const std::filesystem::path& file, HostContext context,
                                                 std::string& error);
    // A technique compiled into the host (the ray-traced reference): no library, GLSL in shaders/.
    static std::unique_ptr<LoadedTechnique> createBuiltin(const TechniqueInfo& info,
                                                          std::unique_ptr<IShadowTechnique> technique,
                                                          HostContext context, std::string& error);
    ~LoadedTechnique();
    LoadedTechnique(const LoadedTechnique&) = delete;
    LoadedTechnique& operator=(const LoadedTechnique&) = delete;

    const TechniqueInfo& info() const { return info_; }
    IShadowTechnique& technique() { return *technique_; }
    PluginHost& host() { return *host_; }
    // The host's main pass with this technique's shadowTerm(), built for each FrameOutputs.
    GLuint mainProgram(FrameOutputs outputs) const;
    // The eye-space blur's variants of it (render/renderer.h eyeBlur*), built on first use and
    // kept: the term pass (SHADOWLAB_EYE_BLUR_TERM), and the main pass reading the blurred term
    // (SHADOWLAB_EYE_BLUR_READ) for each FrameOutputs. 0 with `error` when a build fails.
    GLuint eyeBlurTermProgram(std::string& error);
    GLuint eyeBlurMainProgram(FrameOutputs outputs, std::string& error);
    // The main pass drawing one translucent layer for evaluation (SHADOWLAB_ACCURACY_TARGETS and
    // SHADOWLAB_TRANSLUCENT_PEEL; Renderer::translucentLayer), built on first use.
    GLuint translucentLayerProgram(std::string& error);
    const PluginLibrary* library() const { return library_.get(); }

private:
    LoadedTechnique() = default;
    bool start(HostContext context, const std::filesystem::path& shadowGlsl, std::string& error);
    TechniqueInfo info_;
    std::unique_ptr<PluginLibrary> library_;
    std::unique_ptr<IShadowTechnique> builtin_;
    std::unique_ptr<PluginHost> host_;
    IShadowTechnique* technique_ = nullptr;
    ProgramId mainPrograms_[2] = {0, 0};   // FrameOutputs::Colour, ::Accuracy
    // The main pass's variants built on first use: eye-blur term, eye-blur read (colour, accuracy
    // targets), translucent layer.
    static constexpr int kMainVariants = 4;
    GLuint mainVariant(int slot, std::string& error);
    ProgramId variantPrograms_[kMainVariants] = {0, 0, 0, 0};
    std::filesystem::path shadowGlsl_;
    ShaderLibrary* shaders_ = nullptr;
};

class TechniqueManager {
public:
    TechniqueManager(HostContext context, std::filesystem::path pluginDir);
    void scan(const std::vector<std::string>& reservedIds = {});
    const std::vector<TechniqueInfo>& techniques() const { return techniques_; }
    const std::vector<std::string>& scanErrors() const { return scanErrors_; }
    const TechniqueInfo* find(const std::string& id) const;
    // Loads on first use (GL current); nullptr and an error when it cannot.
    LoadedTechnique* get(const std::string& id, std::string& error);
    // The techniques loaded so far (the soak tests sum their tracked memory).
    std::vector<LoadedTechnique*> loadedTechniques();
    // Hot reload: a library rebuilt on disk replaces the loaded one in place (values kept by
    // parameter id); a failed load or init keeps the old one. Returns ids reloaded this call.
    std::vector<std::string> pollForChanges(ParamStore& params,
                                            std::chrono::milliseconds interval = std::chrono::milliseconds(50));
    const std::string& lastReloadError() const { return lastReloadError_; }
    // How long an incomplete or unloadable library must stay unchanged before it is a failure
    // (until then it is a build in progress: the linker may pause between writes).
    static constexpr std::chrono::milliseconds kReloadSettle{1500};
    void unloadAll() { loaded_.clear(); }
    using BuiltinFactory = std::function<std::unique_ptr<IShadowTechnique>()>;
    void registerBuiltin(const TechniqueInfo& info, BuiltinFactory factory);

private:
    struct Pending {
        std::filesystem::file_time_type time;
        uintmax_t size;
        std::chrono::steady_clock::time_point since;   // first poll that saw this time and size
    };

    HostContext context_;
    std::filesystem::path pluginDir_;
    std::vector<TechniqueInfo> techniques_;
    std::vector<std::string> scanErrors_;
    std::map<std::string, std::unique_ptr<LoadedTechnique>> loaded_;
    std::map<std::string, BuiltinFactory> builtins_;
    std::map<std::string, Pending> pending_;          // changed on disk, waiting to settle
    std::map<std::string, Pending> failed_;           // last version that failed to load
    std::chrono::steady_clock::time_point lastPoll_{};
    std::string lastReloadError_;
};

} // namespace shadowlab
