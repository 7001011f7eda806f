// Cascaded shadow maps (parallel-split shadow maps: Zhang, Sun, Xu and Lo 2006; GPU Gems 3 ch. 10;
// Engel 2006; seed 002 sec. 7.1, "a partitioning of the view frustum into subsets"). The camera
// frustum is cut along the view depth into 1-8 slices by the practical split scheme (a lambda
// blend of logarithmic and uniform splits, kit/cascades.h: seed 002 eq. 8.4 is why logarithmic is
// ideal), each slice gets its own orthographic map fitted around it, all cascades are drawn in one
// pass by a geometry stage writing gl_Layer into a 2D array (csm_cascades.geom), and the main
// pass picks a point's cascade by its view depth, blending into the next over a band.
// Options: `fit` frustum (the camera's near and far), focus-body (the slices clipped to the scene's
// bounds: tighter in a scene smaller than the far plane) or sdsm (sample distribution shadow maps,
// Lauritzen 2010: near and far from a compute reduction of the camera pre-pass's depth, read back
// a few frames late without stalling); `snap` stabilises the cascades (bounding sphere, texel
// snapping: edges stand still while the camera moves, for about twice the texels per area).
// Known artefacts: a visible change of sharpness at cascade boundaries (the blend band hides the
// seam), shimmering edges without `snap`, and with sdsm a range a few frames old: while the camera
// moves fast, pixels beyond last frames' farthest depth fall to the last cascade's edge.
// Spot lights: each cascade is a crop of the host's perspective fit to its slice (seed 000 eq.
// 3.9-3.10); point lights: the kit's cube map (kit/cube_depth_map.h).
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <optional>
#include <vector>

#include <shadowlab/kit/cascade_maps.h>
#include <shadowlab/kit/cascades.h>
#include <shadowlab/kit/cube_depth_map.h>
#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/shadow_map_report.h>
#include <shadowlab/kit/technique_base.h>

#include "shadowlab/kit/csm_shared.h"

