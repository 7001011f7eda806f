// A shadow map of depth from the light: the plumbing of shadowmap, pcf, adaptive-pcf and pcss (and
// of area-reference's per-sample maps). It owns the texture (reallocated only when resolution or
// format change), the framebuffer, the depth pass (glPolygonOffset bias, face culling) and the
// block of uniforms its main-pass GLSL reads (depth_map_shared.h). The light space is the host's
// fit around the whole scene, cropped to the view when the config's fit asks (kit/focus.h), unless
// the technique passes its own.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/focus.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/shadow_map_report.h"

namespace shadowlab::kit {

using shared::depth_map::DepthMapUniforms;
using shared::depth_map::kDepthMapUnit;

enum class Cull : int { None = 0, Back = 1, Front = 2 };

struct DepthMapConfig {
    int resolution = 2048;
    GLenum format = GL_DEPTH_COMPONENT32F;
    float constantBias = 2.0f;     // glPolygonOffset units
    float slopeBias = 2.0f;        // glPolygonOffset factor
    Cull cull = Cull::None;        // none: open and single-sided casters (plates, planes) cast too
    FitConfig fit{};               // the `fit` and `snap` parameters (kit::readFit); default: the scene
    // Casters clipped at this world plane (kept where dot(plane, (p, 1)) >= 0) when set: a warp
    // that is singular behind it (psm's virtual camera plane).
    std::optional<glm::vec4> clipPlane{};
    // The technique's own depth-pass program instead of depth_only.vert (it reads the same block;
    // lispsm's linear depth and depth peeling), or null.
    const Program* program = nullptr;
};

// The shadow pass's face culling (none, back or front faces).
inline void applyCull(Cull cull) {
    if (cull == Cull::None) return;
    glEnable(GL_CULL_FACE);
    glCullFace(cull == Cull::Back ? GL_BACK : GL_FRONT);
}

// A depth texture as a framebuffer's only attachment (the whole texture: layered for arrays and
// cube maps, gl_Layer picking the layer), with nearest filtering and clamping so it is complete for
// plain reads without a sampler object too (pcss's min-depth pass fetches the map).
inline void attachDepthTarget(IHost& host, GLuint framebuffer, GLuint texture, const char* what) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, texture, 0);
    glNamedFramebufferDrawBuffer(framebuffer, GL_NONE);
    glNamedFramebufferReadBuffer(framebuffer, GL_NONE);
    host.checkFramebuffer(framebuffer, what);
}

// depth_format parameter index (kit::depthFormatParam) -> GL format.
inline GLenum depthFormat(int index) {
    static constexpr GLenum kFormats[] = {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32F};
    return kFormats[index < 0 ? 0 : index > 2 ? 2 : index];
}

// The config from a technique's values (kit/params.h): whichever of the depth-map group
// (SHADOWLAB_DEPTH_MAP_PARAMS or SHADOWLAB_BIAS_PARAMS and resolution) and the fit
// (SHADOWLAB_FIT_PARAMS) they hold; the rest keep DepthMapConfig's defaults.
template <class Values>
DepthMapConfig depthMapConfig(const Values& values) {
    DepthMapConfig config;
    if constexpr (requires { values.resolution; }) config.resolution = int(values.resolution);
    if constexpr (requires { values.depth_format; }) config.format = depthFormat(int(values.depth_format));
    if constexpr (requires { values.constant_bias; }) config.constantBias = float(values.constant_bias);
    if constexpr (requires { values.slope_bias; }) config.slopeBias = float(values.slope_bias);
    if constexpr (requires { values.cull; }) config.cull = Cull(int(values.cull));
    if constexpr (requires { values.fit; }) config.fit = fitConfig(values);
    return config;
}

class DepthMap {
public:
    bool create(IHost& host, std::string& error) {
        host_ = &host;
        if (!program_.build(host, {.vertexFile = "depth_only.vert"}, error)) return false;
        framebuffer_ = makeFramebuffer(host, "shadow map");
        uniforms_.create(host, "shadow map uniforms");
        return true;
    }

    // The usual frame: fit (the scene, or cropped to the view), one timed "shadow map" pass with
    // the casters outside the map's volume culled.
    void render(const FrameContext& frame, const DepthMapConfig& config) {
        ensureTexture(config.resolution, config.format);
        GpuPass pass(*host_, "shadow map");
        const FocusedLightSpace focused = focusLightSpace(*host_, frame, config.fit, config.resolution);
        drawDepth(focused.light, config, focused.cullPlanes);
        setFocusBody(focused.body);
        reportToHost();
    }

    // Tells the host this frame's map (its matrix and size, and B when the map was fitted to one)
    // for the texel-footprint measure and debug views; render() does it, a technique drawing with
    // drawDepth() calls it itself (after setFocusBody() when it focused the map on B).
    void reportToHost() const {
        reportShadowMap(*host_, lightSpace_.viewProjection, {resolution_, resolution_}, nullptr, &bodyEdges_);
    }
    // The focus body B (seed 002 eq. 4.2) the next reportToHost() gives the host; empty: none.
    void setFocusBody(const ConvexBody& body) { bodyEdges_ = bodyEdges(body); }

