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
// Biasing: also the two-layer methods of seed 002 ch. 5 (bias_method: midpoint, eq. 5.1, and second
// depth; kit/layered_depth.h).
// Point lights: a cube of six faces storing the linear distance (kit/cube_depth_map.h), with the
// same resolution (per face), bias, culling and filter; `fit`, `snap` and the two-layer methods do
// not apply to it.
#include <shadowlab/kit/cube_depth_map.h>
#include <shadowlab/kit/layered_depth.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

namespace {

using namespace shadowlab;

#define SHADOWMAP_PARAMS(X)                              \
    SHADOWLAB_DEPTH_MAP_PARAMS(X, 2048, 200000, 1)       \
    X(bool, hardware_filter, kit::hardwareFilterParam()) \
    SHADOWLAB_FIT_PARAMS(X)                              \
    SHADOWLAB_TWO_LAYER_PARAMS(X)
SHADOWLAB_PARAMS(Params, SHADOWMAP_PARAMS);

class ShadowMapping final : public kit::TechniqueBase {
    bool setup(std::string& error) override { return map_.create(host(), error) && cube_.create(host(), error); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const kit::DepthMapConfig config = kit::depthMapConfig(p);
        if (frame.light.type == LightType::Point) return cube_.render(frame, config);
        map_.render(frame, config, kit::layeredDepthConfig(p));
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        const SamplerKind sampling = Params::read(params).hardware_filter ? SamplerKind::CompareLinear : SamplerKind::CompareNearest;
        if (frame.light.type == LightType::Point) return cube_.bindMainPass(sampling);
        map_.bindMainPass(sampling);
    }

    kit::LayeredDepthMap map_;
    kit::CubeDepthMap cube_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "shadowmap",
     .displayName = "Shadow mapping",
     .category = "hard",
     .explanation = "Renders the scene's depth from the light, then compares each visible point's depth in light "
                    "space with the stored one: farther means shadowed. Works for any geometry and receiver, costs "
                    "one extra pass, and shows the classic artefacts: acne (self-shadowing from depth quantisation; "
                    "cured by bias), peter panning (too much bias) and blocky edges (limited resolution). Try a low "
                    "light and zero bias.",
     .shadowGlsl = "shadowmap.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(ShadowMapping, kDescriptor)
