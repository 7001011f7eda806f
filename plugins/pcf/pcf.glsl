// Percentage-closer filtering, main-pass side (seed 000 sec. 3.2.4): average the binary shadow
// test s(t, z) = H(d(t) - z) over an n x n box of texel-aligned offsets around the shaded
// point's map position, keeping its depth z (optionally minus the cone bias). With GL_LINEAR
// each tap is itself the texture unit's 2x2 bilinear comparison (Fig. 3.11c).
//
// Two ways to evaluate the filter (the `sampling` parameter; the same filter without the cone
// bias, and with it the same up to a cone at most one texel diagonal wider, see pcfGather):
//   taps    the loop of n^2 lookups (boxPcfDepth, shaders/box_pcf.glsl), one texture() per tap;
//   gather  the texels the taps read, four at a time with textureGather (pcfGather), each weighted
//           by how much of it the taps take. The idea is Castano's ("Shadow Mapping Summary -
//           Part 1", 2013: the optimised PCF of The Witness, also in MJP's Shadows sample), which
//           folds the bilinear taps of a kernel onto its texels and fetches them with the fewest
//           lookups; here the weights are chosen to reproduce this box of taps exactly rather than
//           a wider tent, and the comparisons stay in the texture unit.
#include "light_space.glsl"
#include "light_depth.glsl"
#include "box_pcf.glsl"
#include "cube_shadow.glsl"

#include "shadowlab/kit/depth_map_shared.h"
#include "pcf_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;   // comparison: hardware PCF

// The gather variant, for unit spacing (pcf.cpp uses the taps otherwise). Derivation, per axis
// (the filter is separable apart from the references), in texel units: the point is at u, texel t
// covers [t, t + 1), tap i (0 <= i < n) sits at u + i - c with c = (n - 1) / 2.
//   Nearest taps read texel floor(u + i - c) = t0 + i with t0 = floor(u - c) (boxPcfDepth looks each up
//   at that texel's centre, so the texture unit takes the same one): the n taps are n neighbouring
//   texels, each with weight 1.
//   Bilinear taps read texels floor(u + i - c - 1/2) = t0 + i and t0 + i + 1 with weights 1 - f and
//   f, where t0 = floor(u - c - 1/2) and f = fract(u - c - 1/2) are the same for every tap (the
//   offsets are whole texels apart). Texel t0 + k (0 <= k <= n) is then the left texel of tap k and
//   the right texel of tap k - 1, so its weight is
//       w_k = (1 - f) [k < n] + f [k > 0]  =  (1 - f, 1, 1, ..., 1, f),
//   the box of n bilinear taps as an (n + 1)-texel kernel, the tent-convolved box of Castano's
//   derivation without widening it. In 2D the weight of a texel is w_kx w_ky.
// The m = n (nearest) or n + 1 (bilinear) texels per axis are fetched in 2 x 2 blocks, one
// textureGather at the corner the block's four texels share: ceil(m / 2)^2 lookups instead of n^2
// (36 instead of 121 at 11 x 11). textureGather returns the block's texels in the order (0, 1),
// (1, 1), (1, 0), (0, 0) (x right, y up) and clamps to the edge as the taps do.
// Every block is one comparing gather (textureGather on the sampler2DShadow: four `ref <= depth`
// tests in the texture unit) against one reference depth. Without the cone bias that reference is
// every tap's, and the gather is the taps' filter exactly. With it each tap has its own reference,
// z - slope * r (r: the tap's distance from the centre), and a block's texels are read by up to
// 2 x 2 (nearest) or 3 x 3 (bilinear) taps; the block compares against the smallest of their
// references, the one of the farthest tap. That keeps the cone conservative (a texel is never
// darker than in the taps: every pixel's gather term is >= its taps term) and moves it outwards by
// at most one texel diagonal (slope * sqrt 2 of extra bias, seen at contacts and where a receiver
// turns away from the light; the block's centroid instead, not conservative, was further from the
// taps and darker at contacts on llvmpipe: tests/test_soft_filtering.cpp), where an exact
// per-tap comparison would need raw depths and up to 16 shader comparisons per block. On an H200
// that exact version was 1.3-1.5x slower than the taps (build c84cf6c); this one needs four weights
// and one gather per block, and measured 0.84-0.88x the taps' shadow term at 11 x 11 and 1.09-1.20x
// at 5 x 5 (docs/results/h200-2026-12-01): there each gather costs about three taps.

// Weight of texel k of the kernel along one axis (nearest taps: f = 0 and k < n).
float texelWeight(int k, float f) {
    return (k < uKernel ? 1.0 - f : 0.0) + (k > 0 ? f : 0.0);
}

float pcfGather(vec3 coord, float slope) {
    float resolution = uLightDepth.w;
    float centre = 0.5 * float(uKernel - 1);
    bool bilinear = uBilinear != 0;
    vec2 start = coord.xy * resolution - centre - (bilinear ? 0.5 : 0.0);
    vec2 origin = floor(start);                          // texel t0 in x and y
    vec2 f = bilinear ? start - origin : vec2(0.0);
    int texels = uKernel + (bilinear ? 1 : 0);           // m
    int blocks = (texels + 1) / 2;
    float lit = 0.0;
    for (int b = 0; b < blocks; ++b)
        for (int a = 0; a < blocks; ++a) {
            ivec2 k0 = 2 * ivec2(a, b);                           // the block's lower-left texel
            vec2 corner = (origin + vec2(k0 + 1)) / resolution;   // shared by its four texels
            // Texel weights, 0 past the kernel (the last block of an odd m).
            vec2 wx = vec2(texelWeight(k0.x, f.x), k0.x + 1 < texels ? texelWeight(k0.x + 1, f.x) : 0.0);
            vec2 wy = vec2(texelWeight(k0.y, f.y), k0.y + 1 < texels ? texelWeight(k0.y + 1, f.y) : 0.0);
            // Taps reading the block: k0 .. k0 + 1 (nearest: texel k is tap k) or k0 - 1 .. k0 + 1
            // (bilinear: texel k is read by taps k - 1 and k), within the kernel; the farthest of
            // them from the centre, per axis, is at one end of that range.
            ivec2 first = max(k0 - (bilinear ? 1 : 0), ivec2(0));
            ivec2 last = min(k0 + 1, ivec2(uKernel - 1));
            vec2 reach = max(abs(vec2(first) - centre), abs(vec2(last) - centre)) * uOffsetScale;
            vec4 visible = textureGather(uShadowMap, corner, coord.z - slope * length(reach));
            lit += dot(visible, vec4(wx.x * wy.y, wx.y * wy.y, wx.y * wy.x, wx.x * wy.x));
        }
    return lit;
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, uKernel, uOffsetScale, uConeBias));
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);
    if (uGather != 0) return vec3(pcfGather(coord, slope) / float(uKernel * uKernel));
    return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, uKernel, uOffsetScale, slope, uBilinear != 0));
}
