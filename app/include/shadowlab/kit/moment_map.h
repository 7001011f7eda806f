// The GL side shared by the filterable shadow maps (vsm, esm, evsm, msm; point lights:
// kit/cube_moment_map.h, which MomentTechnique below picks for them): render the casters from
// the light, turn their depth into the technique's moments, blur them with a separable filter,
// optionally build mipmaps, and bind the result for the main pass. Each technique supplies only
// its moment file (a GLSL function `vec4 momentsFromDepth(float depth)`, see
// shaders/moment_map_passes.glsl), its format and the value of an empty texel (MomentTechnique
// below does setup for it); its own uniforms go in a block at binding 2 that its moment file and
// its main-pass GLSL both read.
//
// Two paths give the same map (the `blur` parameter; tests/test_moment_shadows.cpp compares them):
//   fragment  the light renders the moments into a colour target of the map's format; two
//             full-screen passes blur it along x (map -> scratch) and y (scratch -> map), each tap
//             a bilinear texture lookup (shaders/separable_blur.frag).
//   compute   the light renders depth only (shaders/moment_depth_only.frag); one compute pass reads
//             the depth, derives the moments and blurs them along x in shared memory
//             (depth -> scratch), a second blurs along y (scratch -> map) (shaders/separable_blur.comp).
//             No moment target is written by the rasteriser (for msm and evsm 16 bytes a texel, for
//             every covering fragment), and each texel's moments are computed once, not per
//             fragment. Moments that need screen-space derivatives (vsm's eq. 3.16) are still
//             rendered as colour, then blurred in compute.
#pragma once

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <bit>
#include <string>

#include "shadowlab/kit/focus.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/shadow_map_report.h"
#include "shadowlab/kit/moment_light_space.h"
#include "shadowlab/kit/moment_map_config.h"
#include "shadowlab/kit/moment_map_shared.h"
#include "shadowlab/kit/params.h"
#include "shadowlab/kit/technique_base.h"
#include "shadowlab/kit/cube_moment_map.h"

