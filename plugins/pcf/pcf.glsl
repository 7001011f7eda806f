// Percentage-closer filtering, main-pass side (seed 000 sec. 3.2.4): average the binary shadow
// test s(t, z) = H(d(t) - z) over an n x n box of texel-aligned offsets around the shaded
// point's map position, keeping its depth z (optionally minus the cone bias). With GL_LINEAR
// each tap is itself the texture unit's 2x2 bilinear comparison (Fig. 3.11c).
//
// Three ways to evaluate the filter (the `sampling` parameter; the same filter without the cone
// bias, and with it the same up to a cone at most one texel diagonal wider, see the gather variant):
//   taps    the loop of n^2 lookups (boxPcfDepth, shaders/box_pcf.glsl), one texture() per tap;
//   gather  the texels the taps read, four at a time with textureGather (gatheredBlock), each
//           weighted by how much of it the taps take. The idea is Castano's ("Shadow Mapping Summary -
//           Part 1", 2013: the optimised PCF of The Witness, also in MJP's Shadows sample), which
//           folds the bilinear taps of a kernel onto its texels and fetches them with the fewest
//           lookups; here the weights are chosen to reproduce this box of taps exactly rather than
//           a wider tent, and the comparisons stay in the texture unit.
//   folded  the same 2 x 2 blocks, each one bilinear comparison the texture unit weights
//           (foldedBlock: Castano's own form).
//
// classify = depth-range (uClassify 1, 2D maps only): before any of the above, the nearest and
// farthest depth of every texel the kernel can read, from the kit's depth-range mips (min/max
// mips as in kit/depth_range_mips.h, at most four fetches), decide the pixel where every one of
// sec. 3.2.4's binary tests in the kernel agrees; the other pixels run the kernel
// (classifyByDepthRange below).
#include "light_space.glsl"
#include "light_depth.glsl"
#include "box_pcf.glsl"
#include "cube_shadow.glsl"
#include "depth_range.glsl"

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/depth_range_mips_shared.h"
#include "pcf_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;   // comparison: hardware PCF
layout(binding = kDepthRangeMipsUnit) uniform sampler2D uDepthRange;  // classify = depth-range: (min, max) mips

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
// (1, 1), (1, 0), (0, 0) (x right, y up) and clamps to the edge as the taps do (gatheredBlock).
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
// and one gather per block, and measured 0.62-0.65x the taps' shadow term at 11 x 11 and 0.89-0.95x
// at 5 x 5, folded the same (docs/results/h200-2026-12-02-issue10): there each 2 x 2 lookup costs
// 2.1-2.5 taps, whatever the arithmetic around it (the cone bias off changes nothing).

// Weight of texel k of the kernel along one axis (nearest taps: f = 0 and k < n).
float texelWeight(int k, float f) {
    return (k < uKernel ? 1.0 - f : 0.0) + (k > 0 ? f : 0.0);
}

// Weights of the pair of texels k0, k0 + 1 along one axis; 0 past the kernel (the last pair of an odd m).
vec2 pairWeights(int k0, float f, int texels) {
    return vec2(texelWeight(k0, f), k0 + 1 < texels ? texelWeight(k0 + 1, f) : 0.0);
}

// Cone-bias distance, along one axis, of the farthest tap reading the pair k0, k0 + 1: taps k0 ..
// k0 + 1 (nearest: texel k is tap k) or k0 - 1 .. k0 + 1 (bilinear: texel k is read by taps k - 1
// and k), within the kernel; the farthest from the centre is at one end of that range.
float pairReach(int k0, bool bilinear, float centre) {
    float first = float(max(k0 - (bilinear ? 1 : 0), 0));
    float last = float(min(k0 + 1, uKernel - 1));
    return max(abs(first - centre), abs(last - centre)) * uOffsetScale;
}

