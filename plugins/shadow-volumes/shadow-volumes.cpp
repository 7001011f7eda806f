// Stencil shadow volumes (Crow 1977; Heidmann 1991; Everitt and Kilgard 2002): seed 000's second
// family of shadow techniques (sec. 2.3.2, "geometry-based" shadows beside maps and rays), which
// seed 002 sets against shadow maps in its sec. 2.3.2: exact hard shadows, per pixel, with no
// resolution, bias or aliasing, paid for in fill rate (volumes cover the screen many times over)
// and in geometry work on the silhouettes.
//
// Per frame: the volumes of every caster are counted in the stencil of the host's camera
// pre-pass (CameraPrepass: its depth in place, no copy; no depth or colour writes,
// GL_DEPTH_CLAMP), and shadowTerm() reads that stencil at its pixel through the host's view of it
// (no mask pass: that cost 0.25 ms at 1080p on an H200; it runs only for the debug image). The
// volumes come from the host's triangles with adjacency (the rules for closed and open meshes are
// explained in volume.geom), found two ways (parameter `extract`):
//   geometry: volume.geom, a geometry stage over the triangles as they are drawn, emits each
//     triangle's sides and caps as strips.
//   compute: a compute pass writes the same sides and caps to buffers, drawn indirectly
//     (volume_records.h: the buffers, the extraction and the draws).
// The host's camera pre-pass is asked for depth only (kTechniqueNeedsCameraDepth): the full pass
// (position, normal, id) cost 2.17 of the 3.69 ms a frame on cube at 1080p on an H200.
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
#include <cmath>
#include <string>

#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/near_plane.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "shadow_volumes_shared.h"
#include "volume_records.h"
#include "volume_targets.h"

