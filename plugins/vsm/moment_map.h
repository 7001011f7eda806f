// The GL side shared by the filterable shadow maps (vsm, esm, evsm, msm): render the casters'
// moments from the light, blur them with a separable filter (ping-pong between the map and a
// scratch texture of the same format), optionally build mipmaps, and bind the result for the main
// pass. Each technique supplies only its moment fragment shader, its format and the value of an
// empty texel (FilteredMomentTechnique below does init and shutdown for it). Header-only: plugins
// are separate libraries, so esm, evsm and msm include it by relative path ("../vsm/moment_map.h").
#pragma once

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <bit>
#include <string>

#include "moment_light_space.h"

namespace shadowlab::moments {

struct MomentMapConfig {
    int resolution = 1024;
    GLenum format = GL_RG32F;    // GL_R32F, GL_RG32F, GL_RGBA32F or GL_RGBA16 (unorm)
    bool mipmaps = false;        // trilinear lookups; mipmaps are rebuilt after the blur
    int kernelSize = 1;          // taps per direction; 1 = no blur
    bool gaussian = false;       // blur weights: false box, true Gaussian (sigma = kernel / 6)
    glm::vec4 clearValue{1.0f};  // moments of an empty texel: depth 1, nothing occludes there
};

// Parameters every filterable map shares: each plugin's descriptor starts with these four (same ids,
// ranges and help in vsm, esm, evsm and msm), then lists its own from index kCommonParamCount.
enum CommonParam : uint32_t { kResolution, kKernel, kFilter, kMipmaps, kCommonParamCount };

#define SHADOWLAB_MOMENT_MAP_PARAMS(defaultResolution)                                                          \
    {"resolution", "resolution", ParamType::Int, 128, 4096, defaultResolution, "texels",                         \
     "Width and height of the moment map. Low values blur the shadow and lose small occluders; memory, shadow "   \
     "pass and blur time grow with the square.", nullptr},                                                       \
    {"kernel", "blur kernel", ParamType::Int, 1, 31, 5, "texels",                                                \
     "Taps of the separable blur per direction (1 = no blur, only bilinear filtering). Wider kernels give "       \
     "softer, better antialiased edges at a constant width (not physically based) and leak more light where "    \
     "occluders overlap; the blur costs two passes of N taps per texel.", nullptr},                              \
    {"filter", "blur filter", ParamType::Enum, 0, 1, 0, "",                                                      \
     "Weights of the blur: box (seed 000's choice, flat and cheapest) or Gaussian (sigma = kernel / 6: a "       \
     "smoother penumbra, narrower for the same kernel).", "box|gaussian"},                                       \
    {"mipmaps", "mipmaps", ParamType::Bool, 0, 1, 0, "",                                                         \
     "Build mipmaps after the blur and sample trilinearly, so distant or grazing receivers average the map "      \
     "instead of aliasing. Off, minified shadows shimmer; on, they widen and leak more where the footprint is "  \
     "large, and memory grows by a third.", nullptr}

inline MomentMapConfig readCommonParams(const ParamValues& params) {
    MomentMapConfig config;
    config.resolution = params.asInt(kResolution);
    config.kernelSize = params.asInt(kKernel);
    config.gaussian = params.asInt(kFilter) == 1;
    config.mipmaps = params.asBool(kMipmaps);
    return config;
}

class FilteredMomentMap {
public:
    bool init(IHost& host, const char* momentFragment, std::string& error) {
        host_ = &host;
        if (!gladLoadGL(host.glLoader())) {
            error = "could not load OpenGL entry points";
            return false;
        }
        momentProgram_ = host.buildProgram({"moment_depth.vert", momentFragment, nullptr}, error);
        if (!momentProgram_) return false;
        blurProgram_ = host.buildProgram({"fullscreen.vert", "separable_blur.frag", nullptr}, error);
        if (!blurProgram_) return false;
        momentFramebuffer_ = host.createFramebuffer("moment map");
        blurFramebuffer_ = host.createFramebuffer("moment blur");
        return true;
    }

