// Running techniques (see technique_runtime.h).
#include "util/strings.h"
#include "plugin/technique_runtime.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string_view>

#include "render/light_space.h"
#include "util/log.h"
#include "util/paths.h"

namespace shadowlab {

size_t textureBytes(const TextureDesc& desc) {
    const size_t texel = bytesPerTexel(desc.internalFormat);
    const bool multisample = desc.target == GL_TEXTURE_2D_MULTISAMPLE || desc.target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
    const size_t samples = multisample ? size_t(std::max(desc.samples, 1)) : 1u;
    // Layers that do not shrink with the mips: array layers, cube faces (6 per cube).
    size_t layers = 1;
    switch (desc.target) {
    case GL_TEXTURE_2D_ARRAY:
    case GL_TEXTURE_1D_ARRAY:
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: layers = size_t(std::max(desc.depth, 1)); break;
    case GL_TEXTURE_CUBE_MAP: layers = 6; break;
    case GL_TEXTURE_CUBE_MAP_ARRAY: layers = 6 * size_t(std::max(desc.depth, 1)); break;
    default: break;
    }
    size_t total = 0;
    int w = std::max(desc.width, 1), h = std::max(desc.height, 1), d = std::max(desc.depth, 1);
    const bool is3d = desc.target == GL_TEXTURE_3D;
    const int levels = multisample ? 1 : std::max(desc.levels, 1);
    for (int level = 0; level < levels; ++level) {
        total += size_t(w) * size_t(h) * size_t(is3d ? d : 1) * layers * samples * texel;
        w = std::max(w / 2, 1);
        h = std::max(h / 2, 1);
        if (is3d) d = std::max(d / 2, 1);
    }
    return total;
}

PluginHost::PluginHost(HostContext context, const TechniqueInfo& info)
    : context_(context), techniqueId_(info.id), flags_(info.flags) {
    shadowMapReport_ = {sizeof(ShadowMapReport), this, &PluginHost::receiveShadowMaps};
    filterFootprintReport_ = {sizeof(FilterFootprintReport), this, &PluginHost::receiveFilterFootprint};
    translucentDraws_ = {sizeof(TranslucentDraws), this, &PluginHost::installTranslucentHook};
    rayTracing_ = {sizeof(RayTracing), this, &PluginHost::rayTracingScene};
    adjacency_ = {sizeof(Adjacency), this, &PluginHost::adjacencyScene};
}

const AdjacencyScene* PluginHost::adjacencyScene(void* context) {
    return &static_cast<PluginHost*>(context)->context_.renderer.adjacencyScene();
}

const RayTracingScene* PluginHost::rayTracingScene(void* context) {
    return &static_cast<PluginHost*>(context)->context_.renderer.rayTracing();
}

void PluginHost::installTranslucentHook(void* context, const TranslucentDrawHook* hook) {
    auto& host = *static_cast<PluginHost*>(context);
    host.translucentHook_ = {};
    if (!hook) return;
    // Only the fields the plugin's struct has (structSize), the rest keep their defaults.
    TranslucentDrawHook known;
    std::memcpy(&known, hook, std::min<size_t>(sizeof(TranslucentDrawHook), std::max<size_t>(hook->structSize, sizeof(uint32_t))));
    known.structSize = sizeof(TranslucentDrawHook);
    host.translucentHook_ = known;
}

void PluginHost::beforeTranslucentObject(const FrameContext& frame, const ParamValues& params, uint32_t object) {
    if (!translucentHook_.beforeObject) return;
    // The hook's own GpuPass scopes are not timed: the host's "translucent draws" scope holds them.
    muteGpuPasses_ = true;
    translucentHook_.beforeObject(translucentHook_.user, frame, params, object);
    muteGpuPasses_ = false;
}

void PluginHost::receiveFilterFootprint(void* context, const FilterFootprint* footprint) {
    auto& host = *static_cast<PluginHost*>(context);
    host.filterFootprint_ = {};
    if (!footprint) return;
    // Only the fields the plugin's struct has (structSize), the rest keep their defaults.
    FilterFootprint known;
    std::memcpy(&known, footprint, std::min<size_t>(sizeof(FilterFootprint), std::max<size_t>(footprint->structSize, sizeof(uint32_t))));
    known.structSize = sizeof(FilterFootprint);
    if (uint32_t(known.kernel) > uint32_t(FilterKernel::Pcss) || known.taps < 1 || known.taps > 64 || known.sets < 1 ||
        known.sets > 64 || known.searchTaps < 0 || known.searchTaps > 64 || !std::isfinite(known.spacing)) {
        host.log(LogLevel::Warning, "reported a filter footprint out of range; ignored");
        return;
    }
    host.filterFootprint_ = known;
}

void PluginHost::receiveShadowMaps(void* context, const ShadowMapInfo* maps, uint32_t count) {
    auto& host = *static_cast<PluginHost*>(context);
    // A list longer than any technique needs (8 cascades x 6 faces) is a bug in the plugin.
    constexpr uint32_t kMaxMaps = 64;
    if (!maps && count) return;
    if (count > kMaxMaps) {
        host.log(LogLevel::Warning, "reported more than 64 shadow maps; keeping the first 64");
        count = kMaxMaps;
    }
    host.shadowMaps_.clear();
    host.shadowMapLabels_.clear();
    host.focusBodyEdges_.clear();
    host.shadowMapLabels_.reserve(count);
    // The plugin's array strides by its own struct size (an older plugin's is smaller than ours).
    const auto* bytes = reinterpret_cast<const unsigned char*>(maps);
    const size_t stride = count ? std::max<size_t>(maps[0].structSize, sizeof(uint32_t)) : 0;
    if (stride > 4096) {
        host.log(LogLevel::Warning, "reported shadow maps with a structSize over 4096 bytes; ignored");
        return;
    }
    for (uint32_t i = 0; i < count; ++i) {
        // Only the fields the plugin's struct has (structSize), the rest keep their defaults.
        ShadowMapInfo map;
        std::memcpy(&map, bytes + size_t(i) * stride, std::min<size_t>(sizeof(ShadowMapInfo), stride));
        map.structSize = sizeof(ShadowMapInfo);
        if (map.size.x <= 0 || map.size.y <= 0) continue;   // not a map the footprint can be measured on
        host.shadowMapLabels_.push_back(map.label ? map.label : "");
        // B's edges, copied (they point into the plugin); at most 4096 edges.
        std::vector<glm::vec3> edges;
        if (map.focusBodyEdges && map.focusBodyEdgeCount)
            edges.assign(map.focusBodyEdges, map.focusBodyEdges + 2 * size_t(std::min<uint32_t>(map.focusBodyEdgeCount, 4096)));
        map.focusBodyEdges = nullptr;
        map.focusBodyEdgeCount = uint32_t(edges.size() / 2);
        host.focusBodyEdges_.push_back(std::move(edges));
        host.shadowMaps_.push_back(map);
    }
    for (size_t i = 0; i < host.shadowMaps_.size(); ++i) host.shadowMaps_[i].label = host.shadowMapLabels_[i].c_str();
}

PluginHost::~PluginHost() { releaseAll(); }

void PluginHost::log(LogLevel level, const char* message) { logMessage(level, techniqueId_ + ": " + message); }

const void* PluginHost::extension(const char* id) const {
    if (!id) return nullptr;
    const std::string_view name(id);
    if (name == SHADOWLAB_EXT_CAMERA_PREPASS) {
        // The full targets for a technique that asked for them, the depth alone otherwise.
        const CameraPrepass& full = context_.renderer.prepassTargets();
        const CameraPrepass& depth = context_.renderer.prepassDepthTargets();
        if (flags_ & kTechniqueNeedsCameraPrepass) return full.depth ? &full : nullptr;
        if (flags_ & kTechniqueNeedsCameraDepth) return depth.depth ? &depth : nullptr;
        return nullptr;
    }
    if (name == SHADOWLAB_EXT_SHADOW_MAPS) return &shadowMapReport_;
    if (name == SHADOWLAB_EXT_FILTER_FOOTPRINT) return &filterFootprintReport_;
    if (name == SHADOWLAB_EXT_TRANSLUCENT_DRAWS) return &translucentDraws_;
    if (name == SHADOWLAB_EXT_RAY_TRACING) return &rayTracing_;
    if (name == SHADOWLAB_EXT_ADJACENCY) return &adjacency_;
    return nullptr;
}

LightSpace PluginHost::fitLightSpace(const LightInfo& light, const Bounds& bounds) const {
    const Bounds casters = context_.renderer.bounds(DrawSet::Casters);
    return shadowlab::fitLightSpace(light, bounds, &casters);
}

LightSpace PluginHost::fitLightSpaceToPoints(const LightInfo& light, const glm::vec3* points, uint32_t count) const {
    const Bounds casters = context_.renderer.bounds(DrawSet::Casters);
    return shadowlab::fitLightSpaceToPoints(light, points, count, &casters);
}

LightSpace PluginHost::fitLightSpaceToFrustumSlice(const LightInfo& light, const CameraInfo& camera, float nearDistance,
                                                   float farDistance) const {
    glm::vec3 corners[8];
    frustumSliceCorners(camera, nearDistance, farDistance, corners);
    return fitLightSpaceToPoints(light, corners, 8);
}

void PluginHost::drawScene(const DrawRequest& request, uint32_t glProgram) {
    // Only the fields the plugin's struct has: a smaller (older) request keeps the defaults.
    DrawRequest known;
    std::memcpy(&known, &request, std::min<size_t>(sizeof(DrawRequest), std::max<size_t>(request.structSize, sizeof(uint32_t))));
    known.structSize = sizeof(DrawRequest);
    if (uint32_t(known.primitive) > uint32_t(DrawPrimitive::TrianglesAdjacency)) {
        log(LogLevel::Warning, "drawScene: unknown DrawRequest::primitive; drawn as triangles");
        known.primitive = DrawPrimitive::Triangles;
    }
    context_.renderer.drawScene(known, glProgram);
}

void PluginHost::destroyProgram(ProgramId id) {
    if (std::erase(programs_, id)) context_.shaders.release(id);
}

ProgramId PluginHost::buildProgram(const ProgramDesc& desc, std::string& error) {
    ShaderRequest request;
    request.vertexFile = desc.vertexFile ? desc.vertexFile : "";
    request.geometryFile = desc.geometryFile ? desc.geometryFile : "";
    request.fragmentFile = desc.fragmentFile ? desc.fragmentFile : "";
    request.computeFile = desc.computeFile ? desc.computeFile : "";
    request.defines = desc.defines ? desc.defines : "";
    request.searchPaths = {pluginSourceDir(techniqueId_)};
    for (const auto& dir : hostShaderPaths()) request.searchPaths.push_back(dir);
    request.label = techniqueId_ + ": ";
    for (const std::string* stage : {&request.vertexFile, &request.geometryFile, &request.fragmentFile, &request.computeFile})
        if (!stage->empty()) request.label += (request.label.back() == ' ' ? "" : " + ") + *stage;
    const ProgramId id = context_.shaders.build(request, error);
    if (id) programs_.push_back(id);
    return id;
}

uint32_t PluginHost::createTexture(const TextureDesc& desc) {
    GLuint name = 0;
    glCreateTextures(desc.target, 1, &name);
    const int levels = std::max(desc.levels, 1);
    const int depth = std::max(desc.depth, 1);
    switch (desc.target) {
    case GL_TEXTURE_2D_ARRAY:
    case GL_TEXTURE_3D:
        glTextureStorage3D(name, levels, desc.internalFormat, desc.width, desc.height, depth);
        break;
    case GL_TEXTURE_CUBE_MAP_ARRAY:   // depth counts cubes; GL counts layer-faces
        glTextureStorage3D(name, levels, desc.internalFormat, desc.width, desc.height, 6 * depth);
        break;
    case GL_TEXTURE_2D_MULTISAMPLE:
        glTextureStorage2DMultisample(name, std::max(desc.samples, 1), desc.internalFormat, desc.width, desc.height, GL_TRUE);
        break;
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY:
        glTextureStorage3DMultisample(name, std::max(desc.samples, 1), desc.internalFormat, desc.width, desc.height, depth,
                                      GL_TRUE);
        break;
    case GL_TEXTURE_1D:
        glTextureStorage1D(name, levels, desc.internalFormat, desc.width);
        break;
    case GL_TEXTURE_1D_ARRAY:
        glTextureStorage2D(name, levels, desc.internalFormat, desc.width, depth);
        break;
    default:   // GL_TEXTURE_2D, GL_TEXTURE_CUBE_MAP (storage of all six faces)
        glTextureStorage2D(name, levels, desc.internalFormat, desc.width, desc.height);
        break;
    }
    const std::string label = techniqueId_ + ": " + (desc.label ? desc.label : "texture");
    glObjectLabel(GL_TEXTURE, name, GLsizei(label.size()), label.c_str());
    textures_[name] = {label, textureBytes(desc)};
    return name;
}

void PluginHost::destroyTexture(uint32_t texture) {
    if (textures_.erase(texture)) glDeleteTextures(1, &texture);
    std::erase_if(debugImages_, [&](const DebugImage& image) { return image.texture == texture; });
}

uint32_t PluginHost::createBuffer(size_t bytes, const void* data, uint32_t storageFlags, const char* label) {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    glNamedBufferStorage(name, GLsizeiptr(bytes), data, storageFlags);
    const std::string text = techniqueId_ + ": " + (label ? label : "buffer");
    glObjectLabel(GL_BUFFER, name, GLsizei(text.size()), text.c_str());
    buffers_[name] = {text, bytes};
    return name;
}

void PluginHost::destroyBuffer(uint32_t buffer) {
    if (buffers_.erase(buffer)) glDeleteBuffers(1, &buffer);
}

uint32_t PluginHost::createFramebuffer(const char* label) {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    const std::string text = techniqueId_ + ": " + (label ? label : "framebuffer");
    glObjectLabel(GL_FRAMEBUFFER, name, GLsizei(text.size()), text.c_str());
    framebuffers_[name] = text;
    return name;
}

void PluginHost::destroyFramebuffer(uint32_t framebuffer) {
    if (framebuffers_.erase(framebuffer)) glDeleteFramebuffers(1, &framebuffer);
}

bool PluginHost::checkFramebuffer(uint32_t framebuffer, const char* what) {
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE) return true;
    logError(techniqueId_ + ": framebuffer '" + (what ? what : "?") + "' is " + framebufferStatusName(status));
    return false;
}

