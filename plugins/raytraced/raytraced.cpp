// Ray-traced shadows on the GPU (issue 27): seed 000 sec. 2.3.2's third family, "a ray is cast in
// a straight line from the point to a light source; if any geometry is encountered along the ray
// the light source is occluded", and seed 001 sec. 6.2's proposed comparison of its coloured
// shadow maps against ray tracing, in speed and quality. OpenGL has no ray-tracing pipeline: the
// host builds a BVH of the casters once per scene (SHADOWLAB_EXT_RAY_TRACING, app/src/render/bvh.h)
// and shaders/ray_trace.glsl walks it in a compute shader, as ray queries do in Vulkan (Sascha
// Willems' `rayquery` sample, Khronos Vulkan-Samples `ray_queries`: shadow rays from the shaded
// point, no hit shaders).
// One invocation per pixel of the host's camera pre-pass (world position and normal) traces
// `rays` shadow rays and writes the visible fraction of the light into a screen-space RGBA16F
// image that shadowTerm() reads at the fragment's pixel:
//   rays = 1: one ray to the light's centre (hard), offset off the surface exactly as the Embree
//     reference does (p + n * 1e-4 scene size), so the two agree pixel for pixel but at ties;
//   rays = N > 1: soft, N jittered stratified rays over the light's disc (spot, point) or cone
//     (directional), the reference's sampling, the jitter reseeded every frame (randomSeed);
//   temporal > 0: each frame blended with the last at the point's reprojected pixel (through
//     previousViewProjection), rejected where that pixel held another surface (view depth).
// Translucent casters filter by the physical model (1 - a) + a t, textured ones per texel; the
// first opaque caster stops a ray (any hit). Surfaces the pre-pass did not see (translucent
// receivers) are traced in the main pass itself (raytraced.glsl).
// Known costs: rays scale with N and pixels, not with shadow map resolution; a BVH build per scene
// load (seconds for millions of triangles); no denoiser beyond the temporal blend.
// counters = on: rays, node visits and triangle tests per pixel (statistics, read back a few
// frames late without waiting) and a per-pixel cost heat map (debug image 'ray cost').
#include <algorithm>
#include <array>
#include <cmath>

#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "raytraced_shared.h"

