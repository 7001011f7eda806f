// Random numbers for stochastic light passes (stochastic-sm, cssm2; seed 001 sec. 2.1.2, 2.1.3 and
// 4.2.2): one text compiled as C++ (so tests can reproduce a texel's xi) and as GLSL, and the
// block those light passes read. Seed 001 takes xi from an RGB noise texture; a hash costs a few
// integer operations instead of a fetch and, above all, can be decorrelated per surface:
//
//   per-surface  xi = hash(frame seed, texel, object, primitive, channel). Every translucent
//                surface over a texel draws its own xi, so a texel stays lit through surfaces
//                1..k with probability prod (1 - p_i), the expectation both techniques need.
//   per-texel    xi = hash(frame seed, texel, channel), one number shared by every surface over
//                the texel (a noise texture indexed by texel alone). Then a photon passes all k
//                surfaces only if xi clears the largest p_i: the texel is lit with probability
//                1 - max_i p_i, not prod (1 - p_i). Two stacked quads of p = 0.25 give 0.75
//                instead of 0.5625 (tests/test_coloured_shadows.cpp). Not in seed 001: derived
//                (docs/coloured-shadows.md).
//
// The frame seed (FrameContext::randomSeed) changes every frame, so the noise does too.
#ifndef SHADOWLAB_KIT_STOCHASTIC_SHARED_H
#define SHADOWLAB_KIT_STOCHASTIC_SHARED_H
#include "shadowlab/kit/shared.h"

#ifdef __cplusplus
#define SHADOWLAB_STOCHASTIC_FN inline
#define SHADOWLAB_STOCHASTIC_CONST inline constexpr
#else
#define SHADOWLAB_STOCHASTIC_FN
#define SHADOWLAB_STOCHASTIC_CONST const
#endif

SHADOWLAB_SHARED_BEGIN(stochastic)

// Values of the `noise` parameter (kit::noiseParam()).
SHADOWLAB_STOCHASTIC_CONST int kNoisePerSurface = 0;
SHADOWLAB_STOCHASTIC_CONST int kNoisePerTexel = 1;

// The light passes' block (bound while the technique draws its casters; the main pass binds its
// own block at the same binding afterwards).
SHADOWLAB_UNIFORM_BLOCK(StochasticPassUniforms, 2) {
    uint uFrameSeed;          // FrameContext::randomSeed
    int uNoise;               // kNoisePerSurface or kNoisePerTexel
    float uSlopeBias;         // colour maps: glPolygonOffset's factor, applied in the shader
    float uConstantBias;      // colour maps: glPolygonOffset's units (2^-24 each), applied in the shader
};

// A 32-bit integer hash (Chris Wellons' "lowbias32": full avalanche, no visible structure).
SHADOWLAB_STOCHASTIC_FN uint stochasticHash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

SHADOWLAB_STOCHASTIC_FN uint stochasticCombine(uint h, uint value) {
    return stochasticHash(h ^ (value + 0x9e3779b9u + (h << 6u) + (h >> 2u)));
}

// The hash behind xi (below), before it is turned into a number in [0, 1).
SHADOWLAB_STOCHASTIC_FN uint stochasticKey(uint frameSeed, uint texelX, uint texelY, uint object, uint primitive,
                                           uint channel, int noise) {
    uint h = stochasticCombine(stochasticHash(frameSeed), texelX);
    h = stochasticCombine(h, texelY);
    if (noise == kNoisePerSurface) {
        h = stochasticCombine(h, object);
        h = stochasticCombine(h, primitive);
    }
    return stochasticCombine(h, channel);
}

// xi in [0, 1) with 24 bits: keeping a fragment when xi < alpha keeps it with probability alpha
// exactly (alpha = 0 never, alpha = 1 always).
SHADOWLAB_STOCHASTIC_FN float stochasticXiOfKey(uint h) {
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

SHADOWLAB_STOCHASTIC_FN float stochasticXi(uint frameSeed, uint texelX, uint texelY, uint object, uint primitive,
                                           uint channel, int noise) {
    return stochasticXiOfKey(stochasticKey(frameSeed, texelX, texelY, object, primitive, channel, noise));
}

// xi of one sample of a multisampled texel (stochastic-sm's msaa; Enderton et al. 2010 decide per
// sample): the texel's key with the sample index folded in last, so every sample draws its own
// number. The noise modes keep their meaning: per-texel still leaves out object and triangle, so
// all surfaces over a sample share its number (1 - max p per sample).
SHADOWLAB_STOCHASTIC_FN float stochasticSampleXi(uint frameSeed, uint texelX, uint texelY, uint object, uint primitive,
                                                 uint channel, uint sampleIndex, int noise) {
    return stochasticXiOfKey(
        stochasticCombine(stochasticKey(frameSeed, texelX, texelY, object, primitive, channel, noise), sampleIndex));
}

SHADOWLAB_SHARED_END

#ifdef __cplusplus
#include <shadowlab/kit/params.h>
#include <shadowlab/technique.h>
namespace shadowlab::kit {
// The `noise` parameter of the stochastic techniques: how xi is indexed (above).
constexpr ParamDesc noiseParam() {
    return enumParam("noise", "noise", shared::stochastic::kNoisePerSurface, "per-surface|per-texel",
            "How the random number deciding each translucent fragment is drawn. per-surface: hashed from "
            "the texel, the object and the triangle (and the frame), so every surface over a texel decides "
            "on its own and the map converges to the product over the surfaces. per-texel: one number per "
            "texel, as a noise texture indexed by texel alone gives, shared by every surface there: stacked "
            "surfaces then let 1 - max p through instead of the product (wrong wherever two overlap).");
}
} // namespace shadowlab::kit
#else
// In a light pass's fragment stage (translucent_caster.vert supplies the object index): xi of
// channel c for this fragment.
float fragmentXi(uint object, uint channel) {
    uvec2 texel = uvec2(gl_FragCoord.xy);
    return stochasticXi(uFrameSeed, texel.x, texel.y, object, uint(gl_PrimitiveID), channel, uNoise);
}
// xi of sample `sampleIndex` of this fragment's texel (multisampled maps). gl_FragCoord is the
// texel centre unless the shader runs per sample; this one reads no gl_SampleID, so it does not.
float fragmentSampleXi(uint object, uint channel, int sampleIndex) {
    uvec2 texel = uvec2(gl_FragCoord.xy);
    return stochasticSampleXi(uFrameSeed, texel.x, texel.y, object, uint(gl_PrimitiveID), channel, uint(sampleIndex), uNoise);
}
#endif

#endif
