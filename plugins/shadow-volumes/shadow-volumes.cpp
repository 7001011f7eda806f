// Stencil shadow volumes (Crow 1977; Heidmann 1991; Everitt and Kilgard 2002): seed 000's second
// family of shadow techniques (sec. 2.3.2, "geometry-based" shadows beside maps and rays), which
// seed 002 sets against shadow maps in its sec. 2.3.2: exact hard shadows, per pixel, with no
// resolution, bias or aliasing, paid for in fill rate (volumes cover the screen many times over)
// and in geometry work on the silhouettes.
//
// Per frame: the host's camera pre-pass gives the visible depth; it is copied into this
// technique's depth-stencil target, the volumes of every caster are drawn into the stencil (no
// depth or colour writes, GL_DEPTH_CLAMP), and one full-screen pass turns "stencil != 0" into a
// screen mask that shadowTerm() reads at its pixel. The volumes come from volume.geom over the
// host's triangles with adjacency (the rules for closed and open meshes are explained there).
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
#define SHADOW_VOLUMES_PARAMS(X)         \
    X(int, counting, kCountingParam)     \
    X(bool, debug_images, kDebugImagesParam)
SHADOWLAB_PARAMS(Params, SHADOW_VOLUMES_PARAMS);
enum Counting : int { kAuto = 0, kDepthPass = 1, kDepthFail = 2 };

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "shadow-volumes",
     .displayName = "Shadow volumes (stencil)",
     .category = "hard",
     .explanation = "Extrudes every caster's silhouette away from the light into a volume and counts, per pixel, how "
                    "many volume faces lie between the eye and the surface: a non-zero count means shadow. The result "
                    "is exact to the pixel, with no shadow map, resolution, bias or acne, at the price of fill rate: "
                    "the volumes cover the screen many times where casters are many or the light is low. Try the "
                    "camera inside a shadow with counting = depth-pass (regions invert) against depth-fail. "
                    "Translucent casters block like opaque ones. Its images (debug images on): volume overdraw, "
                    "silhouette edges, and the volume mask.",
     .shadowGlsl = "shadow-volumes.glsl",
     .flags = kTechniqueNeedsCameraPrepass,
     .translucencyModel = TranslucencyModel::Opaque,
     .debugViews = ""},   // the host's views need a map; its own images are listed with them
    Params::table);

class ShadowVolumes final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!volumes_.build(host(), {.vertexFile = "volume.vert", .geometryFile = "volume.geom", .fragmentFile = "volume_count.frag"}, error) ||
            !edges_.build(host(), {.vertexFile = "volume.vert", .geometryFile = "volume.geom", .fragmentFile = "volume_count.frag",
                                   .defines = "SHADOW_VOLUME_EDGES 1"}, error) ||
            !fill_.build(host(), {.vertexFile = "fullscreen.vert", .fragmentFile = "volume_count.frag"}, error))
            return false;
        glCreateQueries(GL_SAMPLES_PASSED, GLsizei(samples_.size()), samples_.data());
        glCreateQueries(GL_PRIMITIVES_GENERATED, GLsizei(primitives_.size()), primitives_.data());
        return true;
    }

    void shutdown() override {
        glDeleteQueries(GLsizei(samples_.size()), samples_.data());
        glDeleteQueries(GLsizei(primitives_.size()), primitives_.data());
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
        {
            GpuPass pass(host(), "shadow volumes");
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
            drawVolumes(volumes_, push);
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
            glUniform1f(17, 1.0f);
            host().drawFullscreenTriangle();
        }
        ++frameCount_;
        if (values.debug_images) drawDebugImages(push);
    }

    void bindMainPass(const FrameContext&, const ParamValues&) override {
        glBindTextureUnit(kVolumeMaskUnit, mask_);
        glBindSampler(kVolumeMaskUnit, host().sampler(SamplerKind::Nearest));
    }

    void drawVolumes(const kit::Program& program, float push) {
        glUseProgram(program.get());
        glUniform1f(kPushLocation, push);
        DrawRequest request;
        request.set = DrawSet::Casters;
        request.primitive = DrawPrimitive::TrianglesAdjacency;
        host().drawScene(request, program.get());
    }

    // Overdraw (every volume fragment, depth ignored, 1/16 each) and the silhouette edges.
    void drawDebugImages(float push) {
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
        glUseProgram(volumes_.get());
        glUniform1f(17, 1.0f / 16.0f);
        drawVolumes(volumes_, push);
        glNamedFramebufferTexture(debugFramebuffer_, GL_COLOR_ATTACHMENT0, edgeImage_, 0);
        glClearBufferfv(GL_COLOR, 0, &clear);
        glUseProgram(edges_.get());
        glUniform1f(17, 1.0f);
        drawVolumes(edges_, push);
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

    kit::Program volumes_, edges_, fill_;
    kit::Texture depthStencil_, mask_, overdraw_, edgeImage_;
    kit::Framebuffer framebuffer_, debugFramebuffer_;
    glm::ivec2 size_{0};
    std::array<GLuint, 3> samples_{}, primitives_{};
    std::array<bool, 3> pending_{};
    uint64_t frameCount_ = 0;
};

} // namespace

SHADOWLAB_PLUGIN(ShadowVolumes, kDescriptor)
