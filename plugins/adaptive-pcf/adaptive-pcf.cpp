// Adaptive percentage-closer filtering with jittered disc samples (Uralsky, "Efficient Soft-Edged
// Shadows Using Pixel Shader Branching", GPU Gems 2 ch. 17; seed 000 sections 2.2.7, 3.2.4 and
// 4.3.2). The n x n samples of a jittered grid are mapped to a disc (eq. 3.11-3.12) and ordered
// outermost first; m x m such sets, one per pixel modulo m, live in an m x m x n^2/2 RGBA16_SNORM 3D
// texture. The main pass tests the outer ring first and stops when it agrees (fully lit or fully
// shadowed), so only penumbra pixels pay for all n^2 taps; the per-pixel sets turn PCF's banding
// into fine noise. The share of pixels that stopped early is counted with atomic counters and
// reported a few frames late ("early-out rate") without stalling.
// Known artefacts: noise in the penumbra (m too small shows a repeating pattern, seed 000
// Fig. 4.10), lit gaps narrower than the disc classified as shadowed by the early out, the same
// penumbra width everywhere (no light size), acne under wide discs without the cone bias, and
// bad bias also costs speed (acne pixels look like penumbra and take the full kernel).
// The shadow map is the kit's depth map, the disc sets the kit's (jittered_disk.h,
// disc_offset_texture.h; GLSL in shaders/disc_sampling.glsl), shared with pcss.
// Point lights: the kit's cube map (kit/cube_depth_map.h), the same disc laid across the ray from
// the light with the radius as an angle (radius texels of a face at its centre; adaptive-pcf.glsl).
#include <array>

#include <shadowlab/kit/disc_offset_texture.h>
#include <shadowlab/kit/filtered_depth_maps.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "adaptive_pcf_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kGrid{"grid", "samples n", ParamType::Int, 2, 16, 8, "",
     "Each set is an n x n jittered grid mapped to a disc (n^2 taps in the penumbra, n in the outer "
     "ring tested first). Small n gives coarse, noisy penumbrae and an unreliable early out; large n is "
     "smooth but penumbra pixels cost n^2 lookups and the offset texture grows with n^2.", nullptr};
constexpr ParamDesc kRadius{"radius", "offset scale (radius)", ParamType::Float, 0.5, 32, 4, "texels",
     "Filter radius: the unit-disc offsets are scaled by it. Small radii leave hard, aliased edges; large "
     "ones give wide penumbrae, more noise, more bias needed and fewer early outs (slower).", nullptr};
constexpr ParamDesc kCoherent{"coherent", "early out per 2x2 quad", ParamType::Bool, 0, 1, 1, "",
     "Take the early-out decision per 2x2 pixel quad: the quad stops only when all four rings agree. A GPU "
     "shades quads (and warps) together, so a pixel that stops alone next to one that continues should save "
     "nothing; measured on an H200 it made no difference in speed and lowered the penumbra error slightly. "
     "Off gives seed 000's per-pixel decision.", nullptr};
constexpr ParamDesc kClassify = kit::enumParam("classify", "decide lit and shadowed by", 0, "ring|depth-range",
     "How a pixel outside any penumbra is recognised. ring: seed 000's test, the outer ring of taps all "
     "agreeing. depth-range: first the nearest and farthest depth stored under the whole disc (depth-range "
     "mips, one extra pass, four fetches): nearest at or behind the receiver means every tap is lit, "
     "farthest in front of it every tap shadowed, and the ring is not read; the other pixels take the ring "
     "test. Exactly the same image as ring (a pixel the bounds decide has a unanimous ring), fewer lookups "
     "where most of the view is plainly lit or shadowed; on forest (an H200, with the depth pre-pass) it was "
     "9% slower than ring, whose default it is not.");
constexpr ParamDesc kCountEarlyOuts{"count_early_outs", "count early outs", ParamType::Bool, 0, 1, 0, "",
     "Count the calls and early outs with two atomic counters and report the early-out rate (statistics). "
     "Every fragment increments the same counters, which costs GPU time: leave it off when timing.",
     nullptr};

#define ADAPTIVE_PCF_PARAMS(X)                         \
    X(int, resolution, kit::resolutionParam())         \
    X(int, grid, kGrid)                                \
    X(int, sets, kit::discSetsParam())                 \
    X(float, radius, kRadius)                          \
    X(bool, hardware_filter, kit::bilinearTapsParam()) \
    X(bool, coherent, kCoherent)                       \
    X(int, classify, kClassify)                        \
    X(bool, count_early_outs, kCountEarlyOuts)         \
    SHADOWLAB_PCF_COMMON_PARAMS(X)
SHADOWLAB_PARAMS(Params, ADAPTIVE_PCF_PARAMS);

// Counts of the main pass (shadowTerm calls, early outs) in a ring of small atomic-counter buffers,
// read back only once a fence says the frame that wrote them has finished: never a stall. Both
// count fragments (overdraw included, helper invocations not); points outside the map count as
// calls but not as early outs. "early-out rate" = early outs / calls.
// Atomic counter binding kCounterBinding (adaptive_pcf_shared.h; the host uses none).
// Cost: two atomics per fragment, about 10% of adaptive-pcf's main pass on llvmpipe.
class EarlyOutCounters {
public:
    void init(IHost& host) {
        host_ = &host;
        const GLuint zero[2] = {0, 0};
        for (kit::Buffer& buffer : buffers_)
            buffer = kit::Buffer(host, host.createBuffer(sizeof(zero), zero, GL_DYNAMIC_STORAGE_BIT, "early-out counters"));
    }

