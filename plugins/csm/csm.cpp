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

constexpr ParamDesc kParams[] = {
    {"resolution", "resolution per cascade", ParamType::Int, 256, 4096, 1024, "texels",
     "Width and height of each cascade's map (a layer of the 2D array; the cube's faces for a point "
     "light). Total texels are cascades x resolution^2: four 1024 cascades hold as many as one 2048 map.",
     nullptr},
    {"cascades", "cascades", ParamType::Int, 1, 8, 4, "",
     "Slices of the view frustum, each with its own map. 1 is one map fitted to the whole view; more "
     "put texels near the viewer where they are needed, at the cost of memory and of drawing casters "
     "into every cascade they reach (one pass, a geometry-stage invocation per cascade).",
     nullptr},
    {"lambda", "split lambda", ParamType::Float, 0, 1, 0.75, "",
     "Practical split scheme (Zhang et al. 2006): C_i = lambda n (f/n)^(i/N) + (1 - lambda) (n + (f - n) i/N). "
     "1 is logarithmic (the ideal distribution of perspective aliasing, seed 002 eq. 8.4, but a "
     "near cascade so thin it is wasted when the near plane is small); 0 uniform (far cascades too "
     "fine, the near one blocky).",
     nullptr},
    {"fit", "fit", ParamType::Enum, 0, 2, 1, "",
     "Depth range the splits divide and what each cascade is fitted around. frustum: the camera's near "
     "to far, each slice's 8 corners (the classic scheme). focus-body: the range where the view meets "
     "the scene's bounds, each slice clipped to them (a far plane beyond the scene wastes nothing). "
     "sdsm: sample distribution shadow maps (Lauritzen 2010): the nearest and farthest depth the "
     "camera actually sees, reduced on the GPU from the camera pre-pass and read back a few frames "
     "late; the tightest, but a fast camera motion briefly leaves pixels beyond the range.",
     "frustum|focus-body|sdsm"},
    {"snap", "stabilise (sphere + snap)", ParamType::Bool, 0, 1, 1, "",
     "Stabilised cascades: each fitted as the square around its slice's bounding sphere (the same size "
     "whatever the camera's direction) moved in whole texels, so shadow edges stand still while the "
     "camera moves (no shimmer). Off: the tight rectangle around each slice, sharper (about half the "
     "texel size) but its texel grid slides and edges crawl and flicker under camera motion.",
     nullptr},
    {"blend_band", "blend band", ParamType::Float, 0, 0.5, 0.1, "of a cascade",
     "Fraction of each cascade's depth range, at its far end, over which it fades into the next one, "
     "hiding the seam where the texel size changes. 0 shows a hard seam; large bands look up two "
     "cascades for more pixels.",
     nullptr},
    {"debug_colours", "cascade colours", ParamType::Bool, 0, 1, 0, "",
     "Tints each pixel by the cascade it reads (red, green, blue, yellow, magenta, cyan, orange, grey): "
     "shows where the splits fall and how the blend band mixes them.",
     nullptr},
    {"kernel", "PCF kernel n", ParamType::Int, 1, 7, 1, "taps",
     "n x n comparisons one texel apart in the cascade's map (percentage-closer filtering): 1 is plain "
     "shadow mapping; the ramp is n texels of that cascade wide, so it narrows in farther cascades.",
     nullptr},
    kit::hardwareFilterParam(),
    kit::constantBiasParam(),
    kit::slopeBiasParam(),
    kit::cullParam(),
};
enum : uint32_t {
    kResolution = kit::paramIndex(kParams, "resolution"),
    kCascades = kit::paramIndex(kParams, "cascades"),
    kLambda = kit::paramIndex(kParams, "lambda"),
    kFit = kit::paramIndex(kParams, "fit"),
    kSnap = kit::paramIndex(kParams, "snap"),
    kBlendBand = kit::paramIndex(kParams, "blend_band"),
    kDebugColours = kit::paramIndex(kParams, "debug_colours"),
    kKernel = kit::paramIndex(kParams, "kernel"),
    kHardwareFilter = kit::paramIndex(kParams, "hardware_filter"),
    kConstantBias = kit::paramIndex(kParams, "constant_bias"),
    kSlopeBias = kit::paramIndex(kParams, "slope_bias"),
    kCull = kit::paramIndex(kParams, "cull"),
};

