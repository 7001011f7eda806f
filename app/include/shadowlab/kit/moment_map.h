// The GL side shared by the filterable shadow maps (vsm, esm, evsm, msm): render the casters'
// moments from the light, blur them with a separable filter (ping-pong between the map and a
// scratch texture of the same format), optionally build mipmaps, and bind the result for the main
// pass. Each technique supplies only its moment fragment shader, its format and the value of an
// empty texel (MomentTechnique below does setup for it); its own uniforms go in a block at
// binding 2 that its moment shader and its main-pass GLSL both read.
#pragma once

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <bit>
#include <string>

#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/moment_light_space.h"
#include "shadowlab/kit/moment_map_shared.h"
#include "shadowlab/kit/technique_base.h"

namespace shadowlab::kit {

using shared::moment_map::BlurUniforms;
using shared::moment_map::kMomentMapUnit;
using shared::moment_map::MomentMapUniforms;

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

class MomentMap {
public:
    bool create(IHost& host, const char* momentFragment, std::string& error) {
        host_ = &host;
        if (!momentProgram_.build(host, {.vertexFile = "moment_depth.vert", .fragmentFile = momentFragment}, error))
            return false;
        if (!blurProgram_.build(host, {.vertexFile = "fullscreen.vert", .fragmentFile = "separable_blur.frag"}, error))
            return false;
        momentFramebuffer_ = makeFramebuffer(host, "moment map");
        blurFramebuffer_ = makeFramebuffer(host, "moment blur");
        mapUniforms_.create(host, "moment map uniforms");
        blurUniforms_[0].create(host, "moment blur uniforms (x)");
        blurUniforms_[1].create(host, "moment blur uniforms (y)");
        return true;
    }

    // Shadow pass, blur and mipmaps. The technique's own block (binding 2) must be bound already.
    void render(const FrameContext& frame, const MomentMapConfig& config) {
        ensureTextures(config);
        space_ = fitMomentLightSpace(host_->fitLightSpace(frame.light, DrawSet::All), host_->bounds(DrawSet::Casters),
                                     host_->bounds(DrawSet::All));
        mapUniforms_.set({{}, space_.light.viewProjection, space_.depthPlane});
        {
            GpuPass pass(*host_, "shadow map");
            glBindFramebuffer(GL_FRAMEBUFFER, momentFramebuffer_);
            glViewport(0, 0, resolution_, resolution_);
            const float farDepth = 1.0f;
            glClearNamedFramebufferfv(momentFramebuffer_, GL_COLOR, 0, glm::value_ptr(config.clearValue));
            glClearNamedFramebufferfv(momentFramebuffer_, GL_DEPTH, 0, &farDepth);
            // No culling (the contract's default): thin and open casters need both sides.
            host_->drawScene(DrawSet::OpaqueCasters, momentProgram_.use());
        }
        if (config.kernelSize > 1) {
            GpuPass pass(*host_, "blur");
            glDisable(GL_DEPTH_TEST);
            blurProgram_.use();
            const float texel = 1.0f / float(resolution_);
            // Along x: map -> scratch; along y: scratch -> map.
            blurUniforms_[0].set({{}, {texel, 0.0f, 0.0f, 0.0f}, config.kernelSize, config.gaussian ? 1 : 0, 0, 0});
            glBindFramebuffer(GL_FRAMEBUFFER, blurFramebuffer_);
            glBindTextureUnit(shared::moment_map::kBlurSourceUnit, moments_);
            host_->drawFullscreenTriangle();
            blurUniforms_[1].set({{}, {0.0f, texel, 0.0f, 0.0f}, config.kernelSize, config.gaussian ? 1 : 0, 0, 0});
            glBindFramebuffer(GL_FRAMEBUFFER, momentFramebuffer_);
            glBindTextureUnit(shared::moment_map::kBlurSourceUnit, scratch_);
            host_->drawFullscreenTriangle();
            glBindTextureUnit(shared::moment_map::kBlurSourceUnit, 0);
        }
        if (config.mipmaps) {
            GpuPass pass(*host_, "mipmaps");
            glGenerateTextureMipmap(moments_);
        }
    }