    // Start of a frame: fence the previous frame's counters, collect finished ones, and clear the
    // slot this frame's main pass will count into.
    void beginFrame() {
        if (pending_ >= 0) {
            // Makes the shader's atomic writes visible to glGetBufferSubData / glClearBufferSubData.
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
            fences_[size_t(pending_)] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
            pending_ = -1;
        }
        for (int k = 1; k <= kRing; ++k) collect((frame_ + k) % kRing);   // oldest first
        current_ = frame_ % kRing;
        if (fences_[size_t(current_)]) {   // still in flight after kRing frames: drop it
            glDeleteSync(fences_[size_t(current_)]);
            fences_[size_t(current_)] = nullptr;
        }
        const GLuint zero = 0;
        glClearNamedBufferSubData(buffers_[size_t(current_)], GL_R32UI, 0, 2 * sizeof(GLuint), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &zero);
        ++frame_;
    }

    void bindMainPass() {
        glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, shared::adaptive_pcf::kCounterBinding, buffers_[size_t(current_)]);
        pending_ = current_;
    }

    ~EarlyOutCounters() {
        for (GLsync& fence : fences_)
            if (fence) glDeleteSync(fence);
    }

private:
    static constexpr int kRing = 4;

    void collect(int slot) {
        GLsync& fence = fences_[size_t(slot)];
        if (!fence) return;
        const GLenum status = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);   // poll, no wait
        if (status != GL_ALREADY_SIGNALED && status != GL_CONDITION_SATISFIED) return;
        glDeleteSync(fence);
        fence = nullptr;
        GLuint counts[2] = {0, 0};
        glGetNamedBufferSubData(buffers_[size_t(slot)], 0, sizeof(counts), counts);
        if (counts[0] == 0) return;
        host_->reportStatistic("early-out rate", double(counts[1]) / double(counts[0]));
        host_->reportStatistic("shaded fragments", double(counts[0]));
    }

    IHost* host_ = nullptr;
    std::array<kit::Buffer, kRing> buffers_{};
    std::array<GLsync, kRing> fences_{};
    int frame_ = 0;
    int current_ = 0;
    int pending_ = -1;
};

class AdaptivePcf final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        counters_.init(host());
        uniforms_.create(host(), "adaptive-pcf uniforms");
        return maps_.create(host(), error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        offsets_.ensure(host(), p.grid, p.sets, "disc offsets (m x m x n^2/2)");
        counters_.beginFrame();
        if (!maps_.render(frame, kit::depthMapConfig(p), kit::layeredDepthConfig(p))) return;   // the cube: no kernel report, no mips
        // The disc adaptive-pcf.glsl filters over (seed 000 eq. 3.11-3.12), for the host's kernel view.
        maps_.map().reportFilter({.kernel = FilterKernel::Disc,
                                  .taps = offsets_.n(),
                                  .spacing = p.radius,
                                  .bilinear = p.hardware_filter ? 1u : 0u,
                                  .sets = p.sets,
                                  .discSeed = 1,   // offsets_.ensure's default
                                  .coneBias = p.cone_bias ? 1.0f : 0.0f,
                                  .coherent = p.coherent ? 1u : 0u});
        // classify = depth-range reads mips of the 2D map (the cube path takes the ring test).
        maps_.updateDepthRange(p.classify == 1);
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const SamplerKind sampling = p.hardware_filter ? SamplerKind::CompareLinear : SamplerKind::CompareNearest;
        maps_.bindMainPass(frame, sampling, sampling);
        glBindTextureUnit(shared::adaptive_pcf::kDiscOffsetsUnit, offsets_.texture());
        uniforms_.set({{}, offsets_.n(), p.radius, p.cone_bias ? 1.0f : 0.0f,
                       p.coherent ? 1 : 0, p.count_early_outs ? 1 : 0,
                       frame.light.type == LightType::Point ? 0 : p.classify, 0, 0});
        counters_.bindMainPass();
    }

    kit::FilteredDepthMaps maps_;
    jittered_disk::DiscOffsetTexture offsets_;
    EarlyOutCounters counters_;
    kit::UniformBlock<shared::adaptive_pcf::AdaptivePcfUniforms> uniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFilteredMap,
    {.id = "adaptive-pcf",
     .displayName = "Adaptive PCF (jittered disc)",
     .category = "filtered",
     .explanation = "PCF with n x n jittered samples spread over a disc, a different set in each pixel of an m x m tile, "
                   "so the penumbra becomes fine noise instead of bands. The outermost samples come first: when they "
                   "all agree the pixel is fully lit or fully shadowed and the rest is skipped, so only penumbra pixels "
                   "pay for the whole kernel (count early outs to see the rate). The radius sets the penumbra width, the same "
                   "everywhere: filtering, not a physically soft shadow.",
     .shadowGlsl = "adaptive-pcf.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(AdaptivePcf, kDescriptor)