void PluginHost::registerDebugImage(const char* name, uint32_t texture, DebugImageKind kind) {
    const std::string key = name ? name : "image";
    for (auto& image : debugImages_)
        if (image.name == key) {
            image.texture = texture;
            image.kind = kind;
            return;
        }
    debugImages_.push_back({key, texture, kind});
}

size_t PluginHost::gpuBytes() const {
    size_t total = 0;
    for (const auto& [name, allocation] : textures_) total += allocation.bytes;
    for (const auto& [name, allocation] : buffers_) total += allocation.bytes;
    return total;
}

int PluginHost::releaseAll() {
    const int leftovers = int(textures_.size() + buffers_.size() + framebuffers_.size());
    if (leftovers > 0)
        logWarning(techniqueId_ + ": " + std::to_string(leftovers) +
                   " GL object(s) still alive after shutdown(); released by the host");
    for (auto& [name, allocation] : textures_) glDeleteTextures(1, &name);
    for (auto& [name, allocation] : buffers_) glDeleteBuffers(1, &name);
    for (auto& [name, label] : framebuffers_) glDeleteFramebuffers(1, &name);
    for (ProgramId id : programs_) context_.shaders.release(id);
    textures_.clear();
    buffers_.clear();
    framebuffers_.clear();
    programs_.clear();
    debugImages_.clear();
    translucentHook_ = {};   // it points into the library about to be closed
    return leftovers;
}

