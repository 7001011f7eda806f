// Kernel filtering of a shadow map, shared by pcf, adaptive-pcf and pcss:
//   1. light-space depth helpers and the cone bias (receiver bias growing with the kernel offset),
//   2. the jittered disc sets of adaptive PCF (seed 000 sec. 3.2.4; GPU Gems 2 ch. 17), stored
//      by shadowlab/kit/jittered_disk.h in an m x m x ceil(n^2/2) RGBA16_SNORM 3D texture,
//   3. the adaptive filter itself: outer ring first, stop when it agrees.
// The uniforms stay in each technique's GLSL; everything here takes them as arguments.
// `lightDepth` is (near, far, 1 perspective / 0 orthographic, map resolution) and `worldSize` the
// map's extent in world units (orthographic) or at unit distance (perspective), as set by
// shadowlab/kit/depth_map.h.
#ifndef SHADOWLAB_DISC_SAMPLING_GLSL
#define SHADOWLAB_DISC_SAMPLING_GLSL

#include "common.glsl"

// ---------------------------------------------------------------------------------------------
// 1. Depth in light space: lightLinearDepth and receiverDepthSlope (the cone bias), in
//    light_depth.glsl so techniques without disc sets use them too.
#include "light_depth.glsl"

// ---------------------------------------------------------------------------------------------
// 2. Jittered disc sets: texel t of the set chosen by the pixel holds samples 2t (xy) and
//    2t + 1 (zw); the first ceil(n/2) texels are the outer ring. Sets repeat every m pixels.

vec4 discOffsetPair(sampler3D offsets, ivec2 pixel, int texel) {
    ivec2 sets = textureSize(offsets, 0).xy;
    return texelFetch(offsets, ivec3(pixel % sets, texel), 0);
}

// ---------------------------------------------------------------------------------------------
// 3. Adaptive PCF over one disc set. The including technique defines how one tap compares
//    (hardware sampler2DShadow, or a raw depth read and a compare in the shader):
float discTap(vec2 uv, float ref);

// Sum of the taps of one texel (one or two samples); `taken` counts them.
float discTapPair(vec4 pair, bool second, vec3 coord, vec2 radiusUv, float rimBias, inout int taken) {
    // Cone bias: the receiver depth tolerance grows with the offset's distance from the centre
    // (rimBias at the rim, |offset| = 1).
    float lit = discTap(coord.xy + pair.xy * radiusUv, coord.z - rimBias * length(pair.xy));
    ++taken;
    if (second) {
        lit += discTap(coord.xy + pair.zw * radiusUv, coord.z - rimBias * length(pair.zw));
        ++taken;
    }
    return lit;
}

// True in all four pixels of a 2x2 quad iff `v` holds in all four. Fine derivatives give each
// pixel the difference to its horizontal, then its vertical neighbour; a "miss" flag summed with
// the absolute differences in x and then in y reaches the whole quad (the diagonal through the
// second step). Call it in uniform control flow (derivatives); helper pixels vote too.
bool quadAll(bool v) {
    float miss = v ? 0.0 : 1.0;
    miss += abs(dFdxFine(miss));
    miss += abs(dFdyFine(miss));
    return miss == 0.0;
}

// Lit fraction over the n x n set of this pixel, scaled to `radiusUv` around coord.xy.
// The outer ring (first n samples, rounded up to whole texels) is tested first; when all its
// taps agree (all lit or all shadowed) the point is taken to be outside any penumbra and the
// rest is skipped (`earlyOut`). Known artefact (seed 000 sec. 4.3.2): a lit gap narrower than
// the disc, surrounded by shadow, is classified shadowed.
//
// With `quadCoherent` (a uniform; call in uniform control flow then) the decision is taken per 2x2
// quad: a quad stops only when every pixel's ring agrees (pixels with `skip`, outside the map,
// count as agreeing). GPUs shade quads together and a warp runs as long as its slowest pixel, so
// per-pixel early outs that differ inside a quad were expected to save nothing there. Measured on
// an H200 it changes nothing (within 1% on cube, 1-3% slower on dragon-like, slightly lower
// penumbra error; docs/results/h200-2026-12-01): divergence is not what limits this filter.
float adaptiveDiscPcf(sampler3D offsets, ivec2 pixel, int n, vec3 coord, vec2 radiusUv, float rimBias, bool quadCoherent,
                      bool skip, out bool earlyOut) {
    int count = n * n;
    int texels = (count + 1) / 2;
    int ringTexels = (n + 1) / 2;
    float lit = 0.0;
    int taken = 0;
    earlyOut = false;
    // A skipped pixel (decided by its caller) reads no taps but still votes, as agreeing.
    if (!skip)
        for (int t = 0; t < ringTexels; ++t)
            lit += discTapPair(discOffsetPair(offsets, pixel, t), 2 * t + 1 < count, coord, radiusUv, rimBias, taken);
    bool agree = skip || lit == 0.0 || lit == float(taken);
    bool stop = quadCoherent ? quadAll(agree) : agree;
    if (ringTexels < texels && stop) {
        earlyOut = true;
        return lit / float(taken);
    }
    for (int t = ringTexels; t < texels; ++t)
        lit += discTapPair(discOffsetPair(offsets, pixel, t), 2 * t + 1 < count, coord, radiusUv, rimBias, taken);
    return lit / float(taken);
}

// The per-pixel decision (pcss, which reaches this in non-uniform control flow).
float adaptiveDiscPcf(sampler3D offsets, ivec2 pixel, int n, vec3 coord, vec2 radiusUv, float rimBias,
                      out bool earlyOut) {
    return adaptiveDiscPcf(offsets, pixel, n, coord, radiusUv, rimBias, false, false, earlyOut);
}

#endif