namespace {

using namespace shadowlab;

enum class CsmFit : int { Frustum = 0, FocusBody = 1, Sdsm = 2 };

constexpr ParamDesc kResolution{"resolution", "resolution per cascade", ParamType::Int, 256, 4096, 1024, "texels",
     "Width and height of each cascade's map (a layer of the 2D array; the cube's faces for a point "
     "light). Total texels are cascades x resolution^2: four 1024 cascades hold as many as one 2048 map.",
     nullptr};
constexpr ParamDesc kCascades{"cascades", "cascades", ParamType::Int, 1, 8, 4, "",
     "Slices of the view frustum, each with its own map. 1 is one map fitted to the whole view; more "
     "put texels near the viewer where they are needed, at the cost of memory and of drawing casters "
     "into every cascade they reach (one pass, a geometry-stage invocation per cascade).",
     nullptr};
constexpr ParamDesc kLambda{"lambda", "split lambda", ParamType::Float, 0, 1, 0.75, "",
     "Practical split scheme (Zhang et al. 2006): C_i = lambda n (f/n)^(i/N) + (1 - lambda) (n + (f - n) i/N). "
     "1 is logarithmic (the ideal distribution of perspective aliasing, seed 002 eq. 8.4, but a "
     "near cascade so thin it is wasted when the near plane is small); 0 uniform (far cascades too "
     "fine, the near one blocky).",
     nullptr};
constexpr ParamDesc kFit = kit::enumParam("fit", "fit", 1, "frustum|focus-body|sdsm",
     "Depth range the splits divide and what each cascade is fitted around. frustum: the camera's near "
     "to far, each slice's 8 corners (the classic scheme). focus-body: the range where the view meets "
     "the scene's bounds, each slice clipped to them (a far plane beyond the scene wastes nothing). "
     "sdsm: sample distribution shadow maps (Lauritzen 2010): the nearest and farthest depth the "
     "camera actually sees, reduced on the GPU from the camera pre-pass and read back a few frames "
     "late; the tightest, but a fast camera motion briefly leaves pixels beyond the range.");
constexpr ParamDesc kSnap{"snap", "stabilise (sphere + snap)", ParamType::Bool, 0, 1, 1, "",
     "Stabilised cascades: each fitted as the square around its slice's bounding sphere (the same size "
     "whatever the camera's direction) moved in whole texels, so shadow edges stand still while the "
     "camera moves (no shimmer). Off: the tight rectangle around each slice, sharper (about half the "
     "texel size) but its texel grid slides and edges crawl and flicker under camera motion.",
     nullptr};
constexpr ParamDesc kBlendBand{"blend_band", "blend band", ParamType::Float, 0, 0.5, 0.1, "of a cascade",
     "Fraction of each cascade's depth range, at its far end, over which it fades into the next one, "
     "hiding the seam where the texel size changes. 0 shows a hard seam; large bands look up two "
     "cascades for more pixels.",
     nullptr};
constexpr ParamDesc kDebugColours{"debug_colours", "cascade colours", ParamType::Bool, 0, 1, 0, "",
     "Tints each pixel by the cascade it reads (red, green, blue, yellow, magenta, cyan, orange, grey): "
     "shows where the splits fall and how the blend band mixes them.",
     nullptr};
constexpr ParamDesc kKernel{"kernel", "PCF kernel n", ParamType::Int, 1, 7, 1, "taps",
     "n x n comparisons one texel apart in the cascade's map (percentage-closer filtering): 1 is plain "
     "shadow mapping; the ramp is n texels of that cascade wide, so it narrows in farther cascades.",
     nullptr};

#define CSM_PARAMS(X)                                    \
    X(int, resolution, kResolution)                      \
    X(int, cascades, kCascades)                          \
    X(float, lambda, kLambda)                            \
    X(int, fit, kFit)                                    \
    X(bool, snap, kSnap)                                 \
    X(float, blend_band, kBlendBand)                     \
    X(bool, debug_colours, kDebugColours)                \
    X(int, kernel, kKernel)                              \
    X(bool, hardware_filter, kit::hardwareFilterParam()) \
    SHADOWLAB_BIAS_PARAMS(X, 64, 1)
SHADOWLAB_PARAMS(Params, CSM_PARAMS);
using Id = Params::Id;

// The camera pre-pass only feeds sdsm's depth reduction: asked for on those frames alone (it cost
// 4.26 of csm's 5.6 ms on an H200 when the flag held for every fit).
constexpr FlagCondition kFlagConditions[] = {{kTechniqueNeedsCameraDepth, "fit", "sdsm"}};

class CascadedShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        // One program per cascade count: the geometry stage runs `invocations` instances per
        // triangle, a compile-time constant, and unused instances still cost (on an H200 one
        // cascade through the 8-instance stage took 2.0x shadowmap's pass for the same map).
        for (int count = 1; count <= kit::kMaxCascades; ++count) {
            const std::string defines = "CSM_CASCADES " + std::to_string(count);
            if (!depthPrograms_[size_t(count - 1)].build(
                    host(), {.vertexFile = "world_position.vert", .geometryFile = "csm_cascades.geom", .defines = defines.c_str()},
                    error))
                return false;
        }
        if (!reduceProgram_.build(host(), {.computeFile = "view_depth_bounds.comp"}, error)) return false;
        framebuffer_ = kit::makeFramebuffer(host(), "cascades");
        uniforms_.create(host(), "csm uniforms");
        depthBounds_.create(host());
        return cube_.create(host(), error);
    }

    void shutdown() override { depthBounds_.destroy(); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const kit::DepthMapConfig depth{.resolution = p.resolution,
                                        .constantBias = p.constant_bias,
                                        .slopeBias = p.slope_bias,
                                        .cull = kit::Cull(p.cull)};
        if (frame.light.type == LightType::Point) return cube_.render(frame, depth);

        const int count = std::clamp(p.cascades, 1, kit::kMaxCascades);
        const CsmFit fit = CsmFit(std::clamp(p.fit, 0, 2));
        const float band = p.blend_band;
        ensureMaps(depth.resolution, count);

        const Bounds scene = host().bounds(DrawSet::All);
        kit::DepthRange range{frame.camera.nearPlane, frame.camera.farPlane};
        if (fit != CsmFit::Frustum) range = kit::visibleDepthRange(frame.camera, scene);
        if (fit == CsmFit::Sdsm) {
            depthBounds_.reduce(reduceProgram_);
            range = kit::narrowToMeasured(range, depthBounds_.latest());
        }
        const kit::CascadeRanges ranges = kit::cascadeRanges(range.nearDistance, range.farDistance, count,
                                                             p.lambda, band);
        kit::fitCascades(host(), frame, ranges,
                         {.resolution = depth.resolution, .stabilise = p.snap, .clipToScene = fit != CsmFit::Frustum},
                         cascades_, cullPlanes_);
        writeUniforms(params, count, ranges);

        GpuPass pass(host(), "shadow map");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, resolution_, resolution_);
        glClear(GL_DEPTH_BUFFER_BIT);
        kit::applyCull(depth.cull);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(depth.slopeBias, depth.constantBias);
        glEnable(GL_DEPTH_CLAMP);
        DrawRequest request;
        request.set = DrawSet::OpaqueCasters;
        request.cullPlanes = cullPlanes_.data();
        request.cullPlaneCount = uint32_t(cullPlanes_.size());
        host().drawScene(request, depthPrograms_[size_t(count - 1)].use());
        kit::reportCascades(host(), cascades_, count, resolution_);
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const SamplerKind sampling = p.hardware_filter ? SamplerKind::CompareLinear : SamplerKind::CompareNearest;
        if (frame.light.type == LightType::Point) {
            cube_.bindMainPass(sampling);
            CsmUniforms u{};
            u.uCsmOptions = {std::clamp(p.kernel, 1, 7), 0, 0, 0};
            uniforms_.set(u);
            return;
        }
        glBindTextureUnit(kCascadeMapsUnit, maps_);
        glBindSampler(kCascadeMapsUnit, host().sampler(sampling));
        uniforms_.bind();
    }

    using CsmUniforms = shared::csm::CsmUniforms;
    static constexpr uint32_t kCascadeMapsUnit = shared::csm::kCascadeMapsUnit;

    // The array of cascades (every layer counted by the host), reallocated only when resolution or
    // cascade count change.
    void ensureMaps(int resolution, int count) {
        if (maps_ && resolution == resolution_ && count == layers_) return;
        resolution_ = resolution;
        layers_ = count;
        maps_ = kit::makeTexture(host(), {.target = GL_TEXTURE_2D_ARRAY, .internalFormat = GL_DEPTH_COMPONENT32F,
                                          .width = resolution, .height = resolution, .depth = count,
                                          .label = "cascades"});
        kit::attachDepthTarget(host(), framebuffer_, maps_, "cascades");   // layered: gl_Layer picks the cascade
    }

    void writeUniforms(const ParamValues& params, int count, const kit::CascadeRanges& ranges) {
        CsmUniforms u{};
        for (int i = 0; i < count; ++i) {
            const kit::Cascade& c = cascades_[size_t(i)];
            u.uCascadeMatrix[i] = c.light.viewProjection;
            u.uCascadeRange[i] = {c.viewDistanceBegin, c.viewDistanceEnd, ranges.fitBegin[size_t(i)], c.texelWorldSize};
        }
        u.uCsmParams = {float(count), params.asFloat(Id::blend_band), params.asBool(Id::debug_colours) ? 1.0f : 0.0f,
                        float(resolution_)};
        u.uCsmOptions = {std::clamp(params.asInt(Id::kernel), 1, 7), params.asBool(Id::hardware_filter) ? 1 : 0, 0, 0};
        uniforms_.set(u);
    }

    std::array<kit::Program, kit::kMaxCascades> depthPrograms_;   // [n - 1]: the geometry stage for n cascades
    kit::Program reduceProgram_;
    kit::Framebuffer framebuffer_;
    kit::Texture maps_;
    kit::UniformBlock<CsmUniforms> uniforms_;
    kit::CubeDepthMap cube_;
    int resolution_ = 0;
    int layers_ = 0;
    std::vector<kit::Cascade> cascades_;
    std::vector<glm::vec4> cullPlanes_;
    kit::ViewDepthBounds depthBounds_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueMap,
    {.id = "csm",
     .displayName = "Cascaded shadow maps",
     .category = "hard",
     .explanation = "The camera frustum is cut along the view depth into slices, each with its own shadow map "
                    "fitted around it, so texels are dense near the viewer and sparse far away, the way the "
                    "view needs them. The practical split scheme blends logarithmic and uniform splits (lambda). "
                    "Stabilised cascades (snap) hold shadow edges still while the camera moves; without it they "
                    "shimmer. fit = sdsm measures the depth range the camera really sees on the GPU (sample "
                    "distribution shadow maps). Turn on the cascade colours and move the camera.",
     .shadowGlsl = "csm.glsl"},
    Params::table, kFlagConditions);

} // namespace

SHADOWLAB_PLUGIN(CascadedShadowMaps, kDescriptor)
