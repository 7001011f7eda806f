// Exponential variance shadow maps (Lauritzen and McCool 2008, "Layered variance shadow maps";
// Lauritzen's EVSM). The depth is warped by exp(c+ x) and -exp(-c- x) (x = 2 d - 1) and VSM's two
// moments of each warped depth are stored (RGBA32F), blurred and mipmapped like VSM. The main
// pass takes the Chebyshev bound (seed 000 eq. 3.13-3.15) of each and keeps the smaller one. The
// positive warp stretches the depths behind the nearest occluder, so overlapping occluders no longer
// leave the receiver near the mean: far less light bleeding than VSM; the negative warp fixes the
// cases where the positive one fails (a receiver close in front of the blurred occluder depths).
// Known artefacts: some light bleeding remains for small exponents or very unequal depths (the
// reduction parameter removes it), exponents are capped by 32-bit floats (c <= 42: the squares
// reach exp(2 c)), and the warped variance needs a depth-scaled minimum; 128 bits per texel.
#include <cmath>

#include <shadowlab/kit/moment_map.h>
#include <shadowlab/kit/params.h>

#include "evsm_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kPositiveExponent{"positive_exponent", "positive exponent c+", ParamType::Float, 1, 42, 40, "",
     "Steepness of the warp exp(c+ x) with x = 2d - 1 in [-1, 1] over the casters' depth range. Small values "
     "behave like plain VSM and leak light behind overlapping occluders; 42 is the 32-bit limit (the squares "
     "reach exp(2 c+)).", nullptr};
constexpr ParamDesc kNegativeExponent{"negative_exponent", "negative exponent c-", ParamType::Float, 1, 42, 5, "",
     "Steepness of the second warp -exp(-c- x), the bound that stays tight where the receiver lies close "
     "in front of the filtered depths. Small values waste it; large ones amplify the rounding of depths "
     "near the light (Lauritzen's usual choice is 5 with c+ = 40).", nullptr};

#define EVSM_PARAMS(X)                              \
    SHADOWLAB_MOMENT_MAP_PARAMS(X, 1024)            \
    X(float, positive_exponent, kPositiveExponent)  \
    X(float, negative_exponent, kNegativeExponent)  \
    SHADOWLAB_CHEBYSHEV_PARAMS(X)
SHADOWLAB_PARAMS(Params, EVSM_PARAMS);

class ExponentialVarianceShadowMaps final : public kit::MomentTechnique<Params, shared::evsm::EvsmUniforms, "evsm_moments.glsl"> {
    shared::evsm::EvsmUniforms configure(const Params& p, kit::MomentMapConfig& config) const override {
        config.format = GL_RGBA32F;
        // Depth 1 (x = 1): exp(c+), -exp(-c-), and their squares.
        const float positive = std::exp(p.positive_exponent);
        const float negative = -std::exp(-p.negative_exponent);
        config.clearValue = glm::vec4(positive, positive * positive, negative, negative * negative);
        return {{}, {p.positive_exponent, p.negative_exponent, 0.0f, 0.0f}, p.min_variance, p.light_bleeding, 0.0f, 0.0f};
    }
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "evsm",
     .displayName = "Exponential variance shadow maps",
     .category = "filtered",
     .explanation = "Warps the light depth through a positive and a negative exponential and keeps VSM's mean and "
                   "mean square of each, then takes the tighter of the two Chebyshev bounds. The exponential stretches "
                   "the depth differences behind an occluder, so the light that bleeds through overlapping occluders "
                   "in VSM mostly disappears while the map still blurs and mipmaps like a texture. Costs four 32-bit "
                   "channels per texel; exponents are capped by float range.",
     .shadowGlsl = "evsm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(ExponentialVarianceShadowMaps, kDescriptor)
