// Area-light reference by accumulated shadow maps (seed 000 sec. 2.2.8: "multiple shadow maps per
// light source, each time rendering from a different sampled point on the surface of the light").
// The host's camera pre-pass gives the world position of every pixel; then for each of N
// light samples one hard shadow map is rendered from that sample and a fullscreen pass adds the
// sample's binary visibility of every pixel to an R32F target (blending by 1/N), so the main pass
// reads the visible fraction of the light. Samples: a Hammersley set ((i + 1/2) / N, radical
// inverse of i) mapped to the disc by eq. 3.11-3.12 (stratified for any N; N = 1 is the light's
// centre, i.e. plain shadow mapping), on the disc of radius light.size for spot and point lights
// and, for directional lights, on the cone of angular radius light.size, uniform in solid angle
// (as the ray-traced reference samples it).
// Known artefacts: N + 1 visibility levels (banding with small N), each sample's hard-shadow
// aliasing and acne (averaged, so softened), the point light's disc faces the scene centre
// rather than each shaded point, and the cost: N shadow passes and N fullscreen passes per frame.
// It is slow by design: the upper bound of what single-map soft techniques approximate.
// The per-sample depth pass is the kit's depth map; the sample disc mapping the kit's jittered
// disc (eq. 3.11-3.12).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/fullscreen_pass.h>
#include <shadowlab/kit/jittered_disk.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "area_reference_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kSamples{"samples", "light samples N", ParamType::Int, 1, 256, 32, "",
     "Shadow maps rendered from points spread over the light, averaged per pixel. 1 is plain shadow mapping "
     "from the light's centre; few samples show N + 1 distinct bands in the penumbra; cost grows linearly "
     "(N shadow passes and N fullscreen passes per frame).", nullptr};
constexpr ParamDesc kResolution = kit::withHelp(kit::resolutionParam(),
     "Width and height of each sample's shadow map. Low values add each map's blocky edges to the penumbra; "
     "high values multiply the cost of every one of the N passes.");

#define AREA_REFERENCE_PARAMS(X)    \
    X(int, samples, kSamples)       \
    X(int, resolution, kResolution) \
    SHADOWLAB_OFFSET_BIAS_PARAMS(X, 64)
SHADOWLAB_PARAMS(Params, AREA_REFERENCE_PARAMS);

// Van der Corput radical inverse in base 2: the second Hammersley coordinate.
float radicalInverse(uint32_t i) {
    i = (i << 16u) | (i >> 16u);
    i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
    i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
    i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
    i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
    return float(i) * 2.3283064365386963e-10f;
}