namespace {

using namespace shadowlab;
using shared::raytraced::RaytracedUniforms;

constexpr ParamDesc kRaysParam = {"rays", "rays per pixel N", ParamType::Int, 1, 256, 1, "",
     "1: one shadow ray to the light's centre, a hard shadow exact up to float ties. N > 1: N jittered "
     "stratified rays over the light's area (its size), a soft shadow whose noise falls as 1/sqrt(N); cost grows "
     "linearly with N.", nullptr};
constexpr ParamDesc kTemporalParam = {"temporal", "temporal weight", ParamType::Float, 0, 0.98, 0, "",
     "Weight of the previous frame's result, reprojected to this frame's pixel (0: off). High weights average many "
     "frames of jitter into a smooth penumbra but lag behind moving shadows (ghosting); rejected where the "
     "reprojected pixel held another surface.", nullptr};
constexpr ParamDesc kPassParam = kit::enumParam("pass", "where rays start", 0, "compute|fragment",
     "compute: a compute pass over the host's camera pre-pass, once per pixel, into a screen image. fragment: the main "
     "pass's shadowTerm() traces itself (a ray query in the fragment stage): no pre-pass, but every shaded fragment "
     "traces, overdraw included (use the host's depth pre-pass). Counters and temporal need compute.");
constexpr ParamDesc kCountersParam = {"counters", "count rays and visits", ParamType::Bool, 0, 1, 0, "",
     "Counts rays, BVH node visits and triangle tests per pixel (statistics and the 'ray cost' heat map). Costs "
     "atomics and a second program variant; off for timing.", nullptr};
#define RAYTRACED_PARAMS(X)          \
    X(int, rays, kRaysParam) \
    X(float, temporal, kTemporalParam) \
    X(int, pass, kPassParam) \
    X(bool, counters, kCountersParam)
SHADOWLAB_PARAMS(Params, RAYTRACED_PARAMS);

// The camera pre-pass only feeds the compute pass.
constexpr FlagCondition kFlagConditions[] = {{kTechniqueNeedsCameraPrepass, "pass", "compute"}};

// Counter read-back ring: slot i is read only once its end timestamp is available (the GPU has
// passed it), so nothing waits; results are one to three frames old.
constexpr int kRing = 3;

class RayTraced final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!host().extension(SHADOWLAB_EXT_RAY_TRACING)) {
            error = "the host has no ray-tracing extension (" SHADOWLAB_EXT_RAY_TRACING ")";
            return false;
        }
        if (!trace_.build(host(), {.computeFile = "raytraced_trace.comp"}, error)) return false;
        if (!traceCounted_.build(host(), {.computeFile = "raytraced_trace.comp", .defines = "RT_WITH_COUNTERS 1"}, error))
            return false;
        uniforms_.create(host(), "raytraced uniforms");
        for (Slot& slot : ring_)
            slot.totals = kit::Buffer(host(), host().createBuffer(8 * sizeof(uint32_t), nullptr, GL_DYNAMIC_STORAGE_BIT,
                                                                   "raytraced counters"));
        glCreateQueries(GL_TIMESTAMP, 2 * kRing, queries_.data());
        return true;
    }

    void shutdown() override { glDeleteQueries(2 * kRing, queries_.data()); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const auto* rt = static_cast<const RayTracing*>(host().extension(SHADOWLAB_EXT_RAY_TRACING));
        const RayTracingScene* scene = rt->scene(rt->context);
        host().reportStatistic("bvh build ms", scene->buildMilliseconds);
        host().reportStatistic("bvh MiB", double(scene->bytes) / (1024.0 * 1024.0));
        host().reportStatistic("bvh depth", scene->depth);
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        const Params values = Params::read(params);
        const bool fragment = values.pass == 1 || !prepass || !prepass->position;
        const bool counters = values.counters && !fragment;
        const float temporal = values.temporal;
        const int rays = values.rays;
        // Results in flight were counted with other settings: dropped. Without counters the
        // counted statistics read NaN, so a table never shows an earlier setting's figures.
        if (!counters || rays != lastRays_)
            for (Slot& slot : ring_) slot.pending = false;
        if (counters) {
            readCounters();
        } else {
            for (const char* name : {"rays per pixel", "node visits per pixel", "triangle tests per pixel", "Mrays per s"})
                host().reportStatistic(name, std::nan(""));
        }
        if (rays != lastRays_ || temporal <= 0.0f) historyValid_ = false;
        lastRays_ = rays;
        RaytracedUniforms u{};
        u.uRtPreviousViewProjection = frame.previousViewProjection;
        u.uRtLightPosition = glm::vec4(frame.light.position, float(frame.light.type));
        u.uRtLightDirection = glm::vec4(frame.light.direction, frame.light.size);
        u.uRtParams = glm::vec4(scene->rayOffset, std::cos(frame.light.spotOuterAngle), temporal, 10.0f * scene->rayOffset);
        u.uRtOptions = glm::uvec4(uint32_t(rays), frame.randomSeed, historyValid_ ? 1u : 0u, fragment ? 1u : 0u);
        uniforms_.set(u);
        if (fragment) return;   // shadowTerm() traces
        resize(prepass->size);

        current_ = 1 - current_;
        GpuPass pass(host(), "trace");
        bindScene(*scene);
        glBindTextureUnit(shared::raytraced::kPrepassPositionUnit, prepass->position);
        glBindTextureUnit(shared::raytraced::kPrepassNormalUnit, prepass->normal);
        glBindTextureUnit(shared::raytraced::kHistoryUnit, visibility_[1 - current_]);
        for (uint32_t unit : {shared::raytraced::kPrepassPositionUnit, shared::raytraced::kPrepassNormalUnit,
                              shared::raytraced::kHistoryUnit})
            glBindSampler(unit, host().sampler(SamplerKind::Nearest));
        glBindImageTexture(shared::raytraced::kVisibilityImage, visibility_[current_], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        Slot& slot = ring_[size_t(next_)];
        if (counters) {
            glClearNamedBufferData(slot.totals, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RT_COUNTER_BINDING, slot.totals);
            glBindImageTexture(shared::raytraced::kHeatImage, heat_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glQueryCounter(queries_[size_t(2 * next_)], GL_TIMESTAMP);
        }
        glUseProgram(counters ? traceCounted_.get() : trace_.get());
        glDispatchCompute(GLuint((size_.x + 7) / 8), GLuint((size_.y + 7) / 8), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        if (counters) {
            glQueryCounter(queries_[size_t(2 * next_ + 1)], GL_TIMESTAMP);
            slot.pending = true;
            slot.serial = ++serial_;
            next_ = (next_ + 1) % kRing;
        }
        historyValid_ = temporal > 0.0f;
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        (void)frame;
        (void)params;
        const auto* rt = static_cast<const RayTracing*>(host().extension(SHADOWLAB_EXT_RAY_TRACING));
        bindScene(*rt->scene(rt->context));
        uniforms_.bind();
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        glBindTextureUnit(shared::raytraced::kVisibilityUnit, visibility_[current_]);
        glBindTextureUnit(shared::raytraced::kPrepassPositionUnit, prepass ? prepass->position : 0u);
        for (uint32_t unit : {shared::raytraced::kVisibilityUnit, shared::raytraced::kPrepassPositionUnit})
            glBindSampler(unit, host().sampler(SamplerKind::Nearest));
    }

    // ray_trace.glsl's default storage bindings 3-7.
    static void bindScene(const RayTracingScene& scene) {
        const uint32_t buffers[] = {scene.nodes, scene.triangles, scene.uvs, scene.materials, scene.texels};
        for (uint32_t i = 0; i < 5; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3 + i, buffers[i]);
    }

    // Images at the viewport's size, made again only when it changes.
    void resize(glm::ivec2 size) {
        if (size == size_ && visibility_[0]) return;
        size_ = size;
        for (kit::Texture& texture : visibility_)
            texture = kit::makeTexture(host(), {.internalFormat = GL_RGBA16F, .width = size.x, .height = size.y,
                                                .label = "ray-traced visibility"});
        heat_ = kit::makeTexture(host(), {.internalFormat = GL_RGBA8, .width = size.x, .height = size.y, .label = "ray cost"});
        host().registerDebugImage("ray cost", heat_, DebugImageKind::Color);
        historyValid_ = false;
    }

    // The newest finished slot's totals as statistics (never waiting on the GPU).
    void readCounters() {
        for (int age = 1; age <= kRing; ++age) {
            Slot& slot = ring_[size_t((next_ + kRing - age) % kRing)];
            if (!slot.pending) continue;
            const size_t index = size_t(&slot - ring_.data());
            GLuint available = 0;
            glGetQueryObjectuiv(queries_[2 * index + 1], GL_QUERY_RESULT_AVAILABLE, &available);
            if (!available) continue;
            uint32_t words[8] = {};
            glGetNamedBufferSubData(slot.totals, 0, sizeof(words), words);
            GLuint64 begin = 0, end = 0;
            glGetQueryObjectui64v(queries_[2 * index], GL_QUERY_RESULT, &begin);
            glGetQueryObjectui64v(queries_[2 * index + 1], GL_QUERY_RESULT, &end);
            for (Slot& older : ring_)
                if (older.pending && older.serial <= slot.serial) older.pending = false;
            auto total = [&](int i) { return double(uint64_t(words[2 * i + 1]) << 32 | words[2 * i]); };
            const double pixels = std::max(1.0, total(3));
            host().reportStatistic("rays per pixel", total(0) / pixels);
            host().reportStatistic("node visits per pixel", total(1) / pixels);
            host().reportStatistic("triangle tests per pixel", total(2) / pixels);
            if (end > begin) host().reportStatistic("Mrays per s", total(0) / (double(end - begin) * 1e-9) * 1e-6);
            break;
        }
    }

    struct Slot {
        kit::Buffer totals;
        bool pending = false;
        uint64_t serial = 0;
    };

    kit::Program trace_, traceCounted_;
    kit::UniformBlock<RaytracedUniforms> uniforms_;
    std::array<kit::Texture, 2> visibility_;   // this frame's and the last one's (temporal history)
    kit::Texture heat_;
    glm::ivec2 size_{0};
    int current_ = 0;
    int lastRays_ = 0;
    bool historyValid_ = false;
    std::array<Slot, kRing> ring_;
    std::array<GLuint, 2 * kRing> queries_{};
    int next_ = 0;
    uint64_t serial_ = 0;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kTracedRays,   // no map for the host's views; its own image is 'ray cost'
    {.id = "raytraced",
     .displayName = "Ray-traced shadows (GPU)",
     .category = "soft",
     .explanation = "Casts shadow rays from every visible point towards the light through a BVH of the scene's triangles, "
                    "traversed in a compute shader. One ray per pixel gives an exact hard shadow (no acne, no aliasing, no "
                    "bias to tune); N rays over the light's area give a physically right soft shadow with noise that "
                    "falls as N grows; translucent casters colour the light they pass. Cost scales with pixels and rays, "
                    "not with a map's resolution. Debug view: 'ray cost' (counters on) shows BVH work per pixel.",
     .shadowGlsl = "raytraced.glsl",
     .flags = kTechniqueNeedsCameraPrepass},
    Params::table, kFlagConditions);

} // namespace

SHADOWLAB_PLUGIN(RayTraced, kDescriptor)