    // Main pass: light matrix, depth plane and the map (see moment_shadows.glsl).
    void bindMainPass() const {
        mapUniforms_.bind();
        glBindTextureUnit(kMomentMapUnit, moments_);
        glBindSampler(kMomentMapUnit, host_->sampler(mipmaps_ ? SamplerKind::LinearMipmap : SamplerKind::Linear));
    }

    const MomentLightSpace& space() const { return space_; }
    GLuint texture() const { return moments_; }

private:
    // (Re)allocates only when the resolution, format, mipmapping or the need for a scratch texture
    // changed: never per frame.
    void ensureTextures(const MomentMapConfig& config) {
        const bool blur = config.kernelSize > 1;
        if (moments_ && config.resolution == resolution_ && config.format == format_ && config.mipmaps == mipmaps_ &&
            blur == bool(scratch_))
            return;
        scratch_.reset();
        resolution_ = config.resolution;
        format_ = config.format;
        mipmaps_ = config.mipmaps;
        const int levels = mipmaps_ ? std::bit_width(unsigned(resolution_)) : 1;
        moments_ = makeTexture(*host_, {.internalFormat = format_, .width = resolution_, .height = resolution_,
                                        .levels = levels, .label = "moment map"});
        setSampling(moments_, mipmaps_);
        depth_ = makeTexture(*host_, {.internalFormat = GL_DEPTH_COMPONENT32F, .width = resolution_,
                                      .height = resolution_, .label = "moment map depth buffer"});
        glNamedFramebufferTexture(momentFramebuffer_, GL_COLOR_ATTACHMENT0, moments_, 0);
        glNamedFramebufferTexture(momentFramebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
        host_->checkFramebuffer(momentFramebuffer_, "moment map");
        if (blur) {
            scratch_ = makeTexture(*host_, {.internalFormat = format_, .width = resolution_, .height = resolution_,
                                            .label = "blur scratch"});
            setSampling(scratch_, false);
            glNamedFramebufferTexture(blurFramebuffer_, GL_COLOR_ATTACHMENT0, scratch_, 0);
            host_->checkFramebuffer(blurFramebuffer_, "moment blur");
        }
        host_->registerDebugImage("moments", moments_, DebugImageKind::Moments);
    }

    // The blur reads through the texture's own state (no sampler bound on its unit).
    static void setSampling(GLuint texture, bool mipmaps) {
        glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }

    IHost* host_ = nullptr;
    Program momentProgram_, blurProgram_;
    Framebuffer momentFramebuffer_, blurFramebuffer_;
    Texture moments_, scratch_, depth_;
    UniformBlock<MomentMapUniforms> mapUniforms_;
    UniformBlock<BlurUniforms> blurUniforms_[2];
    int resolution_ = 0;
    GLenum format_ = 0;
    bool mipmaps_ = false;
    MomentLightSpace space_{};
};

// A technique built on one filtered moment map and its own block `Block` (binding 2, read by its
// moment shader and its main-pass GLSL): setup and bindMainPass are done here; the plugin writes
// renderShadows() (its format, clear value and block values) and calls render().
template <class Block>
class MomentTechnique : public TechniqueBase {
public:
    explicit MomentTechnique(const char* momentFragment) : momentFragment_(momentFragment) {}

protected:
    bool setup(std::string& error) override {
        uniforms_.create(host(), "technique uniforms");
        return map_.create(host(), momentFragment_, error);
    }
    void render(const FrameContext& frame, const MomentMapConfig& config, const Block& block) {
        uniforms_.set(block);
        map_.render(frame, config);
    }
    void bindMainPass(const FrameContext&, const ParamValues&) override {
        map_.bindMainPass();
        uniforms_.bind();
    }

private:
    const char* momentFragment_;
    MomentMap map_;
    UniformBlock<Block> uniforms_;
};

} // namespace shadowlab::kit