bool LoadedTechnique::start(HostContext context, const std::filesystem::path& shadowGlsl, std::string& error) {
    shaders_ = &context.shaders;
    shadowGlsl_ = shadowGlsl;
    host_ = std::make_unique<PluginHost>(context, info_);
    for (const FrameOutputs outputs : {FrameOutputs::Colour, FrameOutputs::Accuracy}) {
        const bool accuracy = outputs == FrameOutputs::Accuracy;
        ShaderRequest main;
        main.vertexFile = "main.vert";
        main.fragmentFile = "main.frag";
        main.defines = accuracy ? "SHADOWLAB_ACCURACY_TARGETS 1" : "";
        main.searchPaths = hostShaderPaths();
        main.aliases["technique_shadow.glsl"] = shadowGlsl;
        main.label = info_.id + (accuracy ? ": main pass (accuracy targets)" : ": main pass");
        std::string shaderError;
        mainPrograms_[accuracy ? 1 : 0] = context.shaders.build(main, shaderError);
        if (!mainPrograms_[accuracy ? 1 : 0]) {
            error = "main pass with " + info_.shadowGlsl + " failed to build: " + shaderError;
            return false;
        }
    }
    std::string initError;
    if (!technique_->init(*host_, initError)) {
        error = "init failed: " + (initError.empty() ? std::string("no reason given") : initError);
        return false;   // the destructor shuts down and releases what init created
    }
    return true;
}

