// Light space perspective shadow maps (Wimmer, Scherzer and Purgathofer 2004; seed 002 ch. 8 and
// the recipe of sec. 9.2.1-9.2.6: the virtual far plane for n, the body vector as the warp axis). The map is focused on the focus body B (kit/focus.h, eq. 4.2),
// then warped by a perspective transform P in light space whose axis is the view direction
// projected onto the map's plane: texels move towards the viewer, so near shadows gain resolution
// and far ones lose some, while light rays stay parallel (no change of light type as in PSM).
// n, the distance of P's centre from its near plane, sets the strength of the warp; n_opt (eq.
// 8.10-8.13) equalises the error at B's near and far ends (lispsm_warp.h derives it).
// Known artefacts: when view and light are nearly parallel (duelling frusta, Fig. 8.11) the warp
// converges to uniform and the map is a plain focused one; n too small over-warps (far shadows
// blocky), too large under-warps (Fig. 8.4); depth is hyperbolic along the warp, so bias is in
// uneven units: back faces in the map (cull = front, sec. 9.3) is the default.
// Spot lights: the general case of sec. 8.2.4 / 9.2.3, the warp built in the spot's post-perspective
// space, where its rays are parallel (lispsm_warp.h's spotWarp). Point lights: up to six spot-like
// frusta, the faces of the light's cube (kit/warped_faces.h): each face that sees a visible point
// gets its own map focused on B_f (the view's part in the face, joined with the light) and warped
// as a spot light from the nearest visible vertex in it (sec. 9.2.3's e_world), or focused
// uniformly where the warp is uniform anyway; the lookup picks the face by (P - light)'s major
// axis. Biasing (ch. 5) and linear depth: kit::LayeredDepthMap (bias_method, z_offset are the
// kit's), per face under a point light.
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/warped_map.h>

#include "shadowlab/kit/lispsm_warp.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kNFactor{"n_factor", "warp distance n / n_opt", ParamType::Float, 0.05, 20, 1, "",
     "n, the distance of the warp's centre from its near plane, as a multiple of n_opt (seed 002 eq. "
     "8.13): 1 equalises the error at the focus body's near and far ends. Smaller warps harder (near "
     "shadows sharper, far ones blocky: Fig. 8.4 left); larger tends to a uniform focused map (Fig. 8.4 "
     "right).", nullptr};
constexpr ParamDesc kVirtualFar{"virtual_far", "virtual far plane z_f", ParamType::Float, 0, 1000, 0, "m",
     "Seed 002 sec. 9.2.5: the far distance of a virtual view frustum from which n alone is computed "
     "(eq. 8.13's d, z0, z1 from the focus body of the frustum cut there); the map still covers the "
     "whole body B, so casters beyond it still cast. Nearer warps harder: shadows up to z_f sharper, "
     "beyond it blockier (Fig. 9.3). 0 (or beyond the camera's far plane): the camera's far plane, the "
     "recipe without the option.", nullptr};
constexpr ParamDesc kBodyVector{"body_vector", "body vector", ParamType::Bool, 0, 1, 0, "",
     "Seed 002 sec. 9.2.6, directional lights: the warp's axis from the body vector (the sum of the "
     "vectors from the eye to the focus body's corners, pointing into the middle of B) instead of the "
     "view direction. Off: the view direction, which misses B's middle where the scene's bounds cut the "
     "frustum off-centre (looking out of the scene, down onto the ground). Off by default: on forest-002 "
     "it lowers the near third's error at 2048 texels but raises the far third's at 1024 and 2048 "
     "(docs/plugin-api.md).", nullptr};
constexpr ParamDesc kDepth = kit::enumParam("depth", "stored depth", 0, "hyperbolic|linear",
     "What the map stores (seed 002 sec. 5.3): the warp's own hyperbolic z, whose steps grow along the "
     "warp so that one bias is too small at one end and too large at the other, or linear depth along "
     "the light over the focus body (TSM's linear z), written per fragment with the slope-scaled bias "
     "done in the shader.");
#define LISPSM_PARAMS(X)                                 \
    X(int, resolution, kit::resolutionParam())           \
    X(float, n_factor, kNFactor)                         \
    X(float, virtual_far, kVirtualFar)                   \
    X(bool, body_vector, kBodyVector)                    \
    SHADOWLAB_WARPED_MAP_PARAMS(X)                       \
    X(int, depth, kDepth)                                \
    SHADOWLAB_TWO_LAYER_PARAMS(X)
SHADOWLAB_PARAMS(Params, LISPSM_PARAMS);

class LightSpacePerspectiveShadowMaps final : public kit::WarpedMapTechnique<Params> {
    bool linearDepth(const Params& p) const override { return p.depth == 1; }
    bool warpsCubeFaces() const override { return true; }

