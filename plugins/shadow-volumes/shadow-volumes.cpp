// Stencil shadow volumes (Crow 1977; Heidmann 1991; Everitt and Kilgard 2002): seed 000's second
// family of shadow techniques (sec. 2.3.2, "geometry-based" shadows beside maps and rays), which
// seed 002 sets against shadow maps in its sec. 2.3.2: exact hard shadows, per pixel, with no
// resolution, bias or aliasing, paid for in fill rate (volumes cover the screen many times over)
// and in geometry work on the silhouettes.
//
// Per frame: the host's camera pre-pass gives the visible depth; it is copied into this
// technique's depth-stencil target, the volumes of every caster are drawn into the stencil (no
// depth or colour writes, GL_DEPTH_CLAMP), and one full-screen pass turns "stencil != 0" into a
// screen mask that shadowTerm() reads at its pixel. The volumes come from the host's triangles
// with adjacency (the rules for closed and open meshes are explained in volume.geom), found two
// ways (parameter `extract`):
//   geometry: volume.geom, a geometry stage over the triangles as they are drawn, emits each
//     triangle's sides and caps as strips.
//   compute: volume_extract.comp, one invocation per caster triangle, writes the same sides and
//     caps as records to storage buffers, counting them with atomics into three indirect draw
//     commands, and volume_indirect.vert draws them with glDrawArraysIndirect (dormon/Shadows'
//     CSSV approach). The buffers hold the worst case (a side per edge of a closed mesh, three
//     sides a triangle of any other, a cap a triangle), allocated when the scene's casters change,
//     never per frame; the CPU never reads the counts. Same decisions, same vertices, the same
//     triangles: the image is the geometry variant's (on llvmpipe but for single pixels where a
//     volume face meets the visible surface, whose depth rounds differently after a geometry
//     stage: docs/shadow-volumes.md).
// The host's camera pre-pass is asked for depth only (kTechniqueNeedsCameraDepth): the volumes
// need nothing else, and the full pass (position, normal, id) cost 2.17 of the 3.69 ms a frame
// on cube at 1080p on an H200.
//
// Counting (parameter `counting`):
//   depth-pass (Heidmann): +1 for volume faces facing the eye in front of the scene, -1 for faces
//     facing away. Cheap, but wrong when the eye is inside a volume (the count starts off by one):
//     whole screen regions invert.
//   depth-fail (Carmack's reverse): counts the faces behind the scene instead (-1 front, +1 back),
//     which needs the caps (drawn always here) but is right wherever the eye is.
//   auto: depth-fail only when the near plane, swept towards the light, touches a caster's
//     bounds (the only case depth-pass gets wrong), else depth-pass.
// Artefacts: none of the maps' (no acne, aliasing or peter panning); edges are the exact
// silhouettes, so their hardness is the look of a point light. Translucent casters are treated as
// opaque (the stencil counts surfaces, not their transmission). Receivers that are not in the
// opaque pre-pass (translucent surfaces) read the mask of the opaque surface behind them.
// Debug views (`debug_images`): "volume overdraw" (volume fragments per pixel, 1/16 each, white at
// 16 and more) and "silhouette edges" (the edges volumes are extruded from, seen from the camera).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/near_plane.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "shadow_volumes_shared.h"