std::unique_ptr<LoadedTechnique> LoadedTechnique::load(const std::filesystem::path& file, HostContext context,
                                                       std::string& error) {
    auto loaded = std::unique_ptr<LoadedTechnique>(new LoadedTechnique());
    loaded->library_ = PluginLibrary::open(file, error);
    if (!loaded->library_) return nullptr;
    loaded->info_ = loaded->library_->info();
    loaded->technique_ = loaded->library_->entry().create();
    if (!loaded->technique_) {
        error = file.string() + ": create() returned nothing";
        return nullptr;
    }
    if (!loaded->start(context, pluginSourceDir(loaded->info_.id) / loaded->info_.shadowGlsl, error)) {
        error = file.string() + ": " + error;
        return nullptr;
    }
    return loaded;
}

std::unique_ptr<LoadedTechnique> LoadedTechnique::createBuiltin(const TechniqueInfo& info,
                                                                std::unique_ptr<IShadowTechnique> technique,
                                                                HostContext context, std::string& error) {
    auto loaded = std::unique_ptr<LoadedTechnique>(new LoadedTechnique());
    loaded->info_ = info;
    loaded->builtin_ = std::move(technique);
    loaded->technique_ = loaded->builtin_.get();
    if (!loaded->start(context, sharedShaderDir() / info.shadowGlsl, error)) {
        error = info.id + ": " + error;
        return nullptr;
    }
    return loaded;
}

