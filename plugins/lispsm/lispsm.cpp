// Light space perspective shadow maps (Wimmer, Scherzer and Purgathofer 2004; seed 002 ch. 8 and
// the recipe of sec. 9.2.1-9.2.5). The map is focused on the focus body B (kit/focus.h, eq. 4.2),
// then warped by a perspective transform P in light space whose axis is the view direction
// projected onto the map's plane: texels move towards the viewer, so near shadows gain resolution
// and far ones lose some, while light rays stay parallel (no change of light type as in PSM).
// n, the distance of P's centre from its near plane, sets the strength of the warp; n_opt (eq.
// 8.10-8.13) equalises the error at B's near and far ends (lispsm_warp.h derives it).
// Known artefacts: when view and light are nearly parallel (duelling frusta, Fig. 8.11) the warp
// converges to uniform and the map is a plain focused one; n too small over-warps (far shadows
// blocky), too large under-warps (Fig. 8.4); depth is hyperbolic along the warp, so bias is in
// uneven units: back faces in the map (cull = front, sec. 9.3) is the default.
// Spot and point lights: a focused uniform map (the warp is built for directional lights here).
#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/focus.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "lispsm_warp.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kParams[] = {
    kit::resolutionParam(),
    {"n_factor", "warp distance n / n_opt", ParamType::Float, 0.05, 20, 1, "",
     "n, the distance of the warp's centre from its near plane, as a multiple of n_opt (seed 002 eq. "
     "8.13): 1 equalises the error at the focus body's near and far ends. Smaller warps harder (near "
     "shadows sharper, far ones blocky: Fig. 8.4 left); larger tends to a uniform focused map (Fig. 8.4 "
     "right).", nullptr},
    kit::constantBiasParam(),
    kit::slopeBiasParam(),
    kit::cullParam(2),
    kit::hardwareFilterParam(),
    kit::snapParam(),
};
enum : uint32_t {
    kResolution = kit::paramIndex(kParams, "resolution"),
    kNFactor = kit::paramIndex(kParams, "n_factor"),
    kConstantBias = kit::paramIndex(kParams, "constant_bias"),
    kSlopeBias = kit::paramIndex(kParams, "slope_bias"),
    kCull = kit::paramIndex(kParams, "cull"),
    kHardwareFilter = kit::paramIndex(kParams, "hardware_filter"),
    kSnap = kit::paramIndex(kParams, "snap"),
};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "lispsm",
     .displayName = "Light space perspective shadow maps",
     .category = "hard",
     .explanation = "Shadow mapping focused on the part of the scene that can shadow the view (the focus body), "
                    "then warped by a perspective transform along the view direction as seen from the light, so "
                    "texels crowd towards the viewer: sharp shadows near the camera from the same map size, at "
                    "the cost of distant ones (seed 002 ch. 8-9). The warp distance n is n_opt times n_factor "
                    "(try 0.2 and 5); looking along the light the warp fades to a plain focused map (duelling "
                    "frusta). Back faces are stored by default (cull = front), the seed's best bias. snap only "
                    "affects that uniform fallback (spot and point lights, near-parallel view and light).",
     .shadowGlsl = "lispsm.glsl",
     .translucencyModel = TranslucencyModel::Ignore},   // its map holds opaque casters only
    kParams);

class LightSpacePerspectiveShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override { return map_.create(host(), error); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const kit::DepthMapConfig config{.resolution = params.asInt(kResolution),
                                         .constantBias = params.asFloat(kConstantBias),
                                         .slopeBias = params.asFloat(kSlopeBias),
                                         .cull = kit::Cull(params.asInt(kCull))};
        map_.ensureTexture(config.resolution, config.format);
        GpuPass pass(host(), "shadow map");
        // Step 1 of sec. 9.2.1: focus on B (the uniform fallback when there is no warp).
        const kit::FocusedLightSpace focused =
            kit::focusLightSpace(host(), frame, {kit::Fit::FocusBody, params.asBool(kSnap)}, config.resolution);
        LightSpace lightSpace = focused.light;
        if (frame.light.type == LightType::Directional && !focused.body.empty()) {
            kit::ConvexBody visible = kit::frustumBody(frame.camera.inverseViewProjection);
            kit::clip(visible, host().bounds(DrawSet::All));
            const auto warp = lispsm::directionalWarp(focused.body.vertices(), frame.light.direction, frame.camera,
                                                      lispsm::nearestEyeDepth(frame.camera, visible.vertices()),
                                                      params[kNFactor]);
            if (warp) {
                // The view stays the light's (the block's light axis reads it); P L is the whole matrix.
                lightSpace.viewProjection = warp->viewProjection;
                lightSpace.projection = warp->viewProjection * glm::inverse(lightSpace.view);
                lightSpace.perspective = true;
            }
        }
        // Casters between B and the light's side of the scene are in B; depth clamp keeps any part of
        // a kept caster beyond the warp's depth range in the map rather than clipping it away.
        glEnable(GL_DEPTH_CLAMP);
        map_.drawDepth(lightSpace, config, focused.cullPlanes);
        glDisable(GL_DEPTH_CLAMP);
        map_.reportToHost();
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        map_.bindMainPass(params.asBool(kHardwareFilter) ? SamplerKind::CompareLinear : SamplerKind::CompareNearest);
    }

    kit::DepthMap map_;
};

} // namespace

SHADOWLAB_PLUGIN(LightSpacePerspectiveShadowMaps, kDescriptor)