// The kernel's texels t0 + k, 0 <= k < m, per axis (see above): t0 (origin), f, m; and the
// ceil(m / 2) blocks of 2 x 2 texels per axis that gather and folded read.
struct KernelTexels {
    vec2 origin;
    vec2 f;
    int texels;
    int blocks;
    float centre;     // c = (n - 1) / 2
    bool bilinear;
};

KernelTexels kernelTexels(vec3 coord) {
    KernelTexels k;
    k.bilinear = uBilinear != 0;
    k.centre = 0.5 * float(uKernel - 1);
    vec2 start = coord.xy * uLightDepth.w - k.centre - (k.bilinear ? 0.5 : 0.0);
    k.origin = floor(start);
    k.f = k.bilinear ? start - k.origin : vec2(0.0);
    k.texels = uKernel + (k.bilinear ? 1 : 0);
    k.blocks = (k.texels + 1) / 2;
    return k;
}

// The gather variant's block (a, b): one comparing textureGather at the corner its four texels
// share, weighted per texel (wx, wy: the pairs' weights along x and y).
float gatheredBlock(KernelTexels k, int a, int b, vec2 wx, vec2 wy, float reference) {
    vec2 corner = (k.origin + vec2(float(2 * a + 1), float(2 * b + 1))) / uLightDepth.w;
    vec4 visible = textureGather(uShadowMap, corner, reference);
    return dot(visible, vec4(wx.x * wy.y, wx.y * wy.y, wx.y * wy.x, wx.x * wy.x));
}

// The folded variant: the same 2 x 2 blocks of texels, each read by one bilinear comparison
// (texture() on the GL_LINEAR comparison sampler) placed so that the texture unit's own weights are
// the block's: a pair of texels weighted (w0, w1) along an axis is the bilinear lookup at
// w1 / (w0 + w1) of the way from the first texel's centre to the second's, times w0 + w1; in 2D
// the product of the two axes (Castano 2013's optimised PCF, where the texture unit also does the
// weighting). Nearest taps put every lookup on a texel corner (weights 1/2, 1/2) or, for the last
// pair of an odd m, on a texel centre (1, 0); bilinear taps move the two end pairs by f. The
// texture unit holds a weight with 8 fractional bits, so off-centre end pairs may differ from the
// taps (which are quantised the same way) by about 1/512 of their weight. Same references per
// block as gatheredBlock; one lookup and two weights per block instead of four weights and a dot.
float foldedBlock(KernelTexels k, int a, int b, vec2 wx, vec2 wy, float reference) {
    vec2 s = vec2(wx.x + wx.y, wy.x + wy.y);
    vec2 along = vec2(s.x > 0.0 ? wx.y / s.x : 0.0, s.y > 0.0 ? wy.y / s.y : 0.0);
    vec2 position = (k.origin + vec2(float(2 * a), float(2 * b)) + 0.5 + along) / uLightDepth.w;
    return s.x * s.y * texture(uShadowMap, vec3(position, reference));
}

// Gather (folded false) and folded: the kernel's blocks, each compared against the reference of
// its farthest tap (see above), summed with their weights.
float pcfBlocks(vec3 coord, float slope, bool folded) {
    KernelTexels k = kernelTexels(coord);
    float lit = 0.0;
    for (int b = 0; b < k.blocks; ++b) {
        vec2 wy = pairWeights(2 * b, k.f.y, k.texels);
        float reachY = pairReach(2 * b, k.bilinear, k.centre);
        for (int a = 0; a < k.blocks; ++a) {
            vec2 wx = pairWeights(2 * a, k.f.x, k.texels);
            float reference = coord.z - slope * length(vec2(pairReach(2 * a, k.bilinear, k.centre), reachY));
            lit += folded ? foldedBlock(k, a, b, wx, wy, reference)
                          : gatheredBlock(k, a, b, wx, wy, reference);
        }
    }
    return lit;
}

