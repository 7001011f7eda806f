// Planar projected shadows (Blinn 1988; seed 000 sections 2.2.3 and 3.2.1, eq. 3.1-3.3).
// Each caster is flattened onto every receiver plane by the projection matrix of
// planar_projection.h and drawn into a screen-space mask that the main pass reads. Here the
// classic special cases are handled:
//  - stencil: the shadow is kept on the receiver's visible pixels (no shadow "in the air" beyond
//    the receiver's edge, seed 000 Fig. 3.2b); each plane gets its own stencil id;
//  - anti-shadows: caster parts farther from the plane than the light (seed 000 Fig. 3.3) and parts
//    below the receiver are clipped with gl_ClipDistance, exactly, before projection;
//  - z-fighting: a negative depth offset lifts the shadow above its plane (Fig. 3.2a);
//  - double darkening: the mask is written, not blended, so overlapping casters darken once.
// Known limits: receivers must be planes, objects never shadow themselves or curved receivers.
#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/type_ptr.hpp>

#include <vector>

#include "planar_projection.h"

namespace {

using namespace shadowlab;

enum Param : uint32_t { kDepthOffset, kClipAntiShadow, kStencil, kParamCount };

const ParamDesc kParams[] = {
    {"depth_offset", "depth offset", ParamType::Float, 0, 8, 1, "",
     "Negative polygon offset (factor and units) that lifts the flattened shadow above the receiver. "
     "At zero the shadow and the plane fight for the same depth (z-fighting, seed 000 Fig. 3.2a).", nullptr},
    {"clip_anti_shadow", "clip anti-shadows", ParamType::Bool, 0, 1, 1, "",
     "Clip the parts of casters above a point light (and below the plane) before projecting, so no caster "
     "throws an impossible anti-shadow (seed 000 Fig. 3.3). Off, only the rasteriser's clipping of points with "
     "negative w remains: it removes anti-shadows in front of the viewer but not those projected behind it.", nullptr},
    {"stencil", "stencil to receiver", ParamType::Bool, 0, 1, 1, "",
     "Keep each shadow on the visible pixels of its receiver plane. Off, shadows can fall beyond the edge "
     "of the receiver (seed 000 Fig. 3.2b).", nullptr},
};

const TechniqueDesc kDescriptor{
    "planar",
    "Planar projected shadows",
    "hard",
    "Flattens every caster onto each receiving plane along the rays from the light (a projection "
    "matrix, seed 000 eq. 3.3) and draws the flattened geometry as the shadow. Exact and cheap for a "
    "ground plane, but only planes receive shadows, nothing shadows itself, and the special cases "
    "need care: stencil keeps shadows on the receiver, clipping removes anti-shadows, a depth offset "
    "avoids z-fighting.",
    "planar.glsl",
    kParams,
    kParamCount,
};

class PlanarShadows final : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) override {
        host_ = &host;
        if (!gladLoadGL(host.glLoader())) {
            error = "could not load OpenGL entry points";
            return false;
        }
        idProgram_ = host.buildProgram({"planar_receiver_id.vert", nullptr, nullptr}, error);
        if (!idProgram_) return false;
        shadowProgram_ = host.buildProgram({"planar_project.vert", "planar_mask.frag", nullptr}, error);
        if (!shadowProgram_) return false;
        framebuffer_ = host.createFramebuffer("planar mask");
        return true;
    }

    void renderShadows(const ParamValues& params) override {
        const CameraInfo& camera = host_->camera();
        ensureTargets(camera.viewport);
        const LightInfo& light = host_->light();
        const glm::vec4 lightHomogeneous = light.type == LightType::Directional
                                               ? glm::vec4(-glm::normalize(light.direction), 0.0f)
                                               : glm::vec4(light.position, 1.0f);

        GpuPass pass(*host_, "planar shadows");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, viewport_.x, viewport_.y);
        const float one = 1.0f;
        glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, &one);
        glClearNamedFramebufferfi(framebuffer_, GL_DEPTH_STENCIL, 0, 1.0f, 0);

        // 1. Depth of the whole view; the stencil holds the id of the receiver plane seen at each
        //    pixel (0 where anything else is in front).
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        const GLuint idProgram = host_->glProgram(idProgram_);
        // Everything first, stencil 0, in the host's instanced draws (thousands of objects cost a
        // few calls); then each receiving plane again where it is the visible surface: the same
        // program and vertices give the same depth, so GL_LEQUAL passes exactly there.
        glStencilFunc(GL_ALWAYS, 0, 0xFF);
        host_->drawScene(DrawSet::All, idProgram);
        glDepthFunc(GL_LEQUAL);
        planes_.clear();
        for (uint32_t i = 0; i < host_->objectCount(); ++i) {
            const ObjectInfo info = host_->objectInfo(i);
            // A plane receives only if the light is on its front side (dot(P, L) > 0).
            if (!info.isPlane || !info.receivesShadow || planes_.size() >= 255 || glm::dot(info.plane, lightHomogeneous) <= 0.0f)
                continue;
            planes_.push_back(i);
            glStencilFunc(GL_ALWAYS, GLint(planes_.size()), 0xFF);
            host_->drawObject(i, idProgram);
        }

        // 2. Every caster flattened onto each plane, written as 0 into the mask.
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_FALSE);
        glDepthFunc(GL_LEQUAL);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        const float offset = params.asFloat(kDepthOffset);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(-offset, -offset);
        glEnable(GL_CLIP_DISTANCE0);
        glEnable(GL_CLIP_DISTANCE1);
        const GLuint shadowProgram = host_->glProgram(shadowProgram_);
        glUseProgram(shadowProgram);
        glUniform4fv(18, 1, glm::value_ptr(lightHomogeneous));
        glUniform1i(19, params.asBool(kClipAntiShadow) ? 1 : 0);
        for (size_t p = 0; p < planes_.size(); ++p) {
            const glm::vec4 plane = host_->objectInfo(planes_[p]).plane;
            const glm::mat4 projection = planar::projectionMatrix(plane, lightHomogeneous);
            glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(projection));
            glUniform4fv(17, 1, glm::value_ptr(plane));
            glStencilFunc(params.asBool(kStencil) ? GL_EQUAL : GL_ALWAYS, GLint(p + 1), 0xFF);
            // All casters at once; the receiver itself (and anything lying in its plane) is removed
            // by gl_ClipDistance[0] in planar_project.vert.
            host_->drawScene(DrawSet::Casters, shadowProgram);
        }
        glDisable(GL_CLIP_DISTANCE0);
        glDisable(GL_CLIP_DISTANCE1);
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_STENCIL_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_LESS);
    }

    void bindMainPass(uint32_t, const ParamValues&) override { glBindTextureUnit(4, maskTexture_); }

    void shutdown() override {
        releaseTargets();
        if (framebuffer_) host_->destroyFramebuffer(framebuffer_);
        framebuffer_ = 0;
    }

