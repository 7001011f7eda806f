// Exponential shadow maps (Annen, Mertens, Seidel, Bekaert, Kautz 2008, "Exponential Shadow
// Maps"). The light stores exp(c d) of its depth d, a single "exponential moment" that can be
// blurred and mipmapped like VSM's moments (one 32-bit channel instead of two); the shadow test
// exp(-c d_r) E[exp(c d)], clamped to [0, 1], approximates the filtered step function, exactly in
// the limit of large c where the receiver lies behind every occluder of the window.
// Known artefacts: light leaks where receiver and occluder are close in depth (contact shadows
// fade in, exp(-c (d_r - d)) is far from 0 when d_r - d < a few 1/c); a larger c helps until
// 32-bit floats overflow (c <= 85 here); c is relative to the map's depth range, so the leaks grow
// with the extent of the casters (a shadow-casting ground plane makes it the whole scene). Where the filter window also sees lit texels, their
// large exp(c d) weights dominate and the penumbra shrinks towards the shadow (one-sided
// filtering); receivers inside the window's depth range (non-planar receivers) break the
// assumption d_r >= d and are lit by the clamp.
#include <shadowlab/kit/moment_map.h>
#include <shadowlab/kit/params.h>

#include "esm_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kExponent{"exponent", "exponent c", ParamType::Float, 1, 85, 80, "",
     "Sharpness c of exp(c d), depth d normalised to [0, 1] over the casters (Annen et al use about 80 for "
     "32-bit floats). Small c leaks light wherever receiver and occluder are close (contact shadows fade, "
     "penumbrae widen into the shadow); the maximum is where exp(c) nears the 32-bit float limit.", nullptr};

#define ESM_PARAMS(X)                    \
    SHADOWLAB_MOMENT_MAP_PARAMS(X, 1024) \
    X(float, exponent, kExponent)
SHADOWLAB_PARAMS(Params, ESM_PARAMS);

class ExponentialShadowMaps final : public kit::MomentTechnique<Params, shared::esm::EsmUniforms, "esm_moments.glsl"> {
    shared::esm::EsmUniforms configure(const Params& p, kit::MomentMapConfig& config) const override {
        config.format = GL_R32F;
        config.clearValue = glm::vec4(1.0f);   // exp(c (1 - 1)): depth 1, nothing occludes
        return {{}, p.exponent, 0.0f, 0.0f, 0.0f};
    }
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "esm",
     .displayName = "Exponential shadow maps",
     .category = "filtered",
     .explanation = "Stores exp(c d) of the light depth instead of the depth: the shadow test becomes a product, "
                   "exp(-c d_receiver) times the filtered map, so the map can be blurred and mipmapped like a texture "
                   "with one channel. Cheaper than VSM and free of its overlap light bleeding, but shadows leak light "
                   "where receiver and occluder nearly touch (contact shadows fade in; raise c) and the clamp makes "
                   "penumbrae one-sided.",
     .shadowGlsl = "esm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(ExponentialShadowMaps, kDescriptor)