LoadedTechnique::~LoadedTechnique() {
    // Order matters: a plugin's code lives in its library, so the library goes last.
    if (technique_) {
        technique_->shutdown();
        if (library_) library_->entry().destroy(technique_);
    }
    builtin_.reset();
    if (host_) host_->releaseAll();
    host_.reset();
    for (ProgramId program : mainPrograms_)
        if (program && shaders_) shaders_->release(program);
    for (ProgramId program : variantPrograms_)
        if (program && shaders_) shaders_->release(program);
    library_.reset();
}

GLuint LoadedTechnique::mainProgram(FrameOutputs outputs) const {
    return shaders_->program(mainPrograms_[outputs == FrameOutputs::Accuracy ? 1 : 0]);
}

GLuint LoadedTechnique::mainVariant(int slot, std::string& error) {
    if (!variantPrograms_[slot]) {
        static const char* const defines[kMainVariants] = {
            "SHADOWLAB_EYE_BLUR_TERM 1", "SHADOWLAB_EYE_BLUR_READ 1", "SHADOWLAB_EYE_BLUR_READ 1;SHADOWLAB_ACCURACY_TARGETS 1",
            "SHADOWLAB_ACCURACY_TARGETS 1;SHADOWLAB_TRANSLUCENT_PEEL 1"};
        static const char* const labels[kMainVariants] = {
            ": eye-space blur term pass", ": main pass (blurred shadow term)",
            ": main pass (blurred shadow term, accuracy targets)", ": translucent layer (accuracy targets)"};
        ShaderRequest request;
        request.vertexFile = "main.vert";
        request.fragmentFile = "main.frag";
        request.defines = defines[slot];
        request.searchPaths = hostShaderPaths();
        request.aliases["technique_shadow.glsl"] = shadowGlsl_;
        request.label = info_.id + labels[slot];
        std::string shaderError;
        variantPrograms_[slot] = shaders_->build(request, shaderError);
        if (!variantPrograms_[slot]) {
            error = info_.id + ": " + request.label.substr(info_.id.size() + 2) + " with " + info_.shadowGlsl +
                    " failed to build: " + shaderError;
            return 0;
        }
    }
    return shaders_->program(variantPrograms_[slot]);
}

GLuint LoadedTechnique::eyeBlurTermProgram(std::string& error) { return mainVariant(0, error); }

GLuint LoadedTechnique::eyeBlurMainProgram(FrameOutputs outputs, std::string& error) {
    return mainVariant(outputs == FrameOutputs::Accuracy ? 2 : 1, error);
}

GLuint LoadedTechnique::translucentLayerProgram(std::string& error) { return mainVariant(3, error); }

TechniqueManager::TechniqueManager(HostContext context, std::filesystem::path pluginDir)
    : context_(context), pluginDir_(std::move(pluginDir)) {}

void TechniqueManager::scan(const std::vector<std::string>& reservedIds) {
    PluginScan scan = scanPlugins(pluginDir_, reservedIds);
    techniques_ = std::move(scan.techniques);
    scanErrors_ = std::move(scan.errors);
    for (const auto& error : scanErrors_) logWarning("skipped plugin: " + error);
}