namespace {

using namespace shadowlab;
using namespace shadowlab::shared::shadow_volumes;

constexpr ParamDesc kCountingParam = {
    "counting", "counting", ParamType::Enum, 0, 2, 0, "",
    "How the stencil counts volume faces. depth-pass: the faces in front of the scene (fast, wrong with the camera "
    "inside a shadow: regions invert). depth-fail: the faces behind it (right everywhere, needs the caps). auto: "
    "depth-fail only when the near plane, swept towards the light, touches a caster.",
    "auto|depth-pass|depth-fail"};
constexpr ParamDesc kDebugImagesParam = {
    "debug_images", "debug images", ParamType::Bool, 0, 1, 0, "",
    "Draw the 'volume overdraw' and 'silhouette edges' images every frame (two more passes over the volumes: leave "
    "off when timing).",
    nullptr};
constexpr ParamDesc kExtractParam = {
    "extract", "extract", ParamType::Enum, 0, 1, 0, "",
    "Where the silhouettes are found. geometry: a geometry stage over the triangles with adjacency emits each "
    "triangle's sides and caps as it is drawn. compute: a compute pass writes them to a buffer, counted with atomics "
    "into indirect draw commands, drawn with glDrawArraysIndirect. The same volumes and image; compute holds a "
    "buffer for the worst case (72 bytes a caster triangle of a closed mesh, 108 of an open one) and falls back to "
    "geometry, with a warning, where that does not fit.",
    "geometry|compute"};
#define SHADOW_VOLUMES_PARAMS(X)         \
    X(int, counting, kCountingParam)     \
    X(int, extract, kExtractParam)       \
    X(bool, debug_images, kDebugImagesParam)
SHADOWLAB_PARAMS(Params, SHADOW_VOLUMES_PARAMS);
enum Counting : int { kAuto = 0, kDepthPass = 1, kDepthFail = 2 };
enum Extract : int { kGeometry = 0, kCompute = 1 };

// The records volume_extract.comp writes (shadow_volumes_shared.h).
constexpr uint64_t kSideBytes = 6 * sizeof(float);
constexpr uint64_t kCapBytes = 9 * sizeof(float);

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "shadow-volumes",
     .displayName = "Shadow volumes (stencil)",
     .category = "hard",
     .explanation = "Extrudes every caster's silhouette away from the light into a volume and counts, per pixel, how "
                    "many volume faces lie between the eye and the surface: a non-zero count means shadow. The result "
                    "is exact to the pixel, with no shadow map, resolution, bias or acne, at the price of fill rate: "
                    "the volumes cover the screen many times where casters are many or the light is low. Try the "
                    "camera inside a shadow with counting = depth-pass (regions invert) against depth-fail. The "
                    "silhouettes are found by a geometry stage or (extract = compute) a compute pass drawn "
                    "indirectly. Translucent casters block like opaque ones. Its images (debug images on): volume "
                    "overdraw, silhouette edges, and the volume mask.",
     .shadowGlsl = "shadow-volumes.glsl",
     .flags = kTechniqueNeedsCameraDepth,   // the depth alone: no position, normal or id
     .translucencyModel = TranslucencyModel::Opaque,
     .debugViews = ""},   // the host's views need a map; its own images are listed with them
    Params::table);