    // The options of sec. 9.2.5-9.2.6 for a map of `light` (the spot's frustum, or a point light's
    // face): n's factor, n from the virtual frustum's body (only where it is nearer than the real
    // one; with range = receivers the farthest receiver is one), the body vector of B's corners.
    lispsm::WarpOptions options(const FrameContext& frame, const Params& p, const kit::ConvexBody& body,
                                const kit::DepthRange& range, const LightSpace& light, bool face) {
        const Bounds scene = host().bounds(DrawSet::All);
        lispsm::WarpOptions options;
        options.nFactor = p.n_factor;
        float farForN = p.virtual_far > 0.0f ? p.virtual_far : frame.camera.farPlane;
        if (p.range == 1) farForN = std::min(farForN, range.farDistance);
        if (farForN < frame.camera.farPlane) {
            const kit::ConvexBody virtualView = lispsm::virtualViewBody(frame.camera, farForN);
            options.bodyForN = (face ? kit::faceFocusBody(virtualView, frame.light, scene, light)
                                     : kit::focusBody(virtualView, frame.light, scene, light)).vertices();
        }
        if (p.body_vector)
            options.axisSource = lispsm::bodyVector(body.corners(kit::focus_detail::toleranceFor(body)), frame.camera.position);
        return options;
    }

    // Sec. 9.2.1-9.2.6: the warp of a directional light, or of a spot light in its post-perspective
    // space; none for point lights (faceWarp()) or where it would be uniform anyway.
    std::optional<glm::mat4> warp(const FrameContext& frame, const Params& p, const kit::FocusedLightSpace& focused,
                                  const kit::DepthRange& range) override {
        if (frame.light.type == LightType::Point || focused.body.empty()) return std::nullopt;
        kit::ConvexBody visible = kit::frustumBody(frame.camera.inverseViewProjection);
        kit::clip(visible, host().bounds(DrawSet::All));
        const lispsm::WarpOptions o = options(frame, p, focused.body, range, focused.light, false);
        const float nearest = std::max(lispsm::nearestEyeDepth(frame.camera, visible.vertices()), range.nearDistance);
        const auto w = frame.light.type == LightType::Spot
                           ? lispsm::spotWarp(focused.body.vertices(), focused.light.viewProjection, frame.camera, nearest, o)
                           : lispsm::directionalWarp(focused.body.vertices(), frame.light.direction, frame.camera, nearest, o);
        return w ? std::optional(w->viewProjection) : std::nullopt;
    }

    // A point light's face as a spot light (sec. 8.2.4, 9.2.3): the warp in the face's
    // post-perspective space, its orientation ray from e_world, the vertex of LVS (the view's part
    // in the face) nearest the eye, moved along the view to range = receivers' near distance; the
    // frame rooted there (sec. 9.2.4's C_start), since the eye is mostly outside the face.
    std::optional<glm::mat4> faceWarp(const FrameContext& frame, const Params& p, const kit::CubeFaceFocus& face,
                                      const kit::DepthRange& range) override {
        const std::vector<glm::vec3> visible = face.visible.vertices();
        if (visible.empty()) return std::nullopt;
        glm::vec3 start = visible.front();
        float nearest = 1e30f;
        for (const glm::vec3& v : visible) {
            const float depth = -(frame.camera.view * glm::vec4(v, 1.0f)).z;
            if (depth < nearest) {
                nearest = depth;
                start = v;
            }
        }
        const glm::vec3 view = -glm::vec3(frame.camera.view[0][2], frame.camera.view[1][2], frame.camera.view[2][2]);
        if (range.nearDistance > nearest) {
            start += view * (range.nearDistance - nearest);
            nearest = range.nearDistance;
        }
        const auto w = lispsm::spotWarpFrom(face.body.vertices(), face.light.viewProjection, frame.camera, start, nearest,
                                            false, options(frame, p, face.body, range, face.light, true));
        return w ? std::optional(w->viewProjection) : std::nullopt;
    }
};

constexpr FlagCondition kFlagConditions[] = {kit::kReceiverRangeNeedsDepth};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "lispsm",
     .displayName = "Light space perspective shadow maps",
     .category = "hard",
     .explanation = "Shadow mapping focused on the part of the scene that can shadow the view (the focus body), "
                    "then warped by a perspective transform along the view direction as seen from the light, so "
                    "texels crowd towards the viewer: sharp shadows near the camera from the same map size, at "
                    "the cost of distant ones (seed 002 ch. 8-9). The warp distance n is n_opt times n_factor "
                    "(try 0.2 and 5); looking along the light the warp fades to a plain focused map (duelling "
                    "frusta). A point light gets one warped map per cube face that sees the view (seed 002 "
                    "sec. 8.2.4). Back faces are stored by default (cull = front), the seed's best bias. snap "
                    "only affects the uniform fallback (near-parallel view and light, or a point light's face "
                    "whose warp would be uniform). Debug views: footprint (the warp's texels per pixel, near "
                    "against far), texel-grid and coverage (the warped map and its volume; under a point light "
                    "each pixel's first reported face whose map holds it), focus-body (B, seed 002 eq. 4.2; per "
                    "face under a point light), and the depth image (the six faces' atlas under a point light).",
     .shadowGlsl = "lispsm.glsl",
     .flags = kTechniqueNeedsCameraDepth,              // range = receivers reduces the pre-pass's depth
     .translucencyModel = TranslucencyModel::Ignore},  // its map holds opaque casters only
    Params::table, kFlagConditions);

} // namespace

SHADOWLAB_PLUGIN(LightSpacePerspectiveShadowMaps, kDescriptor)