// The camera pre-pass only feeds sdsm's depth reduction: asked for on those frames alone (it cost
// 4.26 of csm's 5.6 ms on an H200 when the flag held for every fit).
constexpr FlagCondition kFlagConditions[] = {{kTechniqueNeedsCameraPrepass, "fit", "sdsm"}};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "csm",
     .displayName = "Cascaded shadow maps",
     .category = "hard",
     .explanation = "The camera frustum is cut along the view depth into slices, each with its own shadow map "
                    "fitted around it, so texels are dense near the viewer and sparse far away, the way the "
                    "view needs them. The practical split scheme blends logarithmic and uniform splits (lambda). "
                    "Stabilised cascades (snap) hold shadow edges still while the camera moves; without it they "
                    "shimmer. fit = sdsm measures the depth range the camera really sees on the GPU (sample "
                    "distribution shadow maps). Turn on the cascade colours and move the camera. Debug views: coverage (each pixel in its cascade's colour, the cascades' boxes), footprint and texel-grid (per cascade).",
     .shadowGlsl = "csm.glsl",
     .flags = kTechniqueNeedsCameraPrepass,   // fit = sdsm reduces the pre-pass's depth
     .translucencyModel = TranslucencyModel::Ignore,   // its maps hold opaque casters only
     .flagConditions = kFlagConditions,
     .flagConditionCount = 1},
    kParams);

