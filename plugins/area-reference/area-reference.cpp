// Area-light reference by accumulated shadow maps (seed 000 sec. 2.2.8: "multiple shadow maps per
// light source, each time rendering from a different sampled point on the surface of the light").
// A pre-pass stores the world position of every pixel of the host camera; then for each of N
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
// The per-sample depth pass is pcf's (../pcf/kernel_shadow_map.h); the sample disc mapping is
// adaptive-pcf's (../adaptive-pcf/jittered_disk.h).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "../adaptive-pcf/jittered_disk.h"
#include "../pcf/kernel_shadow_map.h"

namespace {

using namespace shadowlab;

enum Param : uint32_t { kSamples, kResolution, kConstantBias, kSlopeBias, kParamCount };

const ParamDesc kParams[] = {
    {"samples", "light samples N", ParamType::Int, 1, 256, 32, "",
     "Shadow maps rendered from points spread over the light, averaged per pixel. 1 is plain shadow mapping "
     "from the light's centre; few samples show N + 1 distinct bands in the penumbra; cost grows linearly "
     "(N shadow passes and N fullscreen passes per frame).", nullptr},
    {"resolution", "resolution", ParamType::Int, 256, 8192, 2048, "texels",
     "Width and height of each sample's shadow map. Low values add each map's blocky edges to the penumbra; "
     "high values multiply the cost of every one of the N passes.", nullptr},
    kernel_filtering::kConstantBiasParam,
    kernel_filtering::kSlopeBiasParam,
};

const TechniqueDesc kDescriptor{
    "area-reference",
    "Area light reference (N shadow maps)",
    "reference",
    "The brute-force soft shadow: renders N shadow maps from points spread over the light's area (or, for "
    "the sun, directions within its angular radius) and averages the N hard visibilities in every pixel. "
    "Physically right up to sampling: penumbrae widen with the distance between caster and receiver and "
    "overlapping casters combine correctly. Slow by design (N shadow passes per frame): it is the target "
    "that single-map techniques such as PCSS approximate. Few samples show banding.",
    "area-reference.glsl",
    kParams,
    kParamCount,
};

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

class AreaReference final : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) override {
        host_ = &host;
        if (!gladLoadGL(host.glLoader())) {
            error = "could not load OpenGL entry points";
            return false;
        }
        if (!sampleMap_.init(host, true, error)) return false;
        positionProgram_ = host.buildProgram({"main.vert", "area_position.frag", nullptr}, error);
        if (!positionProgram_) return false;
        accumulateProgram_ = host.buildProgram({"fullscreen.vert", "area_accumulate.frag", nullptr}, error);
        if (!accumulateProgram_) return false;
        positionFbo_ = host.createFramebuffer("position pre-pass");
        accumulationFbo_ = host.createFramebuffer("visibility accumulation");
        return true;
    }

    void renderShadows(const ParamValues& params) override {
        ensureScreenTargets(host_->camera().viewport);
        sampleMap_.ensureTexture(params.asInt(kResolution));
        positionPrePass();
        accumulateSamples(params);
    }

    void bindMainPass(uint32_t program, const ParamValues& params) override {
        (void)program;
        (void)params;
        glBindTextureUnit(4, accumulation_);
    }

    void shutdown() override {
        sampleMap_.shutdown();
        for (GLuint* texture : {&positions_, &depth_, &accumulation_}) {
            if (*texture) host_->destroyTexture(*texture);
            *texture = 0;
        }
        for (GLuint* framebuffer : {&positionFbo_, &accumulationFbo_}) {
            if (*framebuffer) host_->destroyFramebuffer(*framebuffer);
            *framebuffer = 0;
        }
        viewport_ = glm::ivec2(0);
    }

