// Trapezoidal shadow maps (Martin and Tan 2004; seed 002 sec. 7.3): the camera frustum, focused on
// the visible scene, is approximated in the light's post-perspective space by a trapezoid, which
// the 2D perspective transform N_T stretches onto the whole map, so texels crowd towards the
// viewer. The trapezoid's projection centre is placed so that the focus point (a fraction `focus`
// of the visible depth range along the view axis) lands on the map's 80% line (`line`): the paper's
// 80% rule. kit/trapezoid.h derives it (seed 002 gives no equation for TSM).
// Depth: the paper's fix for the polygon-offset problem of a warped depth, depth kept out of N_T:
// the map stores linear depth along the light written per fragment, with eq. 5.2's bias there, or
// the two-layer biases of ch. 5 (kit::LayeredDepthMap).
// Known artefacts: like LiSPSM it degenerates to the focused uniform map when view and light are
// nearly parallel (duelling frusta); the focus point far along the view (focus near 1) weakens the
// warp, near 0 warps hardest (far shadows blocky). Point lights: the focused uniform map.
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/trapezoid.h>
#include <shadowlab/kit/warped_map.h>

namespace {

using namespace shadowlab;

constexpr ParamDesc kFocus{"focus", "focus point", ParamType::Float, 0.01, 0.95, 0.3, "of the depth range",
     "Where the focus point lies along the view axis, as a fraction of the visible depth range (nearest to "
     "farthest visible point): the paper's focus region, whose far end is mapped to the `line` line of the "
     "map. Smaller warps harder (near shadows sharper, far ones blockier); larger tends to the uniform map.",
     nullptr};
constexpr ParamDesc kLine{"line", "focus line", ParamType::Float, 0.1, 0.9, 0.8, "of the map",
     "The paper's 80% rule: the fraction of the map, from the near (top) edge of the trapezoid, that the "
     "focus region fills.", nullptr};

#define TSM_PARAMS(X)                                    \
    X(int, resolution, kit::resolutionParam())           \
    X(float, focus, kFocus)                              \
    X(float, line, kLine)                                \
    SHADOWLAB_WARPED_MAP_PARAMS(X)                       \
    SHADOWLAB_TWO_LAYER_PARAMS(X)
SHADOWLAB_PARAMS(Params, TSM_PARAMS);

class TrapezoidalShadowMaps final : public kit::WarpedMapTechnique<Params> {
    // N_T's z row is 0: linear depth along the light, written per fragment (the paper's fix).
    bool linearDepth(const Params&) const override { return true; }

    // The trapezoid around B's image, its centre line along the view axis from the nearest to the
    // farthest visible point (V n S, as lispsm focuses, or the receivers' measured range), the focus
    // point `focus` along it.
    std::optional<glm::mat4> warp(const FrameContext& frame, const Params& p, const kit::FocusedLightSpace& focused,
                                  const kit::DepthRange& range) override {
        if (frame.light.type == LightType::Point || focused.body.empty()) return std::nullopt;
        const float nearest = range.nearDistance, farthest = range.farDistance;
        const glm::vec3 eye = frame.camera.position;
        const glm::vec3 view = -glm::normalize(glm::vec3(frame.camera.view[0][2], frame.camera.view[1][2], frame.camera.view[2][2]));
        const tsm::TrapezoidInput input{.body = focused.body.vertices(),
                                        .nearCentre = eye + view * nearest,
                                        .farCentre = eye + view * farthest,
                                        .focusPoint = eye + view * (nearest + p.focus * (farthest - nearest)),
                                        .line = p.line};
        const auto trapezoid = tsm::fitTrapezoid(focused.light.viewProjection, input);
        host().reportStatistic("eta / lambda", trapezoid ? trapezoid->eta / trapezoid->lambda : 0.0);
        return trapezoid ? std::optional(trapezoid->viewProjection) : std::nullopt;
    }
};

constexpr FlagCondition kFlagConditions[] = {kit::kReceiverRangeNeedsDepth};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "tsm",
     .displayName = "Trapezoidal shadow maps",
     .category = "hard",
     .explanation = "Shadow mapping focused on the visible scene, then warped by the 2D perspective that stretches a "
                    "trapezoid around the camera frustum's image in the light's view onto the whole map (Martin and "
                    "Tan 2004; seed 002 sec. 7.3): near shadows get the texels. The focus point (focus, along the "
                    "view) is mapped to the 80% line (line) of the map. Depth is linear along the light, kept out "
                    "of the warp, so one bias fits near and far. Looking along the light it falls back to the "
                    "plain focused map, like lispsm. Compare with lispsm and psm on forest-002 and aliasing-plane.",
     .shadowGlsl = "tsm.glsl",
     .flags = kTechniqueNeedsCameraDepth},     // range = receivers reduces the pre-pass's depth
    Params::table, kFlagConditions);

} // namespace

SHADOWLAB_PLUGIN(TrapezoidalShadowMaps, kDescriptor)
