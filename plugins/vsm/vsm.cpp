// Variance shadow maps (Donnelly and Lauritzen 2006; seed 000 sections 2.2.7 and 3.2.5,
// eq. 3.13-3.16). The light renders the first two moments of depth, M1 = E[d] and M2 = E[d^2],
// into an RG32F map that can be filtered like a colour image: a separable box or Gaussian blur,
// bilinear and optionally trilinear (mipmapped) lookups. The main pass bounds the lit fraction
// from above with the one-tailed Chebyshev inequality, p_max = sigma^2 / (sigma^2 + (d - mu)^2).
// Known artefacts: light bleeding where occluders overlap in depth (seed 000 Fig. 4.12c): the
// variance of a window that sees two occluders is large, so a receiver behind the nearer one is
// lit by a p_max that can approach 0.5; reduced, at the price of thinner penumbrae, by remapping
// [a, 1] to [0, 1]. Self-shadowing on slopes without the minimum variance or the derivative-based
// second moment (eq. 3.16). Penumbrae of constant width: filtering antialiases, it does not soften
// physically.
#include <shadowlab/kit/moment_map.h>
#include <shadowlab/kit/params.h>

#include "vsm_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kDerivativeMoment{"derivative_moment", "derivative-based M2", ParamType::Bool, 0, 1, 0, "",
     "Add 1/4 (dd/dx^2 + dd/dy^2) to the second moment as it is rendered, a slope-scaled bias that stops "
     "tilted surfaces from shadowing themselves without hand-tuned offsets. This is seed 000 eq. 3.16; off, "
     "only the minimum variance and the blur fight acne; on, shadows lighten a little where casters touch "
     "steeply tilted receivers.", nullptr};

#define VSM_PARAMS(X)                                   \
    SHADOWLAB_MOMENT_MAP_PARAMS(X, 1024)                \
    SHADOWLAB_CHEBYSHEV_PARAMS(X)                       \
    X(bool, derivative_moment, kDerivativeMoment)
SHADOWLAB_PARAMS(Params, VSM_PARAMS);

class VarianceShadowMaps final : public kit::MomentTechnique<Params, shared::vsm::VsmUniforms, "vsm_moments.glsl"> {
    shared::vsm::VsmUniforms configure(const Params& p, kit::MomentMapConfig& config) const override {
        config.format = GL_RG32F;   // 32 bits per moment: M2 - M1^2 cancels badly in 16 bits
        config.clearValue = glm::vec4(1.0f, 1.0f, 0.0f, 0.0f);   // d = 1: M1 = 1, M2 = 1
        config.momentsNeedDerivatives = p.derivative_moment;   // eq. 3.16 takes dFdx, dFdy
        return {{}, p.derivative_moment ? 1 : 0, p.min_variance, p.light_bleeding, 0.0f};
    }
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "vsm",
     .displayName = "Variance shadow maps",
     .category = "filtered",
     .explanation = "Stores the mean and the mean square of depth from the light, so the map can be blurred and "
                   "mipmapped like any texture; a shaded point then takes the Chebyshev upper bound of the fraction of "
                   "depths behind it as its visibility (seed 000 eq. 3.13-3.15). Smooth, antialiased edges for one "
                   "lookup and a cheap separable blur, but where occluders overlap at different depths the bound is "
                   "loose and light bleeds through (try the 'overlap' scene, then raise the light-bleeding reduction).",
     .shadowGlsl = "vsm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(VarianceShadowMaps, kDescriptor)