private:
    // Screen-sized targets, reallocated only when the viewport changes.
    void ensureScreenTargets(glm::ivec2 viewport) {
        if (positions_ && viewport == viewport_) return;
        for (GLuint* texture : {&positions_, &depth_, &accumulation_})
            if (*texture) host_->destroyTexture(*texture);
        viewport_ = viewport;
        positions_ = host_->createTexture({GL_TEXTURE_2D, GL_RGBA32F, viewport.x, viewport.y, 1, 1, "world positions"});
        depth_ = host_->createTexture({GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, viewport.x, viewport.y, 1, 1, "pre-pass depth"});
        accumulation_ = host_->createTexture({GL_TEXTURE_2D, GL_R32F, viewport.x, viewport.y, 1, 1, "average visibility"});
        for (GLuint texture : {positions_, accumulation_}) {
            glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        glNamedFramebufferTexture(positionFbo_, GL_COLOR_ATTACHMENT0, positions_, 0);
        glNamedFramebufferTexture(positionFbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
        glNamedFramebufferDrawBuffer(positionFbo_, GL_COLOR_ATTACHMENT0);
        host_->checkFramebuffer(positionFbo_, "position pre-pass");
        glNamedFramebufferTexture(accumulationFbo_, GL_COLOR_ATTACHMENT0, accumulation_, 0);
        glNamedFramebufferDrawBuffer(accumulationFbo_, GL_COLOR_ATTACHMENT0);
        host_->checkFramebuffer(accumulationFbo_, "visibility accumulation");
        host_->registerDebugImage("world positions", positions_, DebugImageKind::Color);
        host_->registerDebugImage("average visibility", accumulation_, DebugImageKind::Mask);
    }

    // World positions of the opaque surfaces the main pass will shade (translucent surfaces are
    // drawn over them there without depth writes, so the opaque surface is the one measured).
    void positionPrePass() {
        GpuPass pass(*host_, "position pre-pass");
        glBindFramebuffer(GL_FRAMEBUFFER, positionFbo_);
        glViewport(0, 0, viewport_.x, viewport_.y);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(positionFbo_, GL_COLOR, 0, zero);
        glClearNamedFramebufferfi(positionFbo_, GL_DEPTH_STENCIL, 0, 1.0f, 0);
        const GLuint program = host_->glProgram(positionProgram_);
        for (uint32_t i = 0; i < host_->objectCount(); ++i)
            if (!host_->objectInfo(i).translucent) host_->drawObject(i, program);
    }

    // For each light sample: its shadow map, then its visibility of every pixel added (times 1/N).
    void accumulateSamples(const ParamValues& params) {
        GpuPass pass(*host_, "light samples");
        const int samples = params.asInt(kSamples);
        const Bounds bounds = host_->sceneBounds(DrawSet::All);
        const LightInfo& light = host_->light();
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(accumulationFbo_, GL_COLOR, 0, zero);
        const GLuint accumulateProgram = host_->glProgram(accumulateProgram_);
        for (int i = 0; i < samples; ++i) {
            const LightSpace lightSpace = host_->fitLightSpaceFor(sampleLight(light, bounds, i, samples), DrawSet::All);
            sampleMap_.drawDepth(lightSpace, params.asFloat(kConstantBias), params.asFloat(kSlopeBias));

            glBindFramebuffer(GL_FRAMEBUFFER, accumulationFbo_);
            glViewport(0, 0, viewport_.x, viewport_.y);
            glDisable(GL_DEPTH_TEST);
            glEnable(GL_BLEND);
            glBlendEquation(GL_FUNC_ADD);
            glBlendColor(1.0f / float(samples), 0.0f, 0.0f, 0.0f);
            glBlendFunc(GL_CONSTANT_COLOR, GL_ONE);
            glUseProgram(accumulateProgram);
            glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(lightSpace.viewProjection));
            glBindTextureUnit(4, positions_);
            glBindTextureUnit(5, sampleMap_.texture());
            host_->drawFullscreenTriangle();
        }
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
    }

    IHost* host_ = nullptr;
    kernel_filtering::KernelShadowMap sampleMap_;   // re-rendered for every light sample
    ProgramId positionProgram_ = 0, accumulateProgram_ = 0;
    GLuint positionFbo_ = 0, accumulationFbo_ = 0;
    GLuint positions_ = 0, depth_ = 0, accumulation_ = 0;
    glm::ivec2 viewport_{0};
};

} // namespace

SHADOWLAB_PLUGIN(AreaReference, kDescriptor)