namespace shadowlab::kit {

using shared::moment_map::BlurUniforms;
using shared::moment_map::kBlurDestinationImageUnit;
using shared::moment_map::kBlurSourceUnit;
using shared::moment_map::kMomentMapUnit;
using shared::moment_map::MomentMapUniforms;

// Parameters every filterable map shares: each plugin's descriptor starts with these seven (same ids,
// ranges and help in vsm, esm, evsm and msm), then lists its own from index kCommonParamCount.
enum CommonParam : uint32_t { kResolution, kKernel, kFilter, kMipmaps, kBlur, kFit, kSnap, kCommonParamCount };

// Their descriptors (the X-macro group SHADOWLAB_MOMENT_MAP_PARAMS below lists them, kit/params.h).
constexpr ParamDesc momentResolutionParam(double defaultValue) {
    return {"resolution", "resolution", ParamType::Int, 128, 4096, defaultValue, "texels",
            "Width and height of the moment map. Low values blur the shadow and lose small occluders; memory, "
            "shadow pass and blur time grow with the square.",
            nullptr};
}
constexpr ParamDesc momentKernelParam() {
    return {"kernel", "blur kernel", ParamType::Int, 1, 31, 5, "texels",
            "Taps of the separable blur per direction (1 = no blur, only bilinear filtering). Wider kernels give "
            "softer, better antialiased edges at a constant width (not physically based) and leak more light "
            "where occluders overlap; the blur costs two passes of N taps per texel.",
            nullptr};
}
constexpr ParamDesc momentFilterParam() {
    return enumParam("filter", "blur filter", 0, "box|gaussian",
            "Weights of the blur: box (seed 000's choice, flat and cheapest) or Gaussian (sigma = kernel / 6: a "
            "smoother penumbra, narrower for the same kernel).");
}
constexpr ParamDesc momentMipmapsParam() {
    return {"mipmaps", "mipmaps", ParamType::Bool, 0, 1, 0, "",
            "Build mipmaps after the blur and sample trilinearly, so distant or grazing receivers average the "
            "map instead of aliasing. Off, minified shadows shimmer; on, they widen and leak more where the "
            "footprint is large, and memory grows by a third.",
            nullptr};
}
constexpr ParamDesc momentBlurParam() {
    return enumParam("blur", "blur pass", 1, "fragment|compute",
            "How the moments are made and blurred; both give the same map. fragment: the light renders the "
            "moments into a colour target (16 bytes a texel for evsm and msm) and two full-screen passes blur "
            "it, a texture lookup per tap. compute: the light renders depth only, one compute pass turns it into "
            "moments and blurs them along x in shared memory, a second blurs along y (vsm's derivative-based M2 "
            "still renders its moments, then blurs in compute). Compare the passes' times in the timing panel or "
            "with --sweep.");
}

// Two that vsm, evsm and msm share, with one meaning (esm has neither): vsm and evsm list both
// (SHADOWLAB_CHEBYSHEV_PARAMS below), msm the second alone.
constexpr ParamDesc minVarianceParam() {
    return {"min_variance", "minimum variance", ParamType::Float, 0, 0.001, 0.00002, "depth^2",
            "Lower clamp of the variance sigma^2, in squared depth normalised to [0, 1] over the casters (seed 000 "
            "suggests 2e-5; evsm scales it to each warped depth by the square of the warp's slope). It guards "
            "eq. 3.14 against rounding: at 0, M2 - M1^2 speckles lit surfaces with shadow (acne) unless blur or "
            "vsm's derivative-based M2 add variance; large values lighten contact shadows and the inner penumbra.",
            nullptr};
}
constexpr ParamDesc lightBleedingParam() {
    return {"light_bleeding", "light-bleeding reduction", ParamType::Float, 0, 0.95, 0.0, "",
            "Remaps the visibility from [a, 1] to [0, 1], so bounds below a become full shadow; 0 is off. Seed 000 "
            "section 3.2.5: small values leave the halo of light behind overlapping occluders (Fig. 4.12c), large "
            "ones remove it but shrink and darken penumbrae until the shadow looks hard again. vsm needs it most; "
            "evsm and msm leave far less of the halo and need far less.",
            nullptr};
}

// The Chebyshev bound's two (seed 000 eq. 3.14 and sec. 3.2.5), as vsm and evsm list them.
#define SHADOWLAB_CHEBYSHEV_PARAMS(X)                              \
    X(float, min_variance, ::shadowlab::kit::minVarianceParam()) \
    X(float, light_bleeding, ::shadowlab::kit::lightBleedingParam())

#define SHADOWLAB_MOMENT_MAP_PARAMS(X, defaultResolution)                                  \
    X(int, resolution, ::shadowlab::kit::momentResolutionParam(defaultResolution))         \
    X(int, kernel, ::shadowlab::kit::momentKernelParam())                                  \
    X(int, filter, ::shadowlab::kit::momentFilterParam())                                  \
    X(bool, mipmaps, ::shadowlab::kit::momentMipmapsParam())                               \
    X(int, blur, ::shadowlab::kit::momentBlurParam())                                      \
    SHADOWLAB_FIT_PARAMS(X)

inline MomentMapConfig readCommonParams(const ParamValues& params) {
    MomentMapConfig config;
    config.resolution = params.asInt(kResolution);
    config.kernelSize = params.asInt(kKernel);
    config.gaussian = params.asInt(kFilter) == 1;
    config.mipmaps = params.asBool(kMipmaps);
    config.blur = params.asInt(kBlur) == 1 ? BlurPath::Compute : BlurPath::Fragment;
    config.fit = readFit(params, kFit, kSnap);
    return config;
}

class MomentMap {
public:
    // `momentFile`: the technique's moment file (momentsFromDepth, then moment_map_passes.glsl).
    // Every program either path needs is built here, once.
    bool create(IHost& host, const char* momentFile, std::string& error) {
        host_ = &host;
        if (!momentProgram_.build(host, {.vertexFile = "moment_depth.vert", .fragmentFile = momentFile,
                                         .defines = "MOMENT_PASS_FRAGMENT 1"}, error))
            return false;
        if (!depthProgram_.build(host, {.vertexFile = "moment_depth.vert", .fragmentFile = "moment_depth_only.frag"}, error))
            return false;
        if (!blurProgram_.build(host, {.vertexFile = "fullscreen.vert", .fragmentFile = "separable_blur.frag"}, error))
            return false;
        if (!computeBlurX_.build(host, {.computeFile = momentFile, .defines = "MOMENT_PASS_COMPUTE 1;MOMENT_BLUR_AXIS 0"},
                                 error))
            return false;
        if (!computeBlurY_.build(host, {.computeFile = "separable_blur.comp", .defines = "MOMENT_BLUR_AXIS 1"}, error))
            return false;
        momentFramebuffer_ = makeFramebuffer(host, "moment map");
        depthFramebuffer_ = makeFramebuffer(host, "moment map (depth only)");
        blurFramebuffer_ = makeFramebuffer(host, "moment blur");
        mapUniforms_.create(host, "moment map uniforms");
        blurUniforms_[0].create(host, "moment blur uniforms (x)");
        blurUniforms_[1].create(host, "moment blur uniforms (y)");
        return true;
    }