// Two unit vectors perpendicular to `axis` and to each other.
void perpendicularBasis(glm::vec3 axis, glm::vec3& tangent, glm::vec3& bitangent) {
    const glm::vec3 helper = std::abs(axis.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    tangent = glm::normalize(glm::cross(helper, axis));
    bitangent = glm::cross(axis, tangent);
}

// Light sample i of n: the light moved to one point of its disc (spot, point) or turned to one
// direction of its cone (directional).
LightInfo sampleLight(const LightInfo& light, const Bounds& bounds, int i, int n) {
    const glm::vec2 square{(float(i) + 0.5f) / float(n), radicalInverse(uint32_t(i))};
    const glm::vec2 disc = jittered_disk::squareToDisc(square);   // eq. 3.11-3.12, |disc|^2 = square.y
    LightInfo sample = light;
    glm::vec3 tangent, bitangent;
    if (light.type == LightType::Directional) {
        // Uniform in solid angle over the cap of angular radius size: cos(theta) = 1 - r^2 (1 - cos size)
        // (the disc map is area preserving, and the cap's area is linear in cos(theta)).
        const glm::vec3 towardLight = -glm::normalize(light.direction);
        perpendicularBasis(towardLight, tangent, bitangent);
        const float s = std::sin(0.5f * light.size);
        const float cosTheta = 1.0f - square.y * 2.0f * s * s;   // 1 - cos(size) = 2 sin^2(size / 2)
        const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
        const float r = std::sqrt(square.y);
        const glm::vec2 phi = r > 0.0f ? disc / r : glm::vec2(1.0f, 0.0f);
        if (sinTheta > 0.0f)
            sample.direction = -(cosTheta * towardLight + sinTheta * (phi.x * tangent + phi.y * bitangent));
        return sample;
    }
    const glm::vec3 center = 0.5f * (bounds.min + bounds.max);
    const glm::vec3 axis = light.type == LightType::Spot ? glm::normalize(light.direction)
                                                         : glm::normalize(center - light.position);
    perpendicularBasis(axis, tangent, bitangent);
    sample.position = light.position + light.size * (disc.x * tangent + disc.y * bitangent);
    return sample;
}

class AreaReference final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        return sampleMap_.create(host(), error) &&
               accumulatePass_.create(host(), "area_accumulate.frag", "visibility accumulation", error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const auto* prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        if (!prepass) return;
        ensureAccumulation(prepass->size);
        sampleMap_.ensureTexture(p.resolution);
        accumulateSamples(frame, *prepass, params);
    }

    void bindMainPass(const FrameContext&, const ParamValues&) override {
        glBindTextureUnit(shared::area_reference::kAverageUnit, accumulation_);
    }

    // Screen-sized target, reallocated only when the viewport changes.
    void ensureAccumulation(glm::ivec2 viewport) {
        if (accumulation_ && viewport == viewport_) return;
        viewport_ = viewport;
        accumulation_ = kit::makeTexture(host(), {.internalFormat = GL_R32F, .width = viewport.x, .height = viewport.y,
                                                  .label = "average visibility"});
        glTextureParameteri(accumulation_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(accumulation_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        accumulatePass_.attach(accumulation_);
        host().checkFramebuffer(accumulatePass_.framebuffer(), "visibility accumulation");
        host().registerDebugImage("average visibility", accumulation_, DebugImageKind::Mask);
    }

    // For each light sample: its shadow map, then its visibility of every pixel added (times 1/N).
    void accumulateSamples(const FrameContext& frame, const CameraPrepass& prepass, const ParamValues& params) {
        const Params p = Params::read(params);
        GpuPass pass(host(), "light samples");
        const int samples = p.samples;
        const Bounds bounds = host().bounds(DrawSet::All);
        const kit::DepthMapConfig config{.resolution = sampleMap_.resolution(),
                                         .constantBias = p.constant_bias,
                                         .slopeBias = p.slope_bias};
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(accumulatePass_.framebuffer(), GL_COLOR, 0, zero);
        for (int i = 0; i < samples; ++i) {
            glDisable(GL_BLEND);
            glEnable(GL_DEPTH_TEST);
            sampleMap_.drawDepth(host().fitLightSpace(sampleLight(frame.light, bounds, i, samples), bounds), config);
            glDisable(GL_POLYGON_OFFSET_FILL);

            accumulatePass_.begin();
            glEnable(GL_BLEND);
            glBlendColor(1.0f / float(samples), 0.0f, 0.0f, 0.0f);
            glBlendFunc(GL_CONSTANT_COLOR, GL_ONE);
            glBindTextureUnit(shared::area_reference::kPositionsUnit, prepass.position);
            glBindTextureUnit(shared::area_reference::kSampleMapUnit, sampleMap_.texture());
            glBindSampler(shared::area_reference::kSampleMapUnit, host().sampler(SamplerKind::CompareNearest));
            accumulatePass_.draw(viewport_);
        }
    }

    kit::DepthMap sampleMap_;   // re-rendered for every light sample
    kit::FullscreenPass accumulatePass_;   // area_accumulate.frag, adding each sample's visibility
    kit::Texture accumulation_;
    glm::ivec2 viewport_{0};
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueMapsUnviewed,
    {.id = "area-reference",
     .displayName = "Area light reference (N shadow maps)",
     .category = "reference",
     .explanation = "The brute-force soft shadow: renders N shadow maps from points spread over the light's area (or, for "
                   "the sun, directions within its angular radius) and averages the N hard visibilities in every pixel. "
                   "Physically right up to sampling: penumbrae widen with the distance between caster and receiver and "
                   "overlapping casters combine correctly. Slow by design (N shadow passes per frame): it is the target "
                   "that single-map techniques such as PCSS approximate. Few samples show banding.",
     .shadowGlsl = "area-reference.glsl",
     .flags = kTechniqueNeedsCameraPrepass},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(AreaReference, kDescriptor)