private:
    void releaseTargets() {
        if (maskTexture_) host_->destroyTexture(maskTexture_);
        if (depthStencil_) host_->destroyTexture(depthStencil_);
        maskTexture_ = depthStencil_ = 0;
    }

    // Screen-sized mask and depth-stencil, reallocated only when the viewport changes.
    void ensureTargets(glm::ivec2 viewport) {
        if (maskTexture_ && viewport == viewport_) return;
        releaseTargets();
        viewport_ = viewport;
        maskTexture_ = host_->createTexture({GL_TEXTURE_2D, GL_R8, viewport.x, viewport.y, 1, 1, "planar shadow mask"});
        depthStencil_ = host_->createTexture({GL_TEXTURE_2D, GL_DEPTH24_STENCIL8, viewport.x, viewport.y, 1, 1, "planar depth-stencil"});
        glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, maskTexture_, 0);
        glNamedFramebufferTexture(framebuffer_, GL_DEPTH_STENCIL_ATTACHMENT, depthStencil_, 0);
        host_->checkFramebuffer(framebuffer_, "planar mask");
        host_->registerDebugImage("planar mask", maskTexture_, DebugImageKind::Mask);
    }

    IHost* host_ = nullptr;
    ProgramId idProgram_ = 0, shadowProgram_ = 0;
    GLuint framebuffer_ = 0, maskTexture_ = 0, depthStencil_ = 0;
    glm::ivec2 viewport_{0};
    std::vector<uint32_t> planes_;
};

} // namespace

SHADOWLAB_PLUGIN(PlanarShadows, kDescriptor)