class ShadowVolumes final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!volumes_.build(host(), {.vertexFile = "volume.vert", .geometryFile = "volume.geom", .fragmentFile = "volume_count.frag"}, error) ||
            !edges_.build(host(), {.vertexFile = "volume.vert", .geometryFile = "volume.geom", .fragmentFile = "volume_count.frag",
                                   .defines = "SHADOW_VOLUME_EDGES 1"}, error) ||
            !fill_.build(host(), {.vertexFile = "fullscreen.vert", .fragmentFile = "volume_count.frag"}, error) ||
            !extract_.build(host(), {.computeFile = "volume_extract.comp"}, error) ||
            !indirect_.build(host(), {.vertexFile = "volume_indirect.vert", .fragmentFile = "volume_count.frag"}, error))
            return false;
        glCreateQueries(GL_SAMPLES_PASSED, GLsizei(samples_.size()), samples_.data());
        glCreateQueries(GL_PRIMITIVES_GENERATED, GLsizei(primitives_.size()), primitives_.data());
        glCreateVertexArrays(1, &emptyVao_);   // the indirect draws fetch no attributes
        GLint maxBlock = 0;
        glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
        maxBlockBytes_ = uint64_t(std::max(maxBlock, 0));
        return true;
    }

    void shutdown() override {
        glDeleteQueries(GLsizei(samples_.size()), samples_.data());
        glDeleteQueries(GLsizei(primitives_.size()), primitives_.data());
        glDeleteVertexArrays(1, &emptyVao_);
        emptyVao_ = 0;
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        if (!prepass || !prepass->depth || !allocate(prepass->size)) return;
        readStatistics();
        const Params values = Params::read(params);
        const int counting = values.counting;
        const bool depthFail =
            counting == kDepthFail || (counting == kAuto && kit::nearPlaneMayBeInShadow(frame, host().objects(), host().objectCount()));
        host().reportStatistic("depth-fail", depthFail ? 1.0 : 0.0);
        // The volumes start 1e-4 of the scene's size beyond each caster, as the reference's rays do.
        const Bounds scene = host().bounds(DrawSet::All);
        const float push = 1e-4f * std::max(glm::length(scene.max - scene.min),
                                            std::max(glm::length(scene.min), glm::length(scene.max)));
        const AdjacencyScene* casters = values.extract == kCompute ? computeScene() : releaseRecords();
        host().reportStatistic("extract compute", casters ? 1.0 : 0.0);
        {
            GpuPass pass(host(), "shadow volumes");
            if (casters) extract(*casters, push);
            host().beginGpuPass("volume depth copy");
            glCopyImageSubData(prepass->depth, GL_TEXTURE_2D, 0, 0, 0, 0, depthStencil_, GL_TEXTURE_2D, 0, 0, 0, 0, size_.x,
                               size_.y, 1);
            glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
            glViewport(0, 0, size_.x, size_.y);
            glClearStencil(0);
            glClear(GL_STENCIL_BUFFER_BIT);
            host().endGpuPass();
            host().beginGpuPass("volume stencil");
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            glDepthMask(GL_FALSE);
            glDepthFunc(GL_LESS);
            glEnable(GL_DEPTH_CLAMP);
            glEnable(GL_STENCIL_TEST);
            glStencilFunc(GL_ALWAYS, 0, 0xFF);
            if (depthFail) {
                glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
                glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
            } else {
                glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
                glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
            }
            const size_t slot = frameCount_ % samples_.size();
            glBeginQuery(GL_SAMPLES_PASSED, samples_[slot]);
            glBeginQuery(GL_PRIMITIVES_GENERATED, primitives_[slot]);
            drawVolumes(casters ? nullptr : &volumes_, push);
            glEndQuery(GL_PRIMITIVES_GENERATED);
            glEndQuery(GL_SAMPLES_PASSED);
            pending_[slot] = true;
            host().endGpuPass();
            // The mask: 0 everywhere, 1 where the count is zero.
            GpuPass mask(host(), "volume mask");
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            const float shadowed = 0.0f;
            glClearBufferfv(GL_COLOR, 0, &shadowed);
            glDisable(GL_DEPTH_TEST);
            glStencilFunc(GL_EQUAL, 0, 0xFF);
            glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
            glUseProgram(fill_.get());
            glUniform1f(kIncrementLocation, 1.0f);
            host().drawFullscreenTriangle();
        }
        ++frameCount_;
        if (values.debug_images) drawDebugImages(push, casters != nullptr);
    }

    void bindMainPass(const FrameContext&, const ParamValues&) override {
        glBindTextureUnit(kVolumeMaskUnit, mask_);
        glBindSampler(kVolumeMaskUnit, host().sampler(SamplerKind::Nearest));
    }

    // The volumes: through the geometry stage `program` (volume.geom), or with a null program the
    // records of this frame's extraction, drawn indirectly (`edges`: their edges as lines).
    // `increment`: what each fragment adds to a debug image.
    void drawVolumes(const kit::Program* program, float push, float increment = 1.0f, bool edges = false) {
        if (!program) {
            glUseProgram(indirect_.get());
            glUniform1f(kPushLocation, push);
            glUniform1f(kIncrementLocation, increment);
            glUniform2ui(kCapacityLocation, sideCapacity_, capCapacity_);
            glBindVertexArray(emptyVao_);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSidesBinding, sides_);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCapsBinding, caps_);
            glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_);
            auto draw = [](GLenum mode, int what, uint32_t command) {
                glUniform1i(kDrawLocation, what);
                glDrawArraysIndirect(mode, reinterpret_cast<const void*>(uintptr_t(command) * sizeof(uint32_t)));
            };
            if (edges) {
                draw(GL_LINES, kDrawEdges, kSideCommand);
            } else {
                draw(GL_TRIANGLES, kDrawSides, kSideCommand);
                draw(GL_TRIANGLES, kDrawNearCaps, kNearCapCommand);
                draw(GL_TRIANGLES, kDrawFarCaps, kFarCapCommand);   // count 0 under a directional light
            }
            glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
            return;
        }
        glUseProgram(program->get());
        glUniform1f(kPushLocation, push);
        glUniform1f(kIncrementLocation, increment);
        DrawRequest request;
        request.set = DrawSet::Casters;
        request.primitive = DrawPrimitive::TrianglesAdjacency;
        host().drawScene(request, program->get());
    }

    // extract = compute: the host's casters with adjacency, with the record buffers sized for
    // them; null (the geometry stage draws instead, said once per scene) when the host lacks the
    // extension or the worst case does not fit a storage block.
    const AdjacencyScene* computeScene() {
        const auto* access = static_cast<const Adjacency*>(host().extension(SHADOWLAB_EXT_ADJACENCY));
        const AdjacencyScene* scene = access ? access->scene(access->context) : nullptr;
        if (!scene) {
            if (!warned_) host().log(LogLevel::Warning, "extract = compute: the host has no adjacency extension; using the geometry stage");
            warned_ = true;
            return nullptr;
        }
        // The worst case: a side per edge of a closed mesh (3 per 2 triangles), three sides a
        // triangle of any other mesh, a cap a triangle (volume.geom's rules).
        const uint64_t sides = std::max<uint64_t>(1, (scene->closedTriangles * 3 + 1) / 2 + (scene->triangles - scene->closedTriangles) * 3);
        const uint64_t caps = std::max<uint64_t>(1, scene->triangles);
        if (sides == sideCapacity_ && caps == capCapacity_ && commands_) return scene;
        sides_ = {};
        caps_ = {};
        sideCapacity_ = capCapacity_ = 0;
        const uint64_t bytes = std::max(sides * kSideBytes, caps * kCapBytes);
        if (bytes > maxBlockBytes_ || sides > UINT32_MAX / 6 || caps > UINT32_MAX / 3) {
            if (!warned_)
                host().log(LogLevel::Warning, ("extract = compute: the worst case of " + std::to_string(scene->triangles) +
                                               " caster triangles needs a storage block of " + std::to_string(bytes >> 20) +
                                               " MiB, over the device's " + std::to_string(maxBlockBytes_ >> 20) +
                                               " MiB; using the geometry stage").c_str());
            warned_ = true;
            return nullptr;
        }
        sides_ = kit::Buffer(host(), host().createBuffer(size_t(sides * kSideBytes), nullptr, 0, "volume sides"));
        caps_ = kit::Buffer(host(), host().createBuffer(size_t(caps * kCapBytes), nullptr, 0, "volume caps"));
        if (!commands_) {   // {count, instances 1, first 0, base instance 0} x 3; the counts cleared every frame
            const uint32_t commands[12] = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
            commands_ = kit::Buffer(host(), host().createBuffer(sizeof(commands), commands, 0, "volume indirect draws"));
        }
        sideCapacity_ = uint32_t(sides);
        capCapacity_ = uint32_t(caps);
        warned_ = false;
        return scene;
    }

    // extract = geometry: the compute variant's buffers go (on the frame the parameter changes; a
    // no-op after), so the technique's memory is the variant's own.
    const AdjacencyScene* releaseRecords() {
        sides_ = {};
        caps_ = {};
        commands_ = {};
        sideCapacity_ = capCapacity_ = 0;
        return nullptr;
    }

    // The sides and caps of every caster into the record buffers and the draw counts, one dispatch
    // per batch of objects sharing a mesh (chunked so no index overflows).
    void extract(const AdjacencyScene& scene, float push) {
        GpuPass pass(host(), "volume extract");
        const GLuint zero = 0;
        for (uint32_t command : {kSideCommand, kNearCapCommand, kFarCapCommand})
            glClearNamedBufferSubData(commands_, GL_R32UI, command * sizeof(uint32_t), sizeof(uint32_t), GL_RED_INTEGER,
                                      GL_UNSIGNED_INT, &zero);
        glUseProgram(extract_.get());
        glUniform1f(kPushLocation, push);
        glUniform2ui(kCapacityLocation, sideCapacity_, capCapacity_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, scene.transforms);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, scene.vertices);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kAdjacencyBinding, scene.indices);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSidesBinding, sides_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCapsBinding, caps_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandsBinding, commands_);
        constexpr uint64_t kMaxGroupsX = 65535, kMaxInvocations = uint64_t(1) << 31;
        for (uint32_t b = 0; b < scene.batchCount; ++b) {
            const AdjacencyBatch& batch = scene.batches[b];
            if (batch.triangleCount == 0) continue;
            glUniform2i(kMeshLocation, batch.baseVertex, GLint(batch.closed));
            const uint32_t perDispatch = uint32_t(std::clamp<uint64_t>(kMaxInvocations / batch.triangleCount, 1, batch.objectCount));
            for (uint32_t first = 0; first < batch.objectCount; first += perDispatch) {
                const uint32_t objects = std::min(perDispatch, batch.objectCount - first);
                const uint64_t groups = (uint64_t(objects) * batch.triangleCount + kExtractGroupSize - 1) / kExtractGroupSize;
                const uint64_t x = std::min(groups, kMaxGroupsX);
                glUniform4ui(kBatchLocation, batch.firstObject + first, objects, batch.firstTriangle, batch.triangleCount);
                glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
            }
        }
        // The draws read the commands and the records; next frame's clear follows the atomics.
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }

    // Overdraw (every volume fragment, depth ignored, 1/16 each) and the silhouette edges.
    void drawDebugImages(float push, bool computed) {
        GpuPass pass(host(), "volume debug images");
        glBindFramebuffer(GL_FRAMEBUFFER, debugFramebuffer_);
        glViewport(0, 0, size_.x, size_.y);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glEnable(GL_DEPTH_CLAMP);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        const float clear = 0.0f;
        glNamedFramebufferTexture(debugFramebuffer_, GL_COLOR_ATTACHMENT0, overdraw_, 0);
        glClearBufferfv(GL_COLOR, 0, &clear);
        drawVolumes(computed ? nullptr : &volumes_, push, 1.0f / 16.0f);
        glNamedFramebufferTexture(debugFramebuffer_, GL_COLOR_ATTACHMENT0, edgeImage_, 0);
        glClearBufferfv(GL_COLOR, 0, &clear);
        drawVolumes(computed ? nullptr : &edges_, push, 1.0f, true);
        glDisable(GL_BLEND);
    }

    // The counters of a frame two or more frames back, when the GPU has them (never a stall).
    void readStatistics() {
        const size_t slot = (frameCount_ + 1) % samples_.size();
        if (!pending_[slot]) return;
        GLuint available = 0;
        glGetQueryObjectuiv(samples_[slot], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return;
        GLuint64 samples = 0, primitives = 0;
        glGetQueryObjectui64v(samples_[slot], GL_QUERY_RESULT, &samples);
        glGetQueryObjectui64v(primitives_[slot], GL_QUERY_RESULT, &primitives);
        pending_[slot] = false;
        host().reportStatistic("volume samples passing depth per pixel", double(samples) / double(size_.x * size_.y));
        host().reportStatistic("volume triangles", double(primitives));
    }

    bool allocate(glm::ivec2 size) {
        if (size == size_ && framebuffer_) return true;
        size_ = size;
        depthStencil_ = kit::Texture(host(), host().createTexture({.internalFormat = GL_DEPTH24_STENCIL8, .width = size.x,
                                                                   .height = size.y, .label = "volume depth and stencil"}));
        mask_ = kit::Texture(host(), host().createTexture({.internalFormat = GL_R8, .width = size.x, .height = size.y,
                                                           .label = "volume mask"}));
        overdraw_ = kit::Texture(host(), host().createTexture({.internalFormat = GL_R8, .width = size.x, .height = size.y,
                                                               .label = "volume overdraw"}));
        edgeImage_ = kit::Texture(host(), host().createTexture({.internalFormat = GL_R8, .width = size.x, .height = size.y,
                                                                .label = "silhouette edges"}));
        framebuffer_ = kit::Framebuffer(host(), host().createFramebuffer("shadow volumes"));
        glNamedFramebufferTexture(framebuffer_, GL_DEPTH_STENCIL_ATTACHMENT, depthStencil_, 0);
        glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, mask_, 0);
        debugFramebuffer_ = kit::Framebuffer(host(), host().createFramebuffer("shadow volume debug images"));
        glNamedFramebufferTexture(debugFramebuffer_, GL_COLOR_ATTACHMENT0, overdraw_, 0);
        host().registerDebugImage("volume mask", mask_, DebugImageKind::Mask);
        host().registerDebugImage("volume overdraw", overdraw_, DebugImageKind::Mask);
        host().registerDebugImage("silhouette edges", edgeImage_, DebugImageKind::Mask);
        pending_.fill(false);
        return host().checkFramebuffer(framebuffer_, "shadow volumes") &&
               host().checkFramebuffer(debugFramebuffer_, "shadow volume debug images");
    }

    kit::Program volumes_, edges_, fill_, extract_, indirect_;
    // extract = compute: the records (capacities in records, 0 until allocated), the commands, a
    // vertex array without attributes, and whether the fallback to geometry was said.
    kit::Buffer sides_, caps_, commands_;
    uint32_t sideCapacity_ = 0, capCapacity_ = 0;
    GLuint emptyVao_ = 0;
    uint64_t maxBlockBytes_ = 0;
    bool warned_ = false;
    kit::Texture depthStencil_, mask_, overdraw_, edgeImage_;
    kit::Framebuffer framebuffer_, debugFramebuffer_;
    glm::ivec2 size_{0};
    std::array<GLuint, 3> samples_{}, primitives_{};
    std::array<bool, 3> pending_{};
    uint64_t frameCount_ = 0;
};

} // namespace

SHADOWLAB_PLUGIN(ShadowVolumes, kDescriptor)
