// Coloured stochastic shadow maps, CSSM2 (McGuire and Enderton 2011, "Colored stochastic shadow
// maps"; seed 001 sec. 2.1.3 for the algorithm, sec. 4.2.2 for the one-pass variant built here,
// sec. 5.3.1 Fig. 5.3.D for its timing with 9 x 9 and 3 x 3 kernels, sec. 5.3.2-5.3.3 for its
// image quality). A depth buffer and an RGB colour map of depths (RGBA32F, cleared to 1) from the
// light, in one render pass (cssm2_caster.frag):
//   opaque casters write their depth to the depth buffer and to every channel (LESS, depth write);
//   translucent casters are depth-tested against that depth without writing, blend MIN, and write
//   max(depth, [xi_c >= p_c]) per channel with p = alpha (1 - t): the depth where a photon of
//   channel c stops, so each channel ends up holding the nearest depth at which its photon did.
// The main pass compares each channel, lit_c = [z <= C_c], over an n x n box of fetches (manual PCF:
// there is no hardware comparison on a colour map). Expectation prod ((1 - a_i) + a_i t_i,c): the
// physical model M2, coloured, on every layer (translucent receivers included, Fig. 5.3.3.A).
// xi is a hash per texel, object, triangle, channel and frame (kit/stochastic_shared.h); seed 001's
// noise texture indexed by texel alone is the `per-texel` noise, which is wrong wherever surfaces
// overlap (1 - max p instead of the product; derived, not in seed 001: docs/coloured-shadows.md).
// Format and clear value are not stated in seed 001: the map must hold depths, so 32F and 1.
// Known artefacts: noise, worst where much light gets through with little saturation (sec.
// 5.3.2); blurred edges from the wide kernels the noise needs; kernel cost without hardware PCF.
#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/stochastic_light_pass.h>
#include <shadowlab/kit/technique_base.h>

#include "cssm2_shared.h"

namespace {

using namespace shadowlab;

// Capped below kit::resolutionParam's 8192: the map is 16 bytes a texel (8192^2: 1 GiB).
constexpr ParamDesc kResolution = kit::withHelp(kit::resolutionParam(2048, 4096),
     "Width and height of the depth buffer and the RGBA32F colour map (16 + 4 bytes a texel: 80 MiB at "
     "2048). Low values make edges blocky; a kernel in texels then covers more of the scene.");
constexpr ParamDesc kKernel{"kernel", "kernel size n", ParamType::Int, 1, 11, 5, "taps",
     "n x n texel fetches, each compared per channel in the shader and averaged. 1 shows the raw "
     "photons (every texel all or nothing per channel); seed 001 timed 9 x 9 and 3 x 3. Cost grows with "
     "n^2 and every edge blurs over n texels.",
     nullptr};
constexpr ParamDesc kConstantBias = kit::withHelp(kit::constantBiasParam(64),
     "Added to every depth the colour map stores, in units of 2^-24 (what glPolygonOffset's units are "
     "for 32F depth near 1; a colour attachment gets no polygon offset, so the shader adds it). Zero "
     "shows acne; large values detach shadows from their casters.");
constexpr ParamDesc kSlopeBias = kit::withHelp(kit::slopeBiasParam(),
     "Added to every stored depth times its slope as seen from the light (glPolygonOffset's factor, "
     "applied in the shader). Zero leaves acne on tilted surfaces; large values push shadows off grazing "
     "contacts.");

#define CSSM2_PARAMS(X)                      \
    X(int, resolution, kResolution)          \
    X(int, kernel, kKernel)                  \
    X(int, noise, kit::noiseParam())         \
    X(bool, cone_bias, kit::coneBiasParam()) \
    X(float, constant_bias, kConstantBias)   \
    X(float, slope_bias, kSlopeBias)         \
    SHADOWLAB_FIT_PARAMS(X)
SHADOWLAB_PARAMS(Params, CSSM2_PARAMS);

class ColouredStochasticShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!opaqueProgram_.build(host(),
                                  {.vertexFile = "depth_only.vert", .fragmentFile = "cssm2_caster.frag",
                                   .defines = "OPAQUE_CASTER 1"},
                                  error))
            return false;
        if (!translucentProgram_.build(host(), {.vertexFile = "translucent_caster.vert", .fragmentFile = "cssm2_caster.frag"},
                                       error))
            return false;
        lightPass_.create(host(), "cssm2 map");
        uniforms_.create(host(), "cssm2 uniforms");
        return true;
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        if (lightPass_.ensure({.resolution = p.resolution, .colourFormat = GL_RGBA32F})) {
            host().registerDebugImage("cssm2 opaque depth", lightPass_.target().depth(), DebugImageKind::Depth);
            host().registerDebugImage("cssm2 colour map", lightPass_.target().colour(), DebugImageKind::Color);
        }
        GpuPass pass(host(), "shadow map");
        // The colour map gets no polygon offset: the caster shader adds the bias.
        lightPass_.begin(frame, kit::fitConfig(p), {{}, 0u, p.noise, p.slope_bias, p.constant_bias});
        const float far[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        glClearBufferfv(GL_COLOR, 0, far);
        glClearBufferfv(GL_DEPTH, 0, far);
        lightPass_.draw(DrawSet::OpaqueCasters, opaqueProgram_);
        glDepthMask(GL_FALSE);
        glEnable(GL_BLEND);
        glBlendEquation(GL_MIN);   // factors are ignored by MIN (seed 001: ONE, ONE)
        glBlendFunc(GL_ONE, GL_ONE);
        lightPass_.draw(DrawSet::TranslucentCasters, translucentProgram_);
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        const Params p = Params::read(params);
        glBindTextureUnit(shared::cssm2::kColourMapUnit, lightPass_.target().colour());
        glBindSampler(shared::cssm2::kColourMapUnit, host().sampler(SamplerKind::Nearest));
        lightPass_.bindMainPass();
        uniforms_.set({{}, p.kernel, p.cone_bias ? 1.0f : 0.0f, 0.0f, 0.0f});
    }

    kit::Program opaqueProgram_;
    kit::Program translucentProgram_;
    kit::StochasticLightPass lightPass_;
    kit::UniformBlock<shared::cssm2::Cssm2Uniforms> uniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kStochasticColourMap,
    {.id = "cssm2",
     .displayName = "Coloured stochastic shadow maps (CSSM2)",
     .category = "coloured",
     .explanation = "A depth map and a colour map from the light in which each channel is a depth map of its "
                    "own: opaque casters write their depth to every channel; each translucent surface stops "
                    "the photon of channel c with probability alpha (1 - t_c) and then writes its depth there, "
                    "keeping the nearest (MIN blending). A point is lit in channel c where it is no farther than "
                    "where that photon stopped, averaged over n x n texels. The result converges to the physical "
                    "transmission, coloured and right on every layer of glass, as the kernel grows, but it is "
                    "noisy (worst in bright, unsaturated light), the kernel blurs edges and, without hardware "
                    "comparison on a colour map, costs n^2 fetches. Try kernel 1, and noise = per-texel under "
                    "overlapping glass.",
     .shadowGlsl = "cssm2.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(ColouredStochasticShadowMaps, kDescriptor)
