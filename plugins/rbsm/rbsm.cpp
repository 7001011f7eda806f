// Revectorization-based shadow mapping (Macedo and Apolinario, "Revectorization-Based Shadow
// Mapping", Graphics Interface 2016; seed 000 sec. 2.2 survey, ref. [13]; docs/anti-aliased-edges.md).
// The shadow map is shadowmap's (the same pass, bias and fit, and its two-layer biases: with
// `bias_method` midpoint or second-depth, seed 002 eq. 5.1, both layers are peeled and resolved
// into the one map of depths every texel test below reads; kit::RawDepthTechnique); the main
// pass rebuilds the jagged boundary of the binary depth test from the map's texel discontinuities
// (rbsm.glsl): (1) the receiver is tested against its texel and the four neighbours, with its own
// depth; a neighbour of the other class is a discontinuity. (2) Along every discontinuous side
// the run of texels sharing it is walked both ways until the boundary steps into the texel's row,
// steps away from it, or `max search` texels pass. (3) The steps' midpoints give the revectorized
// boundary through the run (one line for a staircase, two half lines for a notch, as in
// morphological anti-aliasing), and the receiver's normalized position in its texel says on which
// side of it it lies. Variants: non-conservative (the boundary moves both ways, the paper's full
// revectorization) and conservative (only into lit texels: the shadow can grow, never shrink, so
// revectorization cannot add light leaks). `filtered` replaces the binary side test by the
// coverage of the pixel's footprint (RSMSS's smoothing of the revectorized boundary, in spirit).
// Point lights: the kit's cube map with the plain test and the offset (revectorization and the
// two layers are for 2D maps here).
#include <shadowlab/kit/depth_maps.h>
#include <shadowlab/kit/params.h>

#include "rbsm_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kVariant = kit::enumParam("variant", "variant", 1, "conservative|non-conservative",
     "non-conservative: the revectorized boundary may cut into shadowed and lit texels alike (the paper's "
     "full revectorization; smallest edge error). conservative: it may only move into lit texels, so the shadow "
     "never shrinks and revectorization cannot open a light leak; about half of the staircase error remains "
     "(the shadowed texels' corners).");
constexpr ParamDesc kMaxSearch{"max_search", "max search", ParamType::Int, 1, 64, 16, "texels",
     "How far the walk along an edge goes on either side to find where the boundary steps. Edges nearly "
     "aligned with the map's axes have long runs: a run longer than this is treated as straight there. "
     "Costs up to 4 texel fetches per step at discontinuous texels only.",
     nullptr};
constexpr ParamDesc kFiltered{"filtered", "filtered edge", ParamType::Bool, 0, 1, 0, "",
     "Off: each pixel is on one side of the revectorized boundary (a hard edge). On: the fraction of the "
     "pixel's footprint in the map on each side, a one-pixel ramp that anti-aliases the edge on screen "
     "(against a hard reference sampled at pixel centres it adds a little error).",
     nullptr};

#define RBSM_PARAMS(X)                                  \
    SHADOWLAB_RAW_DEPTH_MAP_PARAMS(X)                   \
    X(int, variant, kVariant)                           \
    X(int, max_search, kMaxSearch)                      \
    X(bool, filtered, kFiltered)                        \
    SHADOWLAB_FIT_PARAMS(X)
SHADOWLAB_PARAMS(Params, RBSM_PARAMS);

class Revectorization final : public kit::RawDepthTechnique<Params, shared::rbsm::RbsmUniforms> {
    // Every test of rbsm.glsl compares the receiver with one whole texel's raw depth.
    shared::rbsm::RbsmUniforms configure(const Params& p) const override {
        return {{}, p.variant == 0 ? 1 : 0, p.max_search, p.filtered ? 1 : 0, 0};
    }
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "rbsm",
     .displayName = "Revectorization-based shadow mapping",
     .category = "hard",
     .explanation = "A plain shadow map whose jagged edges are rebuilt in the main pass (Macedo and Apolinario "
                    "2016): where a neighbouring texel's test differs, the run of texels along that edge is "
                    "walked to where the boundary steps, and a line through the steps' midpoints replaces the "
                    "staircase; the point's position inside its texel decides its side. Hard, sharp shadows "
                    "without texel steps, at the cost of a few fetches at edge texels only. Conservative: the "
                    "shadow may only grow. Compare with shadowmap at resolution 512 on aliasing-plane.",
     .shadowGlsl = "rbsm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(Revectorization, kDescriptor)
