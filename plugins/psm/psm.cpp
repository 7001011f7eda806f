// Perspective shadow maps (Stamminger and Drettakis 2002; seed 002 ch. 7): the map is rendered in
// the camera's post-perspective space, where the view frustum is the unit cube, so near shadows
// get the texels (psm_space.h derives the light space, the uneven z distribution, the virtual
// move-back and the change of light type). Included as the method LiSPSM was built to fix: its
// quality hangs on the near plane and jumps with the move-back, and a light in front of the
// viewer shining back (duelling frusta) needs more than one map; there this falls back to the
// plain focused map, and says so in the statistic "fallback". Biasing: also the two-layer methods
// of seed 002 ch. 5 (bias_method; kit/layered_depth.h).
#include <shadowlab/kit/focus.h>
#include <shadowlab/kit/layered_depth.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "shadowlab/kit/psm_space.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kMoveBack{"move_back", "virtual move-back", ParamType::Bool, 0, 1, 1, "",
     "Seed 002 sec. 7.2.2: casters behind the viewer that shadow the view cross the camera's "
     "singularity in post-perspective space, so the camera is moved back virtually until the whole "
     "focus body is in front of it. Off: the body is cut at the camera's near plane and the depth pass "
     "clips there, so those casters are lost (light leaks in front of the viewer: the stress case "
     "light-behind); the warp is at its strongest. On: they are kept, the warp weakens with the "
     "distance moved back.",
     nullptr};

#define PSM_PARAMS(X)                                    \
    X(int, resolution, kit::resolutionParam())           \
    SHADOWLAB_BIAS_PARAMS(X, 64, 2)                      \
    X(bool, hardware_filter, kit::hardwareFilterParam()) \
    X(bool, move_back, kMoveBack)                        \
    SHADOWLAB_TWO_LAYER_PARAMS(X)
SHADOWLAB_PARAMS(Params, PSM_PARAMS);

class PerspectiveShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override { return maps_.create(host(), error); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        kit::DepthMapConfig config = kit::depthMapConfig(p);   // no fit parameter: the focus body below
        GpuPass pass(host(), "shadow map");
        // The view from the nearest visible receiver on (psm_space.h), and its B (eq. 4.2): what the
        // map must hold, and what decides the move-back and the near plane.
        FrameContext shortened = frame;
        shortened.camera = psm::receiverCamera(
            frame.camera, psm::nearestReceiverDepth(frame.camera, host().objects(), host().objectCount()));
        const kit::FocusedLightSpace focused =
            kit::focusLightSpace(host(), shortened, {kit::Fit::FocusBody, false}, config.resolution);
        LightSpace lightSpace = focused.light;
        kit::ConvexBody body = focused.body;
        if (!p.move_back) {
            // Only B's part in front of the (receiver) near plane: the move-back is then 0, and
            // the depth pass clips at the camera plane, so casters behind the viewer are lost.
            const glm::vec3 forward = -glm::vec3(shortened.camera.view[0][2], shortened.camera.view[1][2], shortened.camera.view[2][2]);
            const glm::vec3 eye = glm::vec3(glm::inverse(shortened.camera.view)[3]);
            kit::clip(body, glm::vec4(forward, -glm::dot(forward, eye) - shortened.camera.nearPlane));
        }
        const auto space = psm::psmSpace(shortened.camera, frame.light, body.vertices());
        host().reportStatistic("near plane", shortened.camera.nearPlane);
        if (space) {
            lightSpace.viewProjection = space->viewProjection;
            lightSpace.projection = space->viewProjection * glm::inverse(lightSpace.view);
            lightSpace.perspective = true;
            config.clipPlane = space->clipPlane;
        }
        host().reportStatistic("fallback", space ? 0.0 : 1.0);
        host().reportStatistic("move-back", space ? space->moveBack : 0.0);
        host().reportStatistic("post-perspective light (0 point, 1 directional, 2 inverted)",
                               space ? double(int(space->lightType)) : -1.0);
        // Depth clamp: parts of kept casters beyond the light frustum's depth range still occlude.
        glEnable(GL_DEPTH_CLAMP);
        maps_.draw(lightSpace, config, kit::layeredDepthConfig(p), focused.cullPlanes);
        glDisable(GL_DEPTH_CLAMP);
        maps_.map().setFocusBody(body);
        maps_.map().reportToHost();
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        const Params p = Params::read(params);
        maps_.bindMainPass(p.hardware_filter ? SamplerKind::CompareLinear : SamplerKind::CompareNearest);
    }

    kit::LayeredDepthMap maps_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "psm",
     .displayName = "Perspective shadow maps",
     .category = "hard",
     .explanation = "The shadow map is rendered after the camera's own perspective, where the view frustum is a "
                    "cube: near shadows get most texels (seed 002 ch. 7). Its weak points are the seed's: the "
                    "near plane decides the distribution (half the depth range goes to the first near-distance "
                    "in front of the camera, eq. 7.1-7.2), casters behind the viewer need a virtual move-back "
                    "that weakens the warp and jumps as the view turns, and a light from in front of the viewer "
                    "cannot be held in one map (it falls back to a plain focused map). Compare with lispsm, "
                    "which keeps light rays parallel and tunes the warp with n_opt; turn move_back off with the light "
                    "behind the camera to see casters lost.",
     .shadowGlsl = "psm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(PerspectiveShadowMaps, kDescriptor)