    // Tells the host the filter a technique applies to this frame's map (SHADOWLAB_EXT_FILTER_FOOTPRINT,
    // for its kernel view and --probe): `kernel` holds the technique's fields (kernel, taps, spacing,
    // ...), the map adds its own (the raw depth texture and the block's depth conventions).
    void reportFilter(FilterFootprint kernel) const {
        const DepthMapUniforms u = mainPassUniforms();
        kernel.depthTexture = texture_;
        kernel.lightDepth = u.uLightDepth;
        kernel.lightWorldSize = u.uLightWorldSize4;
        kernel.lightAxis = u.uLightAxis4;
        reportFilterFootprint(*host_, kernel);
    }

    // The depth pass alone, from any light space and without a timer scope (area-reference draws
    // one per light sample inside its own scope). ensureTexture() first. Casters are culled
    // against `cullPlanes` (DrawRequest's convention) when there are any.
    void drawDepth(const LightSpace& lightSpace, const DepthMapConfig& config,
                   const std::vector<glm::vec4>& cullPlanes = {}) {
        lightSpace_ = lightSpace;
        DepthMapUniforms block = mainPassUniforms();
        if (config.clipPlane) block.uDepthClipPlane = *config.clipPlane;
        uniforms_.set(block);
        if (config.clipPlane) glEnable(GL_CLIP_DISTANCE0);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, resolution_, resolution_);
        glClear(GL_DEPTH_BUFFER_BIT);
        applyCull(config.cull);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(config.slopeBias, config.constantBias);
        DrawRequest request;
        request.set = DrawSet::OpaqueCasters;
        request.cullPlanes = cullPlanes.data();
        request.cullPlaneCount = uint32_t(cullPlanes.size());
        host_->drawScene(request, config.program ? config.program->use() : program_.use());
        glDisable(GL_CLIP_DISTANCE0);
    }

    // Binds the map to its unit with a host sampler (CompareLinear: the texture unit's bilinear
    // comparison, hardware PCF; Nearest: raw depths) and the block the GLSL reads.
    void bindMainPass(SamplerKind sampling) const {
        glBindTextureUnit(kDepthMapUnit, texture_);
        glBindSampler(kDepthMapUnit, host_->sampler(sampling));
        uniforms_.bind();
    }

    // (Re)allocates the map when the resolution or format changed, never per frame.
    void ensureTexture(int resolution, GLenum format = GL_DEPTH_COMPONENT32F) {
        if (texture_ && resolution == resolution_ && format == format_) return;
        resolution_ = resolution;
        format_ = format;
        texture_ = makeTexture(*host_, {.target = GL_TEXTURE_2D, .internalFormat = format, .width = resolution,
                                        .height = resolution, .label = "shadow map"});
        attachDepthTarget(*host_, framebuffer_, texture_, "shadow map");
        host_->registerDebugImage("shadow map", texture_, DebugImageKind::Depth);
    }

    // Another pass's light space as this map's (its main-pass block), without drawing: a map whose
    // depths a full-screen pass writes through framebuffer() (LayeredDepthMap::resolve()).
    void adoptLightSpace(const LightSpace& lightSpace) {
        lightSpace_ = lightSpace;
        uniforms_.set(mainPassUniforms());
    }
    GLuint framebuffer() const { return framebuffer_; }

    const LightSpace& lightSpace() const { return lightSpace_; }
    GLuint texture() const { return texture_; }
    int resolution() const { return resolution_; }

private:
    DepthMapUniforms mainPassUniforms() const {
        DepthMapUniforms u{};
        u.uShadowMatrix = lightSpace_.viewProjection;
        u.uLightDepth = {lightSpace_.nearPlane, lightSpace_.farPlane, lightSpace_.perspective ? 1.0f : 0.0f,
                         float(resolution_)};
        u.uLightWorldSize4 = {lightSpace_.worldSizeAtUnitDepth, 0.0f, 0.0f};
        // The light camera looks down its view space's -z: that axis in world space.
        const glm::mat4& view = lightSpace_.view;
        u.uLightAxis4 = {-view[0][2], -view[1][2], -view[2][2], 0.0f};
        return u;
    }

    IHost* host_ = nullptr;
    std::vector<glm::vec3> bodyEdges_;   // B's edges (kit::bodyEdges) for reportToHost()
    Program program_;
    Framebuffer framebuffer_;
    Texture texture_;
    UniformBlock<DepthMapUniforms> uniforms_;
    int resolution_ = 0;
    GLenum format_ = 0;
    LightSpace lightSpace_{};
};

} // namespace shadowlab::kit
