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

constexpr ParamDesc kStorage = kit::enumParam("storage", "moment storage", 0, "rgba32f|rgba16",
     "How the four moments are stored: rgba32f, 32-bit floats (128 bits per texel), or rgba16, 16-bit unorm "
     "after the paper's optimised quantisation (half the memory and bandwidth; its rounding needs a moment "
     "bias of about 3e-5 or more).");
constexpr ParamDesc kMomentBias{"moment_bias", "moment bias alpha", ParamType::Float, 1e-7, 0.01, 3e-5, "",
     "alpha in b' = (1 - alpha) b + alpha b*, the pull towards a fixed wide depth distribution that keeps "
     "the reconstruction stable against rounding (3e-5 suits both storages; with 32-bit floats 1e-6 still "
     "works). Too small gives noise, acne and, worst with 16-bit storage, NaN; too large leaks light into "
     "shadows and softens contact shadows.", nullptr};
constexpr ParamDesc kDepthBias{"depth_bias", "depth bias", ParamType::Float, 0, 0.05, 0.001, "depth",
     "Receiver depth moved towards the light before the reconstruction (depth normalised to [0, 1] over the "
     "casters). Zero lets sloped or blurred surfaces shadow themselves (acne, surface darkening); too much "
     "detaches shadows from their casters (peter panning).", nullptr};

#define MSM_PARAMS(X)                    \
    SHADOWLAB_MOMENT_MAP_PARAMS(X, 1024) \
    X(int, storage, kStorage)            \
    X(float, moment_bias, kMomentBias)   \
    X(float, depth_bias, kDepthBias)     \
    X(float, light_bleeding, kit::lightBleedingParam())
SHADOWLAB_PARAMS(Params, MSM_PARAMS);

class MomentShadowMapping final : public kit::MomentTechnique<Params, shared::msm::MsmUniforms, "msm_moments.glsl"> {
    shared::msm::MsmUniforms configure(const Params& p, kit::MomentMapConfig& config) const override {
        const bool quantized = p.storage == 1;
        config.format = quantized ? GL_RGBA16 : GL_RGBA32F;
        // Depth 1: nothing occludes there.
        const glm::vec4 farMoments = msm::momentsOfDepth(1.0f);
        config.clearValue = quantized ? glm::clamp(msm::quantizeMoments(farMoments), 0.0f, 1.0f) : farMoments;
        return {{}, quantized ? 1 : 0, p.moment_bias, p.depth_bias, p.light_bleeding};
    }
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "msm",
     .displayName = "Moment shadow mapping",
     .category = "filtered",
     .explanation = "Stores four powers of the light depth, filters them like a texture, and reconstructs from the "
                   "filtered moments the depth distribution that is most plausible for the shaded point (Hamburger "
                   "4MSM): its share in front of the point is the shadow. Four moments describe overlapping occluders "
                   "far better than VSM's two, so light bleeding mostly disappears, and an optimised quantisation "
                   "lets all four fit in 64 bits per texel. Compare with vsm on the 'overlap' scene.",
     .shadowGlsl = "msm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(MomentShadowMapping, kDescriptor)
