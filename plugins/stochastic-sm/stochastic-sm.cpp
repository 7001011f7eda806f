// Stochastic shadow maps (Enderton, Sintorn, Shirley and Luebke 2010, "Stochastic Transparency";
// seed 001 sec. 2.1.2, timed in sec. 5.3.1, Fig. 5.3.C). One depth map: opaque casters as usual,
// translucent casters written with probability alpha (a fragment is discarded when its random
// number xi >= alpha), so a texel behind translucent surfaces a_1..a_k stays lit with probability
// prod (1 - a_i) and a PCF over the map estimates it: translucency model M1 (coverage), right on
// every layer, translucent receivers included (Fig. 2.1.2.C), but uncoloured. xi is a hash of the
// texel, the object, the triangle and the frame seed (kit/stochastic_shared.h), so the noise
// changes every frame; seed 001 read an RGB noise texture instead (sec. 5.3.1).
// Filtering as seed 001 timed it: the texture unit's 2x2 bilinear comparison on every tap of an
// n x n shader kernel (n up to 9).
// Optional MSAA map (seed 001 sec. 2.1.2 and the audit's "MSAA 1-8"; Enderton et al. 2010's
// stochastic transparency): with msaa > 1 the map is a multisample depth texture, translucent
// fragments keep each covered sample with probability alpha through gl_SampleMask, and the lookup
// compares every sample of the n x n nearest texels: samples x n^2 coin flips per pixel instead of
// n^2, for the same kernel footprint. msaa = 1 is the single-sample path above, untouched.
// Known artefacts: noise under translucent casters, which only wide kernels (blurring every edge)
// average away; no colour (a red glass casts a grey shadow); the `per-texel` noise lets stacked
// surfaces through as 1 - max a instead of prod (1 - a_i).
#include <algorithm>
#include <string>
#include <vector>

#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/stochastic_light_pass.h>
#include <shadowlab/kit/technique_base.h>

#include "stochastic_sm_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kKernel{"kernel", "kernel size n", ParamType::Int, 1, 9, 5, "taps",
     "n x n taps one texel apart, averaged per pixel. The map is a coin flip per translucent texel, so "
     "small kernels show the noise (1: every texel lit or not); 9 x 9 is what seed 001 timed. Larger "
     "kernels cost n^2 lookups and blur every edge.",
     nullptr};
constexpr ParamDesc kHardwareFilter{"hardware_filter", "hardware 2x2 per tap", ParamType::Bool, 0, 1, 1, "",
     "Every tap is the texture unit's bilinear 2x2 comparison (seed 001 timed 2x2 hardware PCF under its "
     "9 x 9 kernel): about (n + 1)^2 texels of noise averaged for n^2 lookups. Off: n^2 plain tests, "
     "noisier and with n^2 + 1 shades.",
     nullptr};
constexpr ParamDesc kMsaa = kit::enumParam("msaa", "MSAA samples", 0, "1|2|4|8",
     "Samples per texel of the map. 1: one coin flip per translucent texel (the single-sample map). "
     "2-8: a multisample map in which each covered sample is kept with probability alpha on its own "
     "(stochastic transparency's per-sample masks, Enderton et al. 2010), and every sample of the n x n "
     "texels is compared: samples x n^2 flips per pixel, so the noise falls about as 1 / sqrt(samples) "
     "without widening the kernel (a smaller kernel, sharper edges, for the same noise). The cost grows "
     "with the count: samples x the map's memory and fill, samples x n^2 fetches per pixel, and no "
     "hardware 2x2 filter (hardware_filter is ignored). A count the GPU lacks for 32F depth becomes the "
     "next larger it has, else its largest (llvmpipe has only 4).");

#define STOCHASTIC_SM_PARAMS(X)                       \
    X(int, resolution, kit::resolutionParam())        \
    X(int, kernel, kKernel)                           \
    X(bool, hardware_filter, kHardwareFilter)         \
    X(int, noise, kit::noiseParam())                  \
    X(int, msaa, kMsaa)                               \
    X(bool, cone_bias, kit::coneBiasParam())          \
    SHADOWLAB_OFFSET_BIAS_PARAMS(X, 64)               \
    SHADOWLAB_FIT_PARAMS(X)
SHADOWLAB_PARAMS(Params, STOCHASTIC_SM_PARAMS);

class StochasticShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!opaqueProgram_.build(host(), {.vertexFile = "depth_only.vert"}, error)) return false;
        if (!translucentProgram_.build(host(),
                                       {.vertexFile = "translucent_caster.vert", .fragmentFile = "stochastic_sm_caster.frag"},
                                       error))
            return false;
        if (!translucentMsProgram_.build(host(),
                                         {.vertexFile = "translucent_caster.vert",
                                          .fragmentFile = "stochastic_sm_caster.frag",
                                          .defines = "STOCHASTIC_SM_MSAA 1"},
                                         error))
            return false;
        // The sample counts this GL offers for multisample 32F depth textures, largest first.
        GLint counts = 0;
        glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, GL_DEPTH_COMPONENT32F, GL_NUM_SAMPLE_COUNTS, 1, &counts);
        sampleCounts_.assign(size_t(std::max(counts, 0)), 0);
        if (counts > 0)
            glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, GL_DEPTH_COMPONENT32F, GL_SAMPLES, counts, sampleCounts_.data());
        lightPass_.create(host(), "stochastic shadow map");
        uniforms_.create(host(), "stochastic-sm uniforms");
        return true;
    }

    // Samples per texel for the `msaa` choice: 0 for the single-sample map, else the smallest count
    // the GL offers that is at least the one asked for, or its largest (as glTexImage2DMultisample
    // rounds). What was used is the statistic "map samples per texel" (no log line: the choice is
    // made every frame, and a count the GL lacks is no fault).
    int mapSamples(int choice) const {
        const int requested = 1 << choice;
        if (requested <= 1) return 0;
        int chosen = 0;
        for (const GLint count : sampleCounts_)
            if (count > 1 && count >= requested && (chosen == 0 || count < chosen)) chosen = count;
        if (chosen == 0)
            for (const GLint count : sampleCounts_) chosen = std::max(chosen, count > 1 ? int(count) : 0);
        return chosen;
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const int samples = mapSamples(p.msaa);
        // The host's image viewer reads single-sample textures only: no debug image of a
        // multisampled map (registered anyway, so the entry never names a deleted texture).
        if (lightPass_.ensure({.resolution = p.resolution, .samples = samples}))
            host().registerDebugImage("stochastic shadow map", samples ? 0u : lightPass_.target().depth(), DebugImageKind::Depth);
        host().reportStatistic("map samples per texel", samples ? samples : 1);
        GpuPass pass(host(), "shadow map");
        lightPass_.begin(frame, kit::fitConfig(p), {{}, 0u, p.noise, 0.0f, 0.0f});   // bias: polygon offset
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(p.slope_bias, p.constant_bias);
        lightPass_.draw(DrawSet::OpaqueCasters, opaqueProgram_);
        // The same depth test and writes: a kept translucent fragment (or sample) is an opaque one.
        lightPass_.draw(DrawSet::TranslucentCasters, samples ? translucentMsProgram_ : translucentProgram_);
        samples_ = samples;
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        const Params p = Params::read(params);
        const bool bilinear = p.hardware_filter;
        // One map is bound, on its own unit by type (sampler2DShadow or sampler2DMS); the other unit
        // gets no texture, so it never holds one of the wrong type.
        glBindTextureUnit(kit::kDepthMapUnit, samples_ ? 0u : lightPass_.target().depth());
        glBindSampler(kit::kDepthMapUnit, host().sampler(bilinear ? SamplerKind::CompareLinear : SamplerKind::CompareNearest));
        glBindTextureUnit(shared::stochastic_sm::kMultisampleMapUnit, samples_ ? lightPass_.target().depth() : 0u);
        lightPass_.bindMainPass();
        uniforms_.set({{}, p.kernel, bilinear ? 1 : 0, p.cone_bias ? 1.0f : 0.0f, samples_});
    }

    kit::Program opaqueProgram_;
    kit::Program translucentProgram_;
    kit::Program translucentMsProgram_;   // STOCHASTIC_SM_MSAA: per-sample coin flips
    std::vector<GLint> sampleCounts_;      // offered for multisample 32F depth, from setup()
    int samples_ = 0;                      // of the map rendered this frame; 0 single-sample
    kit::StochasticLightPass lightPass_;
    kit::UniformBlock<shared::stochastic_sm::StochasticSmUniforms> uniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kStochasticMap,
    {.id = "stochastic-sm",
     .displayName = "Stochastic shadow maps",
     .category = "coloured",
     .explanation = "One depth map from the light in which each translucent fragment is kept with probability "
                    "alpha and thrown away otherwise (a random number per texel, surface and frame). Filtering "
                    "the map with PCF then estimates how much light gets through every layer: 1 - alpha per "
                    "translucent surface, right on translucent surfaces too, but without colour (a red glass "
                    "casts a grey shadow: judged by the coverage model). The price is noise, which needs wide "
                    "kernels that blur every edge; it changes every frame. msaa > 1 flips the coin per sample of a "
                    "multisampled map instead (as stochastic transparency does), so the same kernel averages "
                    "several flips per texel: less noise at the same blur, for more memory and fetches. Try "
                    "kernel 1 to see the coin flips, then msaa 4 at the same kernel, and noise = per-texel under "
                    "overlapping glass to see what shared random numbers do.",
     .shadowGlsl = "stochastic-sm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(StochasticShadowMaps, kDescriptor)