    // Shadow pass, blur and mipmaps. The technique's own block (binding 2) must be bound already.
    void render(const FrameContext& frame, const MomentMapConfig& config) {
        ensureTextures(config);
        // The map's rectangle may be cropped to the view (kit/focus.h); its linear depth still spans
        // every caster along the light's axis.
        const FocusedLightSpace focused = focusLightSpace(*host_, frame, config.fit, config.resolution);
        space_ = fitMomentLightSpace(focused.light, host_->bounds(DrawSet::Casters), host_->bounds(DrawSet::All));
        mapUniforms_.set({{}, space_.light.viewProjection, space_.depthPlane});
        bodyEdges_ = bodyEdges(focused.body);
        reportShadowMap(*host_, space_.light.viewProjection, {resolution_, resolution_}, nullptr, &bodyEdges_);
        const bool compute = config.blur == BlurPath::Compute;
        const bool depthOnly = compute && !config.momentsNeedDerivatives;
        {
            GpuPass pass(*host_, "shadow map");
            glViewport(0, 0, resolution_, resolution_);
            const float farDepth = 1.0f;
            if (depthOnly) {
                glBindFramebuffer(GL_FRAMEBUFFER, depthFramebuffer_);
                glClearNamedFramebufferfv(depthFramebuffer_, GL_DEPTH, 0, &farDepth);
            } else {
                glBindFramebuffer(GL_FRAMEBUFFER, momentFramebuffer_);
                glClearNamedFramebufferfv(momentFramebuffer_, GL_COLOR, 0, glm::value_ptr(config.clearValue));
                glClearNamedFramebufferfv(momentFramebuffer_, GL_DEPTH, 0, &farDepth);
            }
            // No face culling (the contract's default): thin and open casters need both sides.
            DrawRequest request;
            request.set = DrawSet::OpaqueCasters;
            request.cullPlanes = focused.cullPlanes.data();
            request.cullPlaneCount = uint32_t(focused.cullPlanes.size());
            host_->drawScene(request, (depthOnly ? depthProgram_ : momentProgram_).use());
        }
        if (compute)
            computeBlur(config, depthOnly);
        else if (config.kernelSize > 1)
            fragmentBlur(config);
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
    BlurUniforms blurValues(const MomentMapConfig& config, glm::vec2 step, int source) const {
        return {{}, {step, 0.0f, 0.0f}, config.kernelSize, config.gaussian ? 1 : 0, source,
                format_ == GL_RGBA16 ? 1 : 0};
    }

    // Along x: map -> scratch; along y: scratch -> map.
    void fragmentBlur(const MomentMapConfig& config) {
        GpuPass pass(*host_, "blur");
        glDisable(GL_DEPTH_TEST);
        blurProgram_.use();
        const float texel = 1.0f / float(resolution_);
        blurUniforms_[0].set(blurValues(config, {texel, 0.0f}, 0));
        glBindFramebuffer(GL_FRAMEBUFFER, blurFramebuffer_);
        glBindTextureUnit(kBlurSourceUnit, moments_);
        host_->drawFullscreenTriangle();
        blurUniforms_[1].set(blurValues(config, {0.0f, texel}, 0));
        glBindFramebuffer(GL_FRAMEBUFFER, momentFramebuffer_);
        glBindTextureUnit(kBlurSourceUnit, scratch_);
        host_->drawFullscreenTriangle();
        glBindTextureUnit(kBlurSourceUnit, 0);
    }

    // Along x: depth (derived into moments as they are loaded) or rendered moments -> scratch, or
    // straight into the map when there is no blur; along y: scratch -> map. Image stores are not
    // ordered with later reads by themselves: a barrier before the y pass fetches the scratch, and
    // one after the last pass for what reads the map next (the main pass's lookups and the next
    // frame's blur: texture fetches; mipmap generation and read-back: texture updates; the
    // fragment path's render targets if the parameter changes: framebuffer; the next image stores).
    void computeBlur(const MomentMapConfig& config, bool fromDepth) {
        const bool blur = config.kernelSize > 1;
        if (!fromDepth && !blur) return;   // the rendered moments are the map
        GpuPass pass(*host_, blur ? "blur" : "moments");
        const GLuint groupsX = GLuint(resolution_ + 255) / 256u;   // separable_blur.comp's group sizes
        blurUniforms_[0].set(blurValues(config, {1.0f, 0.0f}, fromDepth ? 1 : 0));
        glBindTextureUnit(kBlurSourceUnit, fromDepth ? depth_ : moments_);
        glBindImageTexture(kBlurDestinationImageUnit, blur ? scratch_ : moments_, 0, GL_FALSE, 0, GL_WRITE_ONLY, format_);
        computeBlurX_.use();
        glDispatchCompute(groupsX, GLuint(resolution_), 1);
        if (blur) {
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
            blurUniforms_[1].set(blurValues(config, {0.0f, 1.0f}, 0));
            glBindTextureUnit(kBlurSourceUnit, scratch_);
            glBindImageTexture(kBlurDestinationImageUnit, moments_, 0, GL_FALSE, 0, GL_WRITE_ONLY, format_);
            computeBlurY_.use();
            glDispatchCompute(GLuint(resolution_ + 3) / 4u, GLuint(resolution_ + 63) / 64u, 1);
        }
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(kBlurSourceUnit, 0);
        glBindImageTexture(kBlurDestinationImageUnit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    }

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
        // The depth buffer of the colour pass; on the compute path the linear depth the moments
        // are derived from (fetched, never filtered).
        depth_ = makeTexture(*host_, {.internalFormat = GL_DEPTH_COMPONENT32F, .width = resolution_,
                                      .height = resolution_, .label = "moment map depth buffer"});
        glTextureParameteri(depth_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(depth_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glNamedFramebufferTexture(momentFramebuffer_, GL_COLOR_ATTACHMENT0, moments_, 0);
        glNamedFramebufferTexture(momentFramebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
        host_->checkFramebuffer(momentFramebuffer_, "moment map");
        glNamedFramebufferTexture(depthFramebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
        glNamedFramebufferDrawBuffer(depthFramebuffer_, GL_NONE);
        glNamedFramebufferReadBuffer(depthFramebuffer_, GL_NONE);
        host_->checkFramebuffer(depthFramebuffer_, "moment map (depth only)");
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
    std::vector<glm::vec3> bodyEdges_;   // B's edges (kit::bodyEdges) for the host's focus-body view
    Program momentProgram_, depthProgram_, blurProgram_, computeBlurX_, computeBlurY_;
    Framebuffer momentFramebuffer_, depthFramebuffer_, blurFramebuffer_;
    Texture moments_, scratch_, depth_;
    UniformBlock<MomentMapUniforms> mapUniforms_;
    UniformBlock<BlurUniforms> blurUniforms_[2];
    int resolution_ = 0;
    GLenum format_ = 0;
    bool mipmaps_ = false;
    MomentLightSpace space_{};
};

// A file name as a template argument (MomentTechnique<Params, Block, "vsm_moments.glsl">).
template <size_t N>
struct FileName {
    constexpr FileName(const char (&text)[N]) { std::copy_n(text, N, name); }
    char name[N];
};

// A technique built on one filtered moment map, its parameters `Params` (a SHADOWLAB_PARAMS struct
// whose list starts with SHADOWLAB_MOMENT_MAP_PARAMS), its own block `Block` (binding 2, read by
// its moment file and its main-pass GLSL) and its moment file: setup, the frame's passes and
// bindMainPass are done here; the plugin states only what is its own in configure().
template <class Params, class Block, FileName momentFile>
class MomentTechnique : public TechniqueBase {
protected:
    // The map's format and empty texel (clearValue, = momentsFromDepth(1)) and whether its moments
    // need derivatives, set in `config` (the shared parameters already read into it); returns the
    // values of the technique's block for this frame.
    virtual Block configure(const Params& p, MomentMapConfig& config) const = 0;

    bool setup(std::string& error) override {
        uniforms_.create(host(), "technique uniforms");
        return map_.create(host(), momentFile.name, error) && cube_.create(host(), momentFile.name, error);
    }
    // Point lights: the cube moment map (kit/cube_moment_map.h), the 2D map otherwise.
    void renderShadows(const FrameContext& frame, const ParamValues& params) final {
        MomentMapConfig config = readCommonParams(params);
        uniforms_.set(configure(Params::read(params), config));
        if (frame.light.type == LightType::Point)
            cube_.render(frame, config);
        else
            map_.render(frame, config);
    }
    void bindMainPass(const FrameContext& frame, const ParamValues&) override {
        map_.bindMainPass();   // its block is read (not used) by the 2D branch of moment_shadows.glsl
        if (frame.light.type == LightType::Point) cube_.bindMainPass();
        uniforms_.bind();
    }

private:
    MomentMap map_;
    CubeMomentMap cube_;
    UniformBlock<Block> uniforms_;
};

} // namespace shadowlab::kit
