// The shadow map of the kernel-filtering techniques (pcf, adaptive-pcf, pcss; area-reference
// renders its per-sample maps with it too): one depth map from the light, fitted around the scene
// like `shadowmap`, biased with glPolygonOffset, plus the light-space numbers the GLSL side needs
// to turn a kernel offset into a receiver bias (the cone bias of shaders/disc_sampling.glsl) and
// a light size into map texels (pcss). Also the parameters these techniques declare alike.
//
// Header-only: plugins can share C++ only this way. The other plugins include it by relative
// path ("../pcf/kernel_shadow_map.h").
//
// Main-pass uniforms it sets (the technique's GLSL declares them):
//   location 16  mat4 uShadowMatrix     light view-projection (world -> clip)
//   location 20  vec4 uLightDepth       near, far, 1 perspective / 0 orthographic, resolution
//   location 21  vec2 uLightWorldSize   map extent in world units (orthographic) or at unit
//                                       distance from the light (perspective)
//   location 22  vec3 uLightAxis        unit world direction along which the map measures depth
// Techniques put their own uniforms at 23 and above.
#pragma once

#include <string>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/type_ptr.hpp>

namespace shadowlab::kernel_filtering {

// Parameters shared by the techniques built on this map (each lists them in its own descriptor).
inline constexpr ParamDesc kResolutionParam{
    "resolution", "resolution", ParamType::Int, 256, 8192, 2048, "texels",
    "Width and height of the shadow map. Low values let texel steps show through the filter and make "
    "contacts blocky; high values cost memory and shadow-pass time (square law), and a kernel given in "
    "texels then covers less of the scene.", nullptr};
inline constexpr ParamDesc kConstantBiasParam{
    "constant_bias", "constant bias", ParamType::Float, 0, 64, 2, "units",
    "glPolygonOffset units in the shadow pass. Zero shows acne even at the kernel centre; large values "
    "detach shadows from their casters (peter panning).", nullptr};
inline constexpr ParamDesc kSlopeBiasParam{
    "slope_bias", "slope-scaled bias", ParamType::Float, 0, 16, 2, "",
    "glPolygonOffset factor: bias growing with the caster's slope as seen from the light. Zero leaves acne "
    "on tilted surfaces; large values push shadows off grazing contacts.", nullptr};
inline constexpr ParamDesc kConeBiasParam{
    "cone_bias", "cone bias", ParamType::Bool, 0, 1, 1, "",
    "Receiver bias growing with each sample's distance from the kernel centre, scaled by the receiver's "
    "slope against the light (seed 000 sec. 3.2.4, last paragraph). Off: wide kernels darken lit surfaces "
    "(acne, worst on tilted receivers); on: clean, with slight peter panning at contacts under wide kernels.",
    nullptr};

class KernelShadowMap {
public:
    // `hardwareCompare`: the texture compares by itself (sampler2DShadow); otherwise it holds raw
    // depths for sampler2D reads (pcss reads blocker depths and compares in the shader).
    bool init(IHost& host, bool hardwareCompare, std::string& error) {
        host_ = &host;
        hardwareCompare_ = hardwareCompare;
        depthProgram_ = host.buildProgram({"depth_only.vert", nullptr, nullptr}, error);
        if (!depthProgram_) return false;
        framebuffer_ = host.createFramebuffer("shadow map");
        return true;
    }

    // Depth pass from the light; reallocates only when the resolution changed.
    void render(int resolution, float constantBias, float slopeBias) {
        ensureTexture(resolution);
        lightSpace_ = host_->fitLightSpace(DrawSet::All);
        GpuPass pass(*host_, "shadow map");
        drawDepth(lightSpace_, constantBias, slopeBias);
    }

    // The depth pass alone, from any light space and without a timer scope (area-reference draws
    // one per light sample inside its own scope). ensureTexture() first.
    void drawDepth(const LightSpace& lightSpace, float constantBias, float slopeBias) {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, resolution_, resolution_);
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        // No culling: open and single-sided casters (plates, planes) must cast too.
        glDisable(GL_CULL_FACE);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(slopeBias, constantBias);
        const GLuint program = host_->glProgram(depthProgram_);
        glUseProgram(program);
        glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(lightSpace.viewProjection));
        host_->drawScene(DrawSet::OpaqueCasters, program);
        glDisable(GL_POLYGON_OFFSET_FILL);
    }

    // Binds the map to `unit` (linear: the texture unit's bilinear comparison, hardware PCF) and
    // sets the uniforms listed at the top of this file.
    void bindMainPass(GLuint unit, bool linear) const {
        const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
        glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, filter);
        glBindTextureUnit(unit, texture_);
        glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(lightSpace_.viewProjection));
        glUniform4f(20, lightSpace_.nearPlane, lightSpace_.farPlane, lightSpace_.perspective ? 1.0f : 0.0f,
                    float(resolution_));
        glUniform2f(21, lightSpace_.worldSizeAtUnitDepth.x, lightSpace_.worldSizeAtUnitDepth.y);
        // The light camera looks down its view space's -z: that axis in world space.
        const glm::mat4& view = lightSpace_.view;
        glUniform3f(22, -view[0][2], -view[1][2], -view[2][2]);
    }

    void shutdown() {
        if (!host_) return;
        if (texture_) host_->destroyTexture(texture_);
        if (framebuffer_) host_->destroyFramebuffer(framebuffer_);
        texture_ = framebuffer_ = 0;
        resolution_ = 0;
    }

    const LightSpace& lightSpace() const { return lightSpace_; }
    GLuint texture() const { return texture_; }
    int resolution() const { return resolution_; }

    // (Re)allocates the map when the resolution changed, never per frame.
    void ensureTexture(int resolution) {
        if (texture_ && resolution == resolution_) return;
        if (texture_) host_->destroyTexture(texture_);
        resolution_ = resolution;
        texture_ = host_->createTexture({GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, resolution, resolution, 1, 1, "shadow map"});
        if (hardwareCompare_) {
            glTextureParameteri(texture_, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            glTextureParameteri(texture_, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        }
        glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, texture_, 0);
        glNamedFramebufferDrawBuffer(framebuffer_, GL_NONE);
        glNamedFramebufferReadBuffer(framebuffer_, GL_NONE);
        host_->checkFramebuffer(framebuffer_, "shadow map");
        host_->registerDebugImage("shadow map", texture_, DebugImageKind::Depth);
    }

private:
    IHost* host_ = nullptr;
    bool hardwareCompare_ = true;
    ProgramId depthProgram_ = 0;
    GLuint framebuffer_ = 0;
    GLuint texture_ = 0;
    int resolution_ = 0;
    LightSpace lightSpace_{};
};

} // namespace shadowlab::kernel_filtering
