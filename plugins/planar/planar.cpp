// Planar projected shadows (Blinn 1988; seed 000 sections 2.2.3 and 3.2.1, eq. 3.1-3.3).
// Each caster is flattened onto every receiver plane by the projection matrix of
// planar_projection.h and drawn into a screen-space mask that the main pass reads. Here the
// classic special cases are handled:
//  - stencil: the shadow is kept on the receiver's visible pixels (no shadow "in the air" beyond
//    the receiver's edge, seed 000 Fig. 3.2b). The classic method writes a stencil id per plane;
//    here the host's camera pre-pass gives every pixel its object id, and the mask pass keeps a
//    flattened caster only where its plane is the visible surface (the same test, no stencil);
//  - anti-shadows: caster parts farther from the plane than the light (seed 000 Fig. 3.3) and parts
//    below the receiver are clipped with gl_ClipDistance, exactly, before projection;
//  - z-fighting: a negative depth offset lifts the shadow above its plane (Fig. 3.2a); the depth
//    test runs against the pre-pass depth (attached read-only);
//  - double darkening: the mask is written, not blended, so overlapping casters darken once.
// Known limits: receivers must be planes, objects never shadow themselves or curved receivers.
#include <vector>

#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "shadowlab/kit/planar_projection.h"
#include "planar_shared.h"

namespace {

using namespace shadowlab;
using shared::planar::PlanarUniforms;

constexpr ParamDesc kDepthOffset{"depth_offset", "depth offset", ParamType::Float, 0, 8, 1, "",
     "Negative polygon offset (factor and units) that lifts the flattened shadow above the receiver. "
     "At zero the shadow and the plane fight for the same depth (z-fighting, seed 000 Fig. 3.2a).", nullptr};
constexpr ParamDesc kClipAntiShadow{"clip_anti_shadow", "clip anti-shadows", ParamType::Bool, 0, 1, 1, "",
     "Clip the parts of casters above a point light (and below the plane) before projecting, so no caster "
     "throws an impossible anti-shadow (seed 000 Fig. 3.3). Off, only the rasteriser's clipping of points with "
     "negative w remains: it removes anti-shadows in front of the viewer but not those projected behind it.", nullptr};
constexpr ParamDesc kStencil{"stencil", "stencil to receiver", ParamType::Bool, 0, 1, 1, "",
     "Keep each shadow on the visible pixels of its receiver plane. Off, shadows can fall beyond the edge "
     "of the receiver (seed 000 Fig. 3.2b).", nullptr};

#define PLANAR_PARAMS(X)                       \
    X(float, depth_offset, kDepthOffset)       \
    X(bool, clip_anti_shadow, kClipAntiShadow) \
    X(bool, stencil, kStencil)
SHADOWLAB_PARAMS(Params, PLANAR_PARAMS);

class PlanarShadows final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        framebuffer_ = kit::makeFramebuffer(host(), "planar mask");
        uniforms_.create(host(), "planar uniforms");
        return program_.build(host(), {.vertexFile = "planar_project.vert", .fragmentFile = "planar_mask.frag"}, error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        if (!prepass) return;
        ensureTargets(*prepass);
        const LightInfo& light = frame.light;
        const glm::vec4 lightHomogeneous = light.type == LightType::Directional
                                               ? glm::vec4(-glm::normalize(light.direction), 0.0f)
                                               : glm::vec4(light.position, 1.0f);

        GpuPass pass(host(), "planar shadows");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, viewport_.x, viewport_.y);
        const float one = 1.0f;
        glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, &one);

        // Every caster flattened onto each receiving plane, written as 0 into the mask, behind the
        // view's own depth (read-only) and, with the receiver test, only where the plane is seen.
        glDepthMask(GL_FALSE);
        glDepthFunc(GL_LEQUAL);
        const float offset = p.depth_offset;
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(-offset, -offset);
        glEnable(GL_CLIP_DISTANCE0);
        glEnable(GL_CLIP_DISTANCE1);
        glBindTextureUnit(shared::planar::kObjectIdUnit, prepass->objectId);
        const ObjectInfo* objects = host().objects();
        for (uint32_t i = 0; objects && i < host().objectCount(); ++i) {
            // A plane receives only if the light is on its front side (dot(P, L) > 0).
            if (!objects[i].isPlane() || !objects[i].receivesShadow() || glm::dot(objects[i].plane, lightHomogeneous) <= 0.0f)
                continue;
            uniforms_.set({{}, planar::projectionMatrix(objects[i].plane, lightHomogeneous), objects[i].plane,
                           lightHomogeneous, p.clip_anti_shadow ? 1 : 0,
                           p.stencil ? i + 1 : 0u, 0, 0});
            // All casters at once; the receiver itself (and anything lying in its plane) is removed
            // by gl_ClipDistance[0] in planar_project.vert.
            host().drawScene(DrawSet::Casters, program_.use());
        }
    }

    void bindMainPass(const FrameContext&, const ParamValues&) override {
        glBindTextureUnit(shared::planar::kMaskUnit, mask_);
    }

    // Screen-sized mask, reallocated only when the viewport changes; the pre-pass depth is
    // attached again whenever the host reallocated it.
    void ensureTargets(const CameraPrepass& prepass) {
        if (!mask_ || prepass.size != viewport_) {
            viewport_ = prepass.size;
            mask_ = kit::makeTexture(host(), {.internalFormat = GL_R8, .width = viewport_.x, .height = viewport_.y,
                                              .label = "planar shadow mask"});
            glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, mask_, 0);
            host().registerDebugImage("planar mask", mask_, DebugImageKind::Mask);
            attachedDepth_ = 0;
        }
        if (attachedDepth_ != prepass.depth) {
            attachedDepth_ = prepass.depth;
            glNamedFramebufferTexture(framebuffer_, GL_DEPTH_STENCIL_ATTACHMENT, prepass.depth, 0);
            host().checkFramebuffer(framebuffer_, "planar mask");
        }
    }

    kit::Program program_;
    kit::Framebuffer framebuffer_;
    kit::Texture mask_;
    uint32_t attachedDepth_ = 0;
    glm::ivec2 viewport_{0};
    kit::UniformBlock<PlanarUniforms> uniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kCasterGeometry,
    {.id = "planar",
     .displayName = "Planar projected shadows",
     .category = "hard",
     .explanation = "Flattens every caster onto each receiving plane along the rays from the light (a projection "
                    "matrix, seed 000 eq. 3.3) and draws the flattened geometry as the shadow. Exact and cheap for a "
                    "ground plane, but only planes receive shadows, nothing shadows itself, and the special cases "
                    "need care: stencil keeps shadows on the receiver, clipping removes anti-shadows, a depth offset "
                    "avoids z-fighting.",
     .shadowGlsl = "planar.glsl",
     .flags = kTechniqueNeedsCameraPrepass},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(PlanarShadows, kDescriptor)