namespace {

using namespace shadowlab;
using namespace shadowlab::shared::shadow_volumes;

constexpr ParamDesc kCountingParam = kit::enumParam(
    "counting", "counting", 0, "auto|depth-pass|depth-fail",
    "How the stencil counts volume faces. depth-pass: the faces in front of the scene (fast, wrong with the camera "
    "inside a shadow: regions invert). depth-fail: the faces behind it (right everywhere, needs the caps). auto: "
    "depth-fail only when the near plane, swept towards the light, touches a caster.");
constexpr ParamDesc kDebugImagesParam = {
    "debug_images", "debug images", ParamType::Bool, 0, 1, 0, "",
    "Draw the 'volume overdraw' and 'silhouette edges' images every frame (two more passes over the volumes: leave "
    "off when timing).",
    nullptr};
constexpr ParamDesc kExtractParam = kit::enumParam(
    "extract", "extract", 1, "geometry|compute",
    "Where the silhouettes are found. geometry: a geometry stage over the triangles with adjacency emits each "
    "triangle's sides and caps as it is drawn. compute: a compute pass writes them to a buffer, counted with atomics "
    "into indirect draw commands, drawn with glDrawArraysIndirect. The same volumes and image; compute holds a "
    "buffer for the worst case (72 bytes a caster triangle of a closed mesh, 108 of an open one) and falls back to "
    "geometry, with a warning, where that does not fit. Default compute: on an H200 it was faster on dragon-like.");
#define SHADOW_VOLUMES_PARAMS(X)         \
    X(int, counting, kCountingParam)     \
    X(int, extract, kExtractParam)       \
    X(bool, debug_images, kDebugImagesParam)
SHADOWLAB_PARAMS(Params, SHADOW_VOLUMES_PARAMS);
enum Counting : int { kAuto = 0, kDepthPass = 1, kDepthFail = 2 };
enum Extract : int { kGeometry = 0, kCompute = 1 };

class ShadowVolumes final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        const bool built =
            volumes_.build(host(), {.vertexFile = "volume.vert", .geometryFile = "volume.geom", .fragmentFile = "volume_count.frag"}, error) &&
            edges_.build(host(), {.vertexFile = "volume.vert", .geometryFile = "volume.geom", .fragmentFile = "volume_count.frag",
                                  .defines = "SHADOW_VOLUME_EDGES 1"}, error) &&
            fill_.build(host(), {.vertexFile = "fullscreen.vert", .fragmentFile = "volume_count.frag"}, error) && records_.create(host(), error);
        if (built) counters_.create();
        return built;
    }

    void shutdown() override {
        counters_.destroy();
        records_.destroy();
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        stencil_ = 0;
        if (!prepass || !prepass->depth || prepass->structSize < sizeof(CameraPrepass) || !allocate(prepass->size) ||
            !targets_.attachPrepass(host(), *prepass))
            return;
        counters_.read(host(), frameCount_, targets_.size);
        const Params values = Params::read(params);
        const bool depthFail = values.counting == kDepthFail ||
                               (values.counting == kAuto && kit::nearPlaneMayBeInShadow(frame, host().objects(), host().objectCount()));
        host().reportStatistic("depth-fail", depthFail ? 1.0 : 0.0);
        // The volumes start 1e-4 of the scene's size beyond each caster, as the reference's rays do.
        const Bounds scene = host().bounds(DrawSet::All);
        const float push = 1e-4f * std::max(glm::length(scene.max - scene.min),
                                            std::max(glm::length(scene.min), glm::length(scene.max)));
        const AdjacencyScene* casters = nullptr;
        if (values.extract == kCompute) casters = records_.prepare();
        else records_.release();
        host().reportStatistic("extract compute", casters ? 1.0 : 0.0);
        {
            GpuPass pass(host(), "shadow volumes");
            if (casters) records_.extract(*casters, push);
            clearStencil();
            countVolumes(depthFail, casters ? nullptr : &volumes_, push);
            if (values.debug_images) writeMask();
        }
        ++frameCount_;
        stencil_ = prepass->stencil;
        if (values.debug_images) drawDebugImages(push, casters != nullptr);
    }

    void bindMainPass(const FrameContext&, const ParamValues&) override {
        glBindTextureUnit(kVolumeMaskUnit, stencil_);   // the pre-pass's stencil (CameraPrepass::stencil)
        glBindSampler(kVolumeMaskUnit, host().sampler(SamplerKind::Nearest));
    }

    // The host clears the stencil with the depth, but views side by side share the pre-pass.
    void clearStencil() {
        host().beginGpuPass("volume stencil clear");
        glBindFramebuffer(GL_FRAMEBUFFER, targets_.framebuffer);
        glViewport(0, 0, targets_.size.x, targets_.size.y);
        glStencilMask(0xFF);
        glClearStencil(0);
        glClear(GL_STENCIL_BUFFER_BIT);
        host().endGpuPass();
    }

    // The volumes into the stencil, no depth or colour writes: depth-pass counts the faces in
    // front of the scene (+1 facing the eye, -1 facing away), depth-fail those behind it (-1
    // front, +1 back; Carmack's reverse). Counted by queries read frames later (VolumeCounters).
    void countVolumes(bool depthFail, const kit::Program* program, float push) {
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
        counters_.begin(frameCount_);
        drawVolumes(program, push);
        counters_.end(frameCount_);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        host().endGpuPass();
    }

    // The mask: 0 everywhere, 1 where the count is zero.
    void writeMask() {
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

    // The volumes: through the geometry stage `program` (volume.geom), or with a null program the
    // records of this frame's extraction, drawn indirectly (`edges`: their edges as lines).
    // `increment`: what each fragment adds to a debug image.
    void drawVolumes(const kit::Program* program, float push, float increment = 1.0f, bool edges = false) {
        if (!program) return records_.draw(push, increment, edges);
        glUseProgram(program->get());
        glUniform1f(kPushLocation, push);
        glUniform1f(kIncrementLocation, increment);
        DrawRequest request;
        request.set = DrawSet::Casters;
        request.primitive = DrawPrimitive::TrianglesAdjacency;
        host().drawScene(request, program->get());
    }

    // Overdraw (every volume fragment, depth ignored, 1/16 each) and the silhouette edges.
    void drawDebugImages(float push, bool computed) {
        GpuPass pass(host(), "volume debug images");
        glBindFramebuffer(GL_FRAMEBUFFER, targets_.debugFramebuffer);
        glViewport(0, 0, targets_.size.x, targets_.size.y);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glEnable(GL_DEPTH_CLAMP);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        const float clear = 0.0f;
        glNamedFramebufferTexture(targets_.debugFramebuffer, GL_COLOR_ATTACHMENT0, targets_.overdraw, 0);
        glClearBufferfv(GL_COLOR, 0, &clear);
        drawVolumes(computed ? nullptr : &volumes_, push, 1.0f / 16.0f);
        glNamedFramebufferTexture(targets_.debugFramebuffer, GL_COLOR_ATTACHMENT0, targets_.edgeImage, 0);
        glClearBufferfv(GL_COLOR, 0, &clear);
        drawVolumes(computed ? nullptr : &edges_, push, 1.0f, true);
        glDisable(GL_BLEND);
    }

    // The targets at the camera pre-pass's size, reallocated only when it changes.
    bool allocate(glm::ivec2 size) {
        if (size == targets_.size && targets_.framebuffer) return true;
        counters_.forget();
        return targets_.allocate(host(), size);
    }

    kit::Program volumes_, edges_, fill_;
    shadow_volumes::VolumeRecords records_;   // extract = compute
    shadow_volumes::VolumeTargets targets_;
    shadow_volumes::VolumeCounters counters_;
    uint64_t frameCount_ = 0;
    uint32_t stencil_ = 0;   // this frame's count (the pre-pass's stencil view), 0: none counted
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kCasterGeometry,   // no map for the host's views
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
     .flags = kTechniqueNeedsCameraDepth},   // the depth alone: no position, normal or id
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(ShadowVolumes, kDescriptor)