void TechniqueManager::registerBuiltin(const TechniqueInfo& info, BuiltinFactory factory) {
    std::erase_if(techniques_, [&](const TechniqueInfo& t) { return t.id == info.id; });
    techniques_.push_back(info);
    builtins_[info.id] = std::move(factory);
}

const TechniqueInfo* TechniqueManager::find(const std::string& id) const {
    for (const auto& t : techniques_)
        if (t.id == id) return &t;
    return nullptr;
}

LoadedTechnique* TechniqueManager::get(const std::string& id, std::string& error) {
    if (auto it = loaded_.find(id); it != loaded_.end()) return it->second.get();
    const TechniqueInfo* info = find(id);
    if (!info) {
        std::string known;
        for (const auto& t : techniques_) appendListItem(known, t.id);
        error = "no technique '" + id + "' (available: " + known + ")";
        return nullptr;
    }
    std::unique_ptr<LoadedTechnique> loaded;
    if (auto builtin = builtins_.find(id); builtin != builtins_.end())
        loaded = LoadedTechnique::createBuiltin(*info, builtin->second(), context_, error);
    else
        loaded = LoadedTechnique::load(info->library, context_, error);
    if (!loaded) return nullptr;
    auto* raw = loaded.get();
    loaded_[id] = std::move(loaded);
    return raw;
}

std::vector<LoadedTechnique*> TechniqueManager::loadedTechniques() {
    std::vector<LoadedTechnique*> out;
    for (auto& [id, t] : loaded_) out.push_back(t.get());
    return out;
}

std::vector<std::string> TechniqueManager::pollForChanges(ParamStore& params, std::chrono::milliseconds interval) {
    std::vector<std::string> reloaded;
    const auto now = std::chrono::steady_clock::now();
    if (now - lastPoll_ < interval) return reloaded;
    lastPoll_ = now;
    for (auto& [id, loaded] : loaded_) {
        if (!loaded->library()) continue;   // built into the host
        const PluginLibrary& library = *loaded->library();
        const std::filesystem::path file = library.file();   // a copy: the library may be replaced below
        std::error_code ec;
        const auto time = std::filesystem::last_write_time(file, ec);
        const auto size = ec ? 0 : std::filesystem::file_size(file, ec);
        if (ec || (time == library.fileTime() && size == library.fileSize())) {
            pending_.erase(id);
            continue;
        }
        if (auto failed = failed_.find(id); failed != failed_.end() && failed->second.time == time && failed->second.size == size)
            continue;   // this version already failed; wait for the next build
        // The linker may still be writing: reload only once two polls agree on time and size.
        auto pending = pending_.find(id);
        if (pending == pending_.end() || pending->second.time != time || pending->second.size != size) {
            pending_[id] = {time, size, now};
            continue;
        }
        // A linker that pauses longer than a poll leaves an unchanged but incomplete file: wait
        // for a complete ELF image, and call it a failure only once the file has stayed as it is
        // for kReloadSettle (a build that really produced a broken file).
        const bool settled = now - pending->second.since >= kReloadSettle;
        std::string error;
        if (const std::string incomplete = incompleteElfImage(file); !incomplete.empty()) {
            if (!settled) continue;
            error = file.string() + ": " + incomplete + ", unchanged for " +
                    std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(kReloadSettle).count()) + " ms";
        }
        std::unique_ptr<LoadedTechnique> fresh;
        if (error.empty()) fresh = LoadedTechnique::load(file, context_, error);
        if (!fresh) {
            // Rewritten while it was read: a new version, not a failure.
            std::error_code after;
            if (std::filesystem::last_write_time(file, after) != time || std::filesystem::file_size(file, after) != size) {
                pending_.erase(id);
                continue;
            }
            // The dynamic loader refused a file still settling: try again at the next poll.
            if (!settled && error.find("cannot load plugin (") != std::string::npos) continue;
            pending_.erase(id);
            failed_[id] = {time, size, now};
            lastReloadError_ = error;
            logError("hot reload failed, keeping the running version: " + error);
            continue;
        }
        pending_.erase(id);
        failed_.erase(id);
        lastReloadError_.clear();
        params.remap(loaded->info(), fresh->info());
        for (auto& t : techniques_)
            if (t.id == id) t = fresh->info();
        loaded = std::move(fresh);   // the old instance shuts down and unloads here
        logInfo("hot reload: " + id + " reloaded from " + file.string());
        reloaded.push_back(id);
    }
    return reloaded;
}

} // namespace shadowlab
