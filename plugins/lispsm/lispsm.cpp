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
// Spot and point lights: a focused uniform map (the warp is built for directional lights here).
#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/focus.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "lispsm_shared.h"
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
constexpr ParamDesc kDepth{"depth", "stored depth", ParamType::Enum, 0, 1, 0, "",
     "What the map stores (seed 002 sec. 5.3): the warp's own hyperbolic z, whose steps grow along the "
     "warp so that one bias is too small at one end and too large at the other, or linear depth along "
     "the light over the focus body (TSM's linear z), written per fragment with the slope-scaled bias "
     "done in the shader.", "hyperbolic|linear"};
constexpr ParamDesc kBiasMethod{"bias_method", "bias method", ParamType::Enum, 0, 3, 0, "",
     "offset: constant and slope-scaled offset (eq. 5.2, applied per fragment like glPolygonOffset with "
     "a fixed unit of 2^-24). midpoint: a second layer by depth "
     "peeling and the test against min((z2 - z1) / 2, z_offset) past the first (eq. 5.1, dual shadow "
     "maps). second-depth: the test against the second layer (Wang and Molnar). inverted-back-faces: "
     "back faces stored (cull front) with the offset reversed, towards the light. The two-layer "
     "methods draw every face and ignore the bias and cull parameters.",
     "offset|midpoint|second-depth|inverted-back-faces"};
constexpr ParamDesc kZOffset{"z_offset", "midpoint z_offset", ParamType::Float, 0, 1, 0.05, "depth range",
     "Eq. 5.1's largest bias, in units of the map's depth range: about an object's size. Too small "
     "brings back acne where the second surface is far (a ground plane); too large lets light leak "
     "under casters close to their receivers.", nullptr};

// room for a constant bias alone to remove acne (Fig. 5.6)
#define LISPSM_PARAMS(X)                                 \
    X(int, resolution, kit::resolutionParam())           \
    X(float, n_factor, kNFactor)                         \
    X(float, virtual_far, kVirtualFar)                   \
    X(bool, body_vector, kBodyVector)                    \
    SHADOWLAB_BIAS_PARAMS(X, 65536, 2)                   \
    X(bool, hardware_filter, kit::hardwareFilterParam()) \
    X(bool, snap, kit::snapParam())                      \
    X(int, depth, kDepth)                                \
    X(int, bias_method, kBiasMethod)                     \
    X(float, z_offset, kZOffset)
SHADOWLAB_PARAMS(Params, LISPSM_PARAMS);
using Id = Params::Id;

enum class BiasMethod : int { Offset = 0, Midpoint = 1, SecondDepth = 2, InvertedBackFaces = 3 };

class LightSpacePerspectiveShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!map_.create(host(), error) || !secondLayer_.create(host(), error)) return false;
        uniforms_.create(host(), "lispsm biasing");
        return depthProgram_.build(host(), {.vertexFile = "lispsm_depth.vert", .fragmentFile = "lispsm_depth.frag"}, error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        kit::DepthMapConfig config{.resolution = params.asInt(Id::resolution),
                                   .constantBias = params.asFloat(Id::constant_bias),
                                   .slopeBias = params.asFloat(Id::slope_bias),
                                   .cull = kit::Cull(params.asInt(Id::cull))};
        const auto method = BiasMethod(params.asInt(Id::bias_method));
        const bool linear = params.asInt(Id::depth) == 1;
        twoLayers_ = method == BiasMethod::Midpoint || method == BiasMethod::SecondDepth;
        if (method == BiasMethod::InvertedBackFaces) {
            config.cull = kit::Cull::Front;
            config.constantBias = -config.constantBias;
            config.slopeBias = -config.slopeBias;
        }
        if (twoLayers_) {
            // Both layers of every caster, no offset: the layers' gap is the bias.
            config.cull = kit::Cull::None;
            config.constantBias = config.slopeBias = 0.0f;
        }
        map_.ensureTexture(config.resolution, config.format);
        GpuPass pass(host(), "shadow map");
        // Step 1 of sec. 9.2.1: focus on B (the uniform fallback when there is no warp).
        const kit::FocusedLightSpace focused =
            kit::focusLightSpace(host(), frame, {kit::Fit::FocusBody, params.asBool(Id::snap)}, config.resolution);
        LightSpace lightSpace = focused.light;
        if (frame.light.type == LightType::Directional && !focused.body.empty()) {
            const Bounds scene = host().bounds(DrawSet::All);
            kit::ConvexBody visible = kit::frustumBody(frame.camera.inverseViewProjection);
            kit::clip(visible, scene);
            lispsm::WarpOptions options;
            options.nFactor = params[Id::n_factor];
            // Sec. 9.2.5: n from the body of the virtual frustum (only where it is nearer than the real one).
            const float virtualFar = params.asFloat(Id::virtual_far);
            if (virtualFar > 0.0f && virtualFar < frame.camera.farPlane) {
                options.bodyForN = kit::focusBody(lispsm::virtualViewBody(frame.camera, virtualFar), frame.light,
                                                  scene, focused.light).vertices();
            }
            // Sec. 9.2.6: the axis from the body vector of B's corners.
            if (params.asBool(Id::body_vector))
                options.axisSource = lispsm::bodyVector(focused.body.corners(kit::focus_detail::toleranceFor(focused.body)),
                                                         frame.camera.position);
            const auto warp = lispsm::directionalWarp(focused.body.vertices(), frame.light.direction, frame.camera,
                                                      lispsm::nearestEyeDepth(frame.camera, visible.vertices()),
                                                      options);
            if (warp) {
                // The view stays the light's (the block's light axis reads it); P L is the whole matrix.
                lightSpace.viewProjection = warp->viewProjection;
                lightSpace.projection = warp->viewProjection * glm::inverse(lightSpace.view);
                lightSpace.perspective = true;
            }
        }
        // Linear depth along the map's axis over B (or the scene where B is empty), 0 to 1.
        const glm::vec3 axis = -glm::vec3(lightSpace.view[0][2], lightSpace.view[1][2], lightSpace.view[2][2]);
        std::vector<glm::vec3> extent = focused.body.vertices();
        if (extent.empty()) {
            glm::vec3 corners[8];
            kit::boundsCorners(host().bounds(DrawSet::All), corners);
            extent.assign(corners, corners + 8);
        }
        float lo = INFINITY, hi = -INFINITY;
        for (const glm::vec3& p : extent) {
            lo = std::min(lo, glm::dot(axis, p));
            hi = std::max(hi, glm::dot(axis, p));
        }
        const float range = std::max(hi - lo, 1e-6f);
        shared::lispsm::LispsmUniforms block{};
        block.uLinearDepthPlane = glm::vec4(axis / range, -lo / range);
        block.uLinearDepth = linear ? 1 : 0;
        block.uBiasMethod = twoLayers_ ? int(method) : 0;
        block.uZOffset = params.asFloat(Id::z_offset);
        // The bias is applied in the fragment stage for both depths, never by glPolygonOffset: with
        // depth clamp on, a warped caster's unclamped window z can be far outside [0, 1], and a 32F
        // depth buffer's offset unit is 2^(e - 23) for the primitive's largest exponent e, so on an
        // H200 those casters were pushed behind the receivers (every shadow of the perspective-near
        // and light-behind stress cases lost; llvmpipe's unit stayed 2^-24). Here a unit is 2^-24.
        block.uSlopeFactor = config.slopeBias;
        block.uConstantUnits = config.constantBias;
        config.program = &depthProgram_;
        config.constantBias = config.slopeBias = 0.0f;
        uniforms_.set(block);
        uniforms_.bind();
        // Casters between B and the light's side of the scene are in B; depth clamp keeps any part of
        // a kept caster beyond the warp's depth range in the map rather than clipping it away.
        glEnable(GL_DEPTH_CLAMP);
        map_.drawDepth(lightSpace, config, focused.cullPlanes);
        if (twoLayers_) {
            // The second layer (sec. 5.2, depth peeling): the same pass behind the first layer.
            secondLayer_.ensureTexture(config.resolution, config.format);
            glBindTextureUnit(shared::lispsm::kFirstDepthUnit, map_.texture());
            glBindSampler(shared::lispsm::kFirstDepthUnit, host().sampler(SamplerKind::Nearest));
            block.uPeel = 1;
            uniforms_.set(block);
            secondLayer_.drawDepth(lightSpace, config, focused.cullPlanes);
        }
        glDisable(GL_DEPTH_CLAMP);
        map_.setFocusBody(focused.body);
        map_.reportToHost();
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        map_.bindMainPass(params.asBool(Id::hardware_filter) ? SamplerKind::CompareLinear : SamplerKind::CompareNearest);
        uniforms_.bind();
        // Raw depths of both layers (the first again where there is no second: never read then).
        const GLuint nearest = host().sampler(SamplerKind::Nearest);
        glBindTextureUnit(shared::lispsm::kFirstDepthUnit, map_.texture());
        glBindSampler(shared::lispsm::kFirstDepthUnit, nearest);
        glBindTextureUnit(shared::lispsm::kSecondDepthUnit, twoLayers_ ? secondLayer_.texture() : map_.texture());
        glBindSampler(shared::lispsm::kSecondDepthUnit, nearest);
    }

    kit::DepthMap map_, secondLayer_;
    kit::Program depthProgram_;
    kit::UniformBlock<shared::lispsm::LispsmUniforms> uniforms_;
    bool twoLayers_ = false;
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
                    "affects that uniform fallback (spot and point lights, near-parallel view and light). Debug "
                    "views: footprint (the warp's texels per pixel, near against far), texel-grid and coverage "
                    "(the warped map and its volume), focus-body (B, seed 002 eq. 4.2), and the depth image.",
     .shadowGlsl = "lispsm.glsl",
     .translucencyModel = TranslucencyModel::Ignore},   // its map holds opaque casters only
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(LightSpacePerspectiveShadowMaps, kDescriptor)
