// Moment shadow mapping (Peters and Klein 2015; seed 000 section 2.2.7 calls it much more robust
// than VSM). The light stores four moments of depth, b = (z, z^2, z^3, z^4), which filter like
// VSM's two (separable blur, bilinear, mipmaps). The main pass reconstructs, with the Hamburger
// 4MSM algorithm, a three-point depth distribution consistent with the filtered moments and the
// receiver's depth, and takes the weight in front of the receiver as the shadow intensity
// (hamburger4msm.h). Optionally the moments are stored in 64 bits per texel (RGBA16 unorm) through
// the paper's optimised quantisation transform instead of 128 (RGBA32F).
// Known artefacts: much less light bleeding than VSM but some remains where occluders overlap at
// very different depths (reduced by remapping as in VSM); the moment bias that keeps the
// reconstruction stable (and makes 16-bit storage possible) adds a little leaking of its own and
// self-shadowing on slopes needs a depth bias; 16-bit storage bands at large bias; four channels
// double VSM's memory at 32 bits.
#include <shadowlab/kit/moment_map.h>
#include <shadowlab/kit/params.h>

#include "msm_shared.h"
#include "shadowlab/kit/hamburger4msm.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kParams[] = {
    SHADOWLAB_MOMENT_MAP_PARAMS(1024),
    {"storage", "moment storage", ParamType::Enum, 0, 1, 0, "",
     "How the four moments are stored: rgba32f, 32-bit floats (128 bits per texel), or rgba16, 16-bit unorm "
     "after the paper's optimised quantisation (half the memory and bandwidth; its rounding needs a moment "
     "bias of about 3e-5 or more).", "rgba32f|rgba16"},
    {"moment_bias", "moment bias alpha", ParamType::Float, 1e-7, 0.01, 3e-5, "",
     "alpha in b' = (1 - alpha) b + alpha b*, the pull towards a fixed wide depth distribution that keeps "
     "the reconstruction stable against rounding (3e-5 suits both storages; with 32-bit floats 1e-6 still "
     "works). Too small gives noise, acne and, worst with 16-bit storage, NaN; too large leaks light into "
     "shadows and softens contact shadows.", nullptr},
    {"depth_bias", "depth bias", ParamType::Float, 0, 0.05, 0.001, "depth",
     "Receiver depth moved towards the light before the reconstruction (depth normalised to [0, 1] over the "
     "casters). Zero lets sloped or blurred surfaces shadow themselves (acne, surface darkening); too much "
     "detaches shadows from their casters (peter panning).", nullptr},
    {"light_bleeding", "light-bleeding reduction", ParamType::Float, 0, 0.95, 0.0, "",
     "Remaps the visibility from [a, 1] to [0, 1], so values below a become full shadow; 0 is off. As in VSM "
     "(seed 000 section 3.2.5), but MSM needs much less; large values shrink and darken penumbrae.", nullptr},
};

enum : uint32_t {
    kResolution = kit::paramIndex(kParams, "resolution"),
    kKernel = kit::paramIndex(kParams, "kernel"),
    kFilter = kit::paramIndex(kParams, "filter"),
    kMipmaps = kit::paramIndex(kParams, "mipmaps"),
    kStorage = kit::paramIndex(kParams, "storage"),
    kMomentBias = kit::paramIndex(kParams, "moment_bias"),
    kDepthBias = kit::paramIndex(kParams, "depth_bias"),
    kLightBleedingReduction = kit::paramIndex(kParams, "light_bleeding"),
};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "msm",
     .displayName = "Moment shadow mapping",
     .category = "filtered",
     .explanation = "Stores four powers of the light depth, filters them like a texture, and reconstructs from the "
                   "filtered moments the depth distribution that is most plausible for the shaded point (Hamburger "
                   "4MSM): its share in front of the point is the shadow. Four moments describe overlapping occluders "
                   "far better than VSM's two, so light bleeding mostly disappears, and an optimised quantisation "
                   "lets all four fit in 64 bits per texel. Compare with vsm on the 'overlap' scene. Debug views: footprint, texel-grid and coverage (the map and its volume), focus-body (with fit = focus-body: B, seed 002 eq. 4.2), and 'moments'.",
     .shadowGlsl = "msm.glsl",
     .translucencyModel = TranslucencyModel::Ignore},   // its map holds opaque casters only
    kParams);

class MomentShadowMapping final : public kit::MomentTechnique<shared::msm::MsmUniforms> {
public:
    MomentShadowMapping() : MomentTechnique("msm_moments.glsl") {}

private:
    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        kit::MomentMapConfig config = kit::readCommonParams(params);
        const bool quantized = params.asInt(kStorage) == 1;
        config.format = quantized ? GL_RGBA16 : GL_RGBA32F;
        // Depth 1: nothing occludes there.
        const glm::vec4 farMoments = msm::momentsOfDepth(1.0f);
        config.clearValue = quantized ? glm::clamp(msm::quantizeMoments(farMoments), 0.0f, 1.0f) : farMoments;
        render(frame, config, {{}, quantized ? 1 : 0, params.asFloat(kMomentBias), params.asFloat(kDepthBias),
                       params.asFloat(kLightBleedingReduction)});
    }
};

} // namespace

SHADOWLAB_PLUGIN(MomentShadowMapping, kDescriptor)
