// Basic shadow mapping (Williams 1978; seed 000 sections 2.2.4 and 3.2.2, seed 004 slides).
// Pass 1 renders the depth of the scene from the light into a texture: orthographic for
// directional lights, perspective for spot (and point) lights. Pass 2, in the host's main pass,
// projects each shaded point into that texture and compares depths: a point farther from the
// light than the stored depth is in shadow.
// Known artefacts: shadow acne without bias (seed 000 Fig. 3.7-3.8a), peter panning with too much
// bias (Fig. 3.8b), blocky edges from limited resolution (Fig. 3.6).
// Options: constant and slope-scaled bias through glPolygonOffset, culling of front faces in
// the shadow pass (only back faces are stored; seed 002 "biasing with back faces"), and the
// hardware's 2x2 comparison filter (sampler2DShadow with linear filtering).
// Point lights: a cube of six faces storing the linear distance (kit/cube_depth_map.h), with the
// same resolution (per face), bias, culling and filter; `fit` and `snap` do not apply to it.
#include <shadowlab/kit/cube_depth_map.h>
#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

namespace {

using namespace shadowlab;

constexpr ParamDesc kParams[] = {
    kit::resolutionParam(),
    kit::depthFormatParam(),
    kit::constantBiasParam(200000),
    kit::slopeBiasParam(),
    kit::cullParam(),
    kit::hardwareFilterParam(),
    kit::fitParam(),
    kit::snapParam(),
};
enum : uint32_t {
    kResolution = kit::paramIndex(kParams, "resolution"),
    kDepthFormat = kit::paramIndex(kParams, "depth_format"),
    kConstantBias = kit::paramIndex(kParams, "constant_bias"),
    kSlopeBias = kit::paramIndex(kParams, "slope_bias"),
    kCull = kit::paramIndex(kParams, "cull"),
    kHardwareFilter = kit::paramIndex(kParams, "hardware_filter"),
    kFit = kit::paramIndex(kParams, "fit"),
    kSnap = kit::paramIndex(kParams, "snap"),
};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "shadowmap",
     .displayName = "Shadow mapping",
     .category = "hard",
     .explanation = "Renders the scene's depth from the light, then compares each visible point's depth in light "
                    "space with the stored one: farther means shadowed. Works for any geometry and receiver, costs "
                    "one extra pass, and shows the classic artefacts: acne (self-shadowing from depth quantisation; "
                    "cured by bias), peter panning (too much bias) and blocky edges (limited resolution). Try a low "
                    "light and zero bias. Debug views: footprint, texel-grid and coverage (the map and its volume), focus-body (with fit = focus-body: B, seed 002 eq. 4.2), and the 'shadow map' depth image.",
     .shadowGlsl = "shadowmap.glsl",
     .translucencyModel = TranslucencyModel::Ignore},   // its map holds opaque casters only
    kParams);

class ShadowMapping final : public kit::TechniqueBase {
    bool setup(std::string& error) override { return map_.create(host(), error) && cube_.create(host(), error); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const kit::DepthMapConfig config{.resolution = params.asInt(kResolution),
                                         .format = kit::depthFormat(params.asInt(kDepthFormat)),
                                         .constantBias = params.asFloat(kConstantBias),
                                         .slopeBias = params.asFloat(kSlopeBias),
                                         .cull = kit::Cull(params.asInt(kCull)),
                                         .fit = kit::readFit(params, kFit, kSnap)};
        if (frame.light.type == LightType::Point) return cube_.render(frame, config);
        map_.render(frame, config);
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        const SamplerKind sampling = params.asBool(kHardwareFilter) ? SamplerKind::CompareLinear : SamplerKind::CompareNearest;
        if (frame.light.type == LightType::Point) return cube_.bindMainPass(sampling);
        map_.bindMainPass(sampling);
    }

    kit::DepthMap map_;
    kit::CubeDepthMap cube_;
};

} // namespace

SHADOWLAB_PLUGIN(ShadowMapping, kDescriptor)