// The depth reduction's results come back through a ring of buffers, each with a timestamp query
// issued after its dispatch: a slot is read only once its query is available (the GPU is past it),
// so glGetNamedBufferSubData never waits. With three slots a result is one to three frames old.
constexpr int kRingSize = 3;

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
        if (!reduceProgram_.build(host(), {.computeFile = "csm_depth_bounds.comp"}, error)) return false;
        framebuffer_ = kit::makeFramebuffer(host(), "cascades");
        uniforms_.create(host(), "csm uniforms");
        for (auto& slot : ring_)
            slot.buffer = kit::Buffer(host(), host().createBuffer(2 * sizeof(uint32_t), nullptr, GL_DYNAMIC_STORAGE_BIT,
                                                                  "csm depth bounds"));
        glCreateQueries(GL_TIMESTAMP, kRingSize, queries_.data());
        return cube_.create(host(), error);
    }

    void shutdown() override { glDeleteQueries(kRingSize, queries_.data()); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const kit::DepthMapConfig depth{.resolution = params.asInt(kResolution),
                                        .constantBias = params.asFloat(kConstantBias),
                                        .slopeBias = params.asFloat(kSlopeBias),
                                        .cull = kit::Cull(params.asInt(kCull))};
        if (frame.light.type == LightType::Point) return cube_.render(frame, depth);

        const int count = std::clamp(params.asInt(kCascades), 1, kit::kMaxCascades);
        const CsmFit fit = CsmFit(std::clamp(params.asInt(kFit), 0, 2));
        const float band = params.asFloat(kBlendBand);
        ensureMaps(depth.resolution, count);

        const Bounds scene = host().bounds(DrawSet::All);
        kit::DepthRange range{frame.camera.nearPlane, frame.camera.farPlane};
        if (fit != CsmFit::Frustum) range = kit::visibleDepthRange(frame.camera, scene);
        if (fit == CsmFit::Sdsm) {
            reduceDepth();
            if (depthBounds_) {
                // A few frames old: 2% of slack either way, and never beyond what the view can reach.
                range.nearDistance = std::clamp(depthBounds_->nearDistance / 1.02f, range.nearDistance, range.farDistance);
                range.farDistance = std::clamp(depthBounds_->farDistance * 1.02f, range.nearDistance * 1.001f, range.farDistance);
            }
        }
        const kit::CascadeRanges ranges = kit::cascadeRanges(range.nearDistance, range.farDistance, count,
                                                             params.asFloat(kLambda), band);
        fitCascades(frame, ranges, {.resolution = depth.resolution, .stabilise = params.asBool(kSnap),
                                    .clipToScene = fit != CsmFit::Frustum});
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
        report(count);
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        const SamplerKind sampling = params.asBool(kHardwareFilter) ? SamplerKind::CompareLinear : SamplerKind::CompareNearest;
        if (frame.light.type == LightType::Point) {
            cube_.bindMainPass(sampling);
            CsmUniforms u{};
            u.uCsmOptions = {std::clamp(params.asInt(kKernel), 1, 7), 0, 0, 0};
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

    void fitCascades(const FrameContext& frame, const kit::CascadeRanges& ranges, const kit::CascadeFitConfig& config) {
        const Bounds scene = host().bounds(DrawSet::All);
        const size_t count = ranges.fitBegin.size();
        cascades_.assign(count, {});
        cullPlanes_.clear();
        if (frame.light.type == LightType::Directional) {
            const glm::mat4 lightView = kit::stableLightView(frame.light);
            const Bounds casters = host().bounds(DrawSet::Casters);
            glm::vec2 lo(1e30f), hi(-1e30f);
            for (size_t i = 0; i < count; ++i) {
                cascades_[i] = kit::fitDirectionalCascade(frame.camera, lightView, ranges.fitBegin[i], ranges.splits[i + 1],
                                                          config, scene, casters);
                // The rectangle in the shared light view, from the orthographic matrix.
                const glm::mat4& p = cascades_[i].light.projection;
                lo = glm::min(lo, glm::vec2((-1.0f - p[3][0]) / p[0][0], (-1.0f - p[3][1]) / p[1][1]));
                hi = glm::max(hi, glm::vec2((1.0f - p[3][0]) / p[0][0], (1.0f - p[3][1]) / p[1][1]));
            }
            // Casters outside every cascade's rectangle reach no map (one set of planes for the
            // single pass; the geometry stage culls per cascade).
            LightSpace all = cascades_[0].light;
            all.projection = glm::ortho(lo.x, hi.x, lo.y, hi.y, all.nearPlane, all.farPlane);
            all.viewProjection = all.projection * all.view;
            const float margin = 1e-4f * std::max(glm::length(scene.max - scene.min), 1.0f);
            cullPlanes_ = kit::mapSidePlanes(all, margin);
        } else {
            const LightSpace sceneFit = host().fitLightSpace(frame.light, DrawSet::All);
            for (size_t i = 0; i < count; ++i)
                cascades_[i] = kit::fitPerspectiveCascade(frame.camera, sceneFit, ranges.fitBegin[i], ranges.splits[i + 1],
                                                          config, scene);
        }
        for (size_t i = 0; i < count; ++i) {
            cascades_[i].viewDistanceBegin = ranges.splits[i];
            cascades_[i].viewDistanceEnd = ranges.splits[i + 1];
        }
    }

    void writeUniforms(const ParamValues& params, int count, const kit::CascadeRanges& ranges) {
        CsmUniforms u{};
        for (int i = 0; i < count; ++i) {
            const kit::Cascade& c = cascades_[size_t(i)];
            u.uCascadeMatrix[i] = c.light.viewProjection;
            u.uCascadeRange[i] = {c.viewDistanceBegin, c.viewDistanceEnd, ranges.fitBegin[size_t(i)], c.texelWorldSize};
        }
        u.uCsmParams = {float(count), params.asFloat(kBlendBand), params.asBool(kDebugColours) ? 1.0f : 0.0f,
                        float(resolution_)};
        u.uCsmOptions = {std::clamp(params.asInt(kKernel), 1, 7), params.asBool(kHardwareFilter) ? 1 : 0, 0, 0};
        uniforms_.set(u);
    }

    // Tells the host which maps a pixel reads: in order, each serving its split range; the first
    // from view depth 0 and the last to any depth, as the shader picks them.
    void report(int count) {
        static const char* kLabels[kit::kMaxCascades] = {"cascade 0", "cascade 1", "cascade 2", "cascade 3",
                                                         "cascade 4", "cascade 5", "cascade 6", "cascade 7"};
        std::array<ShadowMapInfo, kit::kMaxCascades> maps;
        for (int i = 0; i < count; ++i) {
            ShadowMapInfo& m = maps[size_t(i)];
            m.worldToClip = cascades_[size_t(i)].light.viewProjection;
            m.size = glm::ivec2(resolution_);
            m.viewDistanceBegin = i == 0 ? 0.0f : cascades_[size_t(i)].viewDistanceBegin;
            m.viewDistanceEnd = i == count - 1 ? 1e30f : cascades_[size_t(i)].viewDistanceEnd;
            m.layer = uint32_t(i);
            m.label = kLabels[i];
        }
        kit::reportShadowMaps(host(), maps.data(), uint32_t(count));
    }

    // fit = sdsm: first collects the newest result the GPU has finished (never waiting), then
    // reduces this frame's pre-pass into the next slot of the ring.
    void reduceDepth() {
        for (int age = 1; age <= kRingSize; ++age) {   // newest pending first
            Slot& slot = ring_[size_t((next_ + kRingSize - age) % kRingSize)];
            if (!slot.pending) continue;
            const GLuint query = queries_[size_t(&slot - ring_.data())];
            GLuint available = 0;
            glGetQueryObjectuiv(query, GL_QUERY_RESULT_AVAILABLE, &available);
            if (!available) continue;
            uint32_t bits[2] = {0, 0};
            glGetNamedBufferSubData(slot.buffer, 0, sizeof(bits), bits);
            for (Slot& older : ring_)
                if (older.pending && older.serial <= slot.serial) older.pending = false;
            const uint32_t maxBits = ~bits[1];
            float nearest = 0.0f, farthest = 0.0f;
            std::memcpy(&nearest, &bits[0], sizeof(float));
            std::memcpy(&farthest, &maxBits, sizeof(float));
            // Nothing drawn (cleared values) or nonsense: keep the previous bounds.
            if (bits[0] != 0xFFFFFFFFu && std::isfinite(nearest) && std::isfinite(farthest) && farthest >= nearest &&
                nearest > 0.0f)
                depthBounds_ = kit::DepthRange{nearest, farthest};
            break;
        }
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        if (!prepass || !prepass->position) return;
        Slot& slot = ring_[size_t(next_)];
        GpuPass pass(host(), "depth bounds");
        const uint32_t ones = 0xFFFFFFFFu;
        glClearNamedBufferData(slot.buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &ones);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CSM_DEPTH_BOUNDS_BINDING, slot.buffer);
        glBindTextureUnit(shared::csm::kPrepassPositionUnit, prepass->position);
        glBindSampler(shared::csm::kPrepassPositionUnit, host().sampler(SamplerKind::Nearest));
        glUseProgram(reduceProgram_.get());
        glDispatchCompute(GLuint((prepass->size.x + 15) / 16), GLuint((prepass->size.y + 15) / 16), 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glQueryCounter(queries_[size_t(next_)], GL_TIMESTAMP);
        slot.pending = true;
        slot.serial = ++serial_;
        next_ = (next_ + 1) % kRingSize;
    }

    struct Slot {
        kit::Buffer buffer;
        bool pending = false;
        uint64_t serial = 0;
    };

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
    std::array<Slot, kRingSize> ring_;
    std::array<GLuint, kRingSize> queries_{};
    int next_ = 0;
    uint64_t serial_ = 0;
    std::optional<kit::DepthRange> depthBounds_;
};

} // namespace

SHADOWLAB_PLUGIN(CascadedShadowMaps, kDescriptor)