// The exact early out of classify = depth-range: 1 when every comparison of the kernel passes
// (lit), 0 when every one fails (shadowed), -1 when the bounds cannot tell (run the kernel).
// Every lookup of every sampling reads texels within the taps' span u +- c s (u = coord.xy *
// resolution in texels, c = (n - 1) / 2, s the offset scale; gather and folded run only at s = 1)
// widened by h = 1/2 where a lookup is a bilinear one (each reads the 2 x 2 texels within half a
// texel of it). The region is one texel wider still on every side: folded with nearest taps puts
// the last lookup of an odd kernel on a texel centre, whose bilinear neighbour (weight 0, up to
// the texture unit's rounding) lies one texel past the kernel, and the texture unit's own
// rounding of a bilinear tap's position may pick the neighbouring pair where the shader's floor()
// would not. Weight-0 texels included, so no comparison the kernel makes is left out.
// The compared depths (the cone bias): every tap compares ref = coord.z - slope * r (r >= 0 its
// distance from the centre; gather and folded: a block's farthest tap's r), never more than
// coord.z and never less than coord.z - slope * c s sqrt 2 (the corner tap's r; the factor
// 1.41436 is sqrt 2 with 1e-4 to spare against the rounding of length() and of the product). So
// the region's nearest depth at or behind coord.z means ref <= depth for every comparison
// (LEQUAL: lit), and its farthest depth in front of the smallest ref means ref > depth for every
// one (shadowed). The map is 32-bit float (no rounding of ref in the comparison) and the sampler
// clamps to the edge (no border depth the mips would not hold). A decided pixel's kernel would
// have summed n^2 ones or zeros: 1 and 0 exactly (gather and folded with bilinear taps sum their
// weights in float, n^2 up to a few ulps; the shadow term is stored as a half float, where that
// rounds to 1; tests/test_soft_filtering.cpp, PcfClassify, finds no pixel changed).
// What it cannot decide: a receiver tilted against the light has texels on its near side closer
// to the light than coord.z (the cone bias is what keeps its taps lit), so the region's nearest
// depth is in front of it once the region (rounded up to the mips' power-of-two blocks) spans
// more than the depth bias covers: at 11 x 11 nearly all of the lit ground of cube and contact.
float classifyByDepthRange(vec3 coord, float slope) {
    float resolution = uLightDepth.w;
    float reach = 0.5 * float(uKernel - 1) * uOffsetScale;   // c s, texels
    float h = (uBilinear != 0 || uSampling == 2) ? 0.5 : 0.0;
    vec2 u = coord.xy * resolution;
    ivec2 lo = ivec2(floor(u - reach - h)) - 1;
    ivec2 hi = ivec2(floor(u + reach + h)) + 1;
    vec2 range = depthRangeInTexels(uDepthRange, lo, hi, resolution);
    if (range.x >= coord.z) return 1.0;
    if (range.y < coord.z - slope * (reach * 1.41436)) return 0.0;
    return -1.0;
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, uKernel, uOffsetScale, uConeBias));
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);
    if (uClassify == 1) {
        float decided = classifyByDepthRange(coord, slope);
        if (decided >= 0.0) return vec3(decided);
    }
    if (uSampling != 0) return vec3(pcfBlocks(coord, slope, uSampling == 2) / float(uKernel * uKernel));
    // The smallest kernels with the size a constant (the call is inlined, so its loops have fixed
    // bounds). On an H200 (docs/results/h200-2026-12-03-issue10) the shadow term fell 46% at 3 x 3
    // and 6-21% at 5 x 5 (forest the most), with the same image; from 7 x 7 up, and for gather and
    // folded, it changed nothing, so those keep the loop.
    bool bilinear = uBilinear != 0;
    switch (uKernel) {
    case 3: return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, 3, uOffsetScale, slope, bilinear));
    case 5: return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, 5, uOffsetScale, slope, bilinear));
    }
    return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, uKernel, uOffsetScale, slope, bilinear));
}