    // Shadow pass, blur and mipmaps. setUniforms() sets the technique's own uniforms of its moment
    // fragment shader (locations >= 21) while that program is bound.
    template <class SetUniforms>
    void render(const MomentMapConfig& config, SetUniforms&& setUniforms) {
        ensureTextures(config);
        space_ = fitMomentLightSpace(host_->fitLightSpace(DrawSet::All), host_->sceneBounds(DrawSet::Casters),
                                     host_->sceneBounds(DrawSet::All));
        {
            GpuPass pass(*host_, "shadow map");
            glBindFramebuffer(GL_FRAMEBUFFER, momentFramebuffer_);
            glViewport(0, 0, resolution_, resolution_);
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            glDisable(GL_BLEND);
            glDisable(GL_CULL_FACE);          // thin and open casters need both sides
            glDisable(GL_POLYGON_OFFSET_FILL);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            const float farDepth = 1.0f;
            glClearNamedFramebufferfv(momentFramebuffer_, GL_COLOR, 0, glm::value_ptr(config.clearValue));
            glClearNamedFramebufferfv(momentFramebuffer_, GL_DEPTH, 0, &farDepth);
            const GLuint program = host_->glProgram(momentProgram_);
            glUseProgram(program);
            setLightUniforms();
            setUniforms();
            host_->drawScene(DrawSet::OpaqueCasters, program);
        }
        if (config.kernelSize > 1) {
            GpuPass pass(*host_, "blur");
            glDisable(GL_DEPTH_TEST);
            glUseProgram(host_->glProgram(blurProgram_));
            glUniform1i(17, config.kernelSize);
            glUniform1i(18, config.gaussian ? 1 : 0);
            const float texel = 1.0f / float(resolution_);
            // Along x: map -> scratch; along y: scratch -> map.
            glBindFramebuffer(GL_FRAMEBUFFER, blurFramebuffer_);
            glUniform2f(16, texel, 0.0f);
            glBindTextureUnit(4, moments_);
            host_->drawFullscreenTriangle();
            glBindFramebuffer(GL_FRAMEBUFFER, momentFramebuffer_);
            glUniform2f(16, 0.0f, texel);
            glBindTextureUnit(4, scratch_);
            host_->drawFullscreenTriangle();
            glBindTextureUnit(4, 0);
        }
        if (config.mipmaps) {
            GpuPass pass(*host_, "mipmaps");
            glGenerateTextureMipmap(moments_);
        }
    }

    // Main pass: light matrix, depth plane and the map on unit 4 (see moment_shadows.glsl).
    void bindMainPass() {
        setLightUniforms();
        glBindTextureUnit(4, moments_);
    }

    void shutdown() {
        releaseTextures();
        if (momentFramebuffer_) host_->destroyFramebuffer(momentFramebuffer_);
        if (blurFramebuffer_) host_->destroyFramebuffer(blurFramebuffer_);
        momentFramebuffer_ = blurFramebuffer_ = 0;
    }

    const MomentLightSpace& space() const { return space_; }
    GLuint texture() const { return moments_; }

private:
    void setLightUniforms() {
        glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(space_.light.viewProjection));
        glUniform4fv(20, 1, glm::value_ptr(space_.depthPlane));
    }

    // (Re)allocates only when the resolution, format, mipmapping or the need for a scratch texture
    // changed: never per frame.
    void ensureTextures(const MomentMapConfig& config) {
        const bool blur = config.kernelSize > 1;
        if (moments_ && config.resolution == resolution_ && config.format == format_ && config.mipmaps == mipmaps_ &&
            blur == (scratch_ != 0))
            return;
        releaseTextures();
        resolution_ = config.resolution;
        format_ = config.format;
        mipmaps_ = config.mipmaps;
        const int levels = mipmaps_ ? std::bit_width(unsigned(resolution_)) : 1;
        moments_ = host_->createTexture({GL_TEXTURE_2D, format_, resolution_, resolution_, 1, levels, "moment map"});
        setSampling(moments_, mipmaps_);
        depth_ = host_->createTexture(
            {GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, resolution_, resolution_, 1, 1, "moment map depth buffer"});
        glNamedFramebufferTexture(momentFramebuffer_, GL_COLOR_ATTACHMENT0, moments_, 0);
        glNamedFramebufferTexture(momentFramebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
        host_->checkFramebuffer(momentFramebuffer_, "moment map");
        if (blur) {
            scratch_ = host_->createTexture({GL_TEXTURE_2D, format_, resolution_, resolution_, 1, 1, "blur scratch"});
            setSampling(scratch_, false);
            glNamedFramebufferTexture(blurFramebuffer_, GL_COLOR_ATTACHMENT0, scratch_, 0);
            host_->checkFramebuffer(blurFramebuffer_, "moment blur");
        }
        host_->registerDebugImage("moments", moments_, DebugImageKind::Moments);
    }

    static void setSampling(GLuint texture, bool mipmaps) {
        glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }

    void releaseTextures() {
        for (GLuint* texture : {&moments_, &scratch_, &depth_}) {
            if (*texture) host_->destroyTexture(*texture);
            *texture = 0;
        }
    }

    IHost* host_ = nullptr;
    ProgramId momentProgram_ = 0;
    ProgramId blurProgram_ = 0;
    GLuint momentFramebuffer_ = 0;
    GLuint blurFramebuffer_ = 0;
    GLuint moments_ = 0;
    GLuint scratch_ = 0;
    GLuint depth_ = 0;
    int resolution_ = 0;
    GLenum format_ = 0;
    bool mipmaps_ = false;
    MomentLightSpace space_{};
};

// A technique built on one filtered moment map: init() and shutdown() are done here; the plugin
// writes renderShadows() (its format, clear value and moment-pass uniforms) and bindMainPass().
class FilteredMomentTechnique : public IShadowTechnique {
public:
    explicit FilteredMomentTechnique(const char* momentFragment) : momentFragment_(momentFragment) {}
    bool init(IHost& host, std::string& error) override { return map_.init(host, momentFragment_, error); }
    void shutdown() override { map_.shutdown(); }

protected:
    FilteredMomentMap map_;

private:
    const char* momentFragment_;
};

} // namespace shadowlab::moments
