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
// Known artefacts: noise under translucent casters, which only wide kernels (blurring every edge)
// average away; no colour (a red glass casts a grey shadow); the `per-texel` noise lets stacked
// surfaces through as 1 - max a instead of prod (1 - a_i).
#include <shadowlab/kit/focus.h>
#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/light_target.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/stochastic_shared.h>
#include <shadowlab/kit/technique_base.h>

#include "stochastic_sm_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kParams[] = {
    kit::resolutionParam(),
    {"kernel", "kernel size n", ParamType::Int, 1, 9, 5, "taps",
     "n x n taps one texel apart, averaged per pixel. The map is a coin flip per translucent texel, so "
     "small kernels show the noise (1: every texel lit or not); 9 x 9 is what seed 001 timed. Larger "
     "kernels cost n^2 lookups and blur every edge.",
     nullptr},
    {"hardware_filter", "hardware 2x2 per tap", ParamType::Bool, 0, 1, 1, "",
     "Every tap is the texture unit's bilinear 2x2 comparison (seed 001 timed 2x2 hardware PCF under its "
     "9 x 9 kernel): about (n + 1)^2 texels of noise averaged for n^2 lookups. Off: n^2 plain tests, "
     "noisier and with n^2 + 1 shades.",
     nullptr},
    kit::noiseParam(),
    kit::coneBiasParam(),
    kit::constantBiasParam(),
    kit::slopeBiasParam(),
    kit::fitParam(),
    kit::snapParam(),
};
enum : uint32_t {
    kResolution = kit::paramIndex(kParams, "resolution"),
    kKernel = kit::paramIndex(kParams, "kernel"),
    kHardwareFilter = kit::paramIndex(kParams, "hardware_filter"),
    kNoise = kit::paramIndex(kParams, "noise"),
    kConeBias = kit::paramIndex(kParams, "cone_bias"),
    kConstantBias = kit::paramIndex(kParams, "constant_bias"),
    kSlopeBias = kit::paramIndex(kParams, "slope_bias"),
    kFit = kit::paramIndex(kParams, "fit"),
    kSnap = kit::paramIndex(kParams, "snap"),
};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "stochastic-sm",
     .displayName = "Stochastic shadow maps",
     .category = "coloured",
     .explanation = "One depth map from the light in which each translucent fragment is kept with probability "
                    "alpha and thrown away otherwise (a random number per texel, surface and frame). Filtering "
                    "the map with PCF then estimates how much light gets through every layer: 1 - alpha per "
                    "translucent surface, right on translucent surfaces too, but without colour (a red glass "
                    "casts a grey shadow: judged by the coverage model). The price is noise, which needs wide "
                    "kernels that blur every edge; it changes every frame. Try kernel 1 to see the coin flips, "
                    "and noise = per-texel under overlapping glass to see what shared random numbers do. Debug views: footprint, texel-grid and coverage (the map and its volume), and 'stochastic shadow map'.",
     .shadowGlsl = "stochastic-sm.glsl",
     .translucencyModel = TranslucencyModel::Coverage},
    kParams);

class StochasticShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!opaqueProgram_.build(host(), {.vertexFile = "depth_only.vert"}, error)) return false;
        if (!translucentProgram_.build(host(),
                                       {.vertexFile = "translucent_caster.vert", .fragmentFile = "stochastic_sm_caster.frag"},
                                       error))
            return false;
        target_.create(host(), "stochastic shadow map");
        mapUniforms_.create(host(), "stochastic shadow map uniforms");
        passUniforms_.create(host(), "stochastic light pass uniforms");
        uniforms_.create(host(), "stochastic-sm uniforms");
        return true;
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const int resolution = params.asInt(kResolution);
        if (target_.ensure({.resolution = resolution}))
            host().registerDebugImage("stochastic shadow map", target_.depth(), DebugImageKind::Depth);
        GpuPass pass(host(), "shadow map");
        const kit::FocusedLightSpace focused = kit::focusLightSpace(host(), frame, kit::readFit(params, kFit, kSnap), resolution);
        const LightSpace& lightSpace = focused.light;
        mapUniforms_.set(kit::lightSpaceUniforms(lightSpace, resolution));
        kit::reportShadowMap(host(), lightSpace.viewProjection, {resolution, resolution});
        passUniforms_.set({{}, frame.randomSeed, params.asInt(kNoise), 0.0f, 0.0f});
        target_.bind();
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(params.asFloat(kSlopeBias), params.asFloat(kConstantBias));
        host().drawScene(kit::culledDraw(DrawSet::OpaqueCasters, focused.cullPlanes), opaqueProgram_.use());
        // The same depth test and writes: a kept translucent fragment is an opaque one.
        host().drawScene(kit::culledDraw(DrawSet::TranslucentCasters, focused.cullPlanes), translucentProgram_.use());
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        const bool bilinear = params.asBool(kHardwareFilter);
        glBindTextureUnit(kit::kDepthMapUnit, target_.depth());
        glBindSampler(kit::kDepthMapUnit, host().sampler(bilinear ? SamplerKind::CompareLinear : SamplerKind::CompareNearest));
        mapUniforms_.bind();
        uniforms_.set({{}, params.asInt(kKernel), bilinear ? 1 : 0, params.asBool(kConeBias) ? 1.0f : 0.0f, 0.0f});
    }

    kit::Program opaqueProgram_;
    kit::Program translucentProgram_;
    kit::LightTarget target_;
    kit::UniformBlock<kit::DepthMapUniforms> mapUniforms_;
    kit::UniformBlock<shared::stochastic::StochasticPassUniforms> passUniforms_;
    kit::UniformBlock<shared::stochastic_sm::StochasticSmUniforms> uniforms_;
};

} // namespace

SHADOWLAB_PLUGIN(StochasticShadowMaps, kDescriptor)
