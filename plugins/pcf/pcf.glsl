// Percentage-closer filtering, main-pass side (seed 000 sec. 3.2.4): average the binary shadow
// test s(t, z) = H(d(t) - z) over an n x n box of texel-aligned offsets around the shaded
// point's map position, keeping its depth z (optionally minus the cone bias). With GL_LINEAR
// each tap is itself the texture unit's 2x2 bilinear comparison (Fig. 3.11c).
//
// Three ways to evaluate the filter (the `sampling` parameter; the same filter without the cone
// bias, and with it the same up to a cone at most one texel diagonal wider, see pcfBlocks):
//   taps    the loop of n^2 lookups (boxPcfDepth, shaders/box_pcf.glsl), one texture() per tap;
//   gather  the texels the taps read, four at a time with textureGather (pcfBlocks), each weighted
//           by how much of it the taps take. The idea is Castano's ("Shadow Mapping Summary -
//           Part 1", 2013: the optimised PCF of The Witness, also in MJP's Shadows sample), which
//           folds the bilinear taps of a kernel onto its texels and fetches them with the fewest
//           lookups; here the weights are chosen to reproduce this box of taps exactly rather than
//           a wider tent, and the comparisons stay in the texture unit.
//   folded  the same 2 x 2 blocks, each one bilinear comparison the texture unit weights
//           (pcfBlocks: Castano's own form).
//
// The `classify` parameter (uClassify, 2D maps only) skips lookups whose outcome the kit's
// depth-range mips (min/max mips, kit/depth_range_mips.h) already decide, exactly:
//   depth-range (1) before any sampling, the nearest and farthest depth of every texel the kernel
//           can read (at most four fetches) decide the pixel where every one of sec. 3.2.4's binary
//           tests agrees; the other pixels run the kernel (classifyByDepthRange below);
//   cells (2) gather and folded only: each 4 x 4 cell of the kernel's texels (one texel of mips
//           level 1) decides the 2 x 2 blocks it holds against their own references (pcfBlocks);
//           taps ignore it.
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

// Gather and folded, for unit spacing (pcf.cpp uses the taps otherwise). Derivation, per axis
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
// The m = n (nearest) or n + 1 (bilinear) texels per axis are fetched in 2 x 2 blocks at even
// texel coordinates (pcfBlocks): ceil(m / 2)^2 lookups, or one more row and column when t0 is odd,
// instead of n^2 (36 or 49 instead of 121 at 11 x 11). textureGather returns a block's texels in
// the order (0, 1), (1, 1), (1, 0), (0, 0) (x right, y up) and clamps to the edge as the taps do.

// Weight of texel k of the kernel along one axis (nearest taps: f = 0 and k < n).
float texelWeight(int k, float f) {
    return (k < uKernel ? 1.0 - f : 0.0) + (k > 0 ? f : 0.0);
}

// Cone-bias distance, along one axis, of the farthest tap reading the pair k0, k0 + 1: taps k0 ..
// k0 + 1 (nearest: texel k is tap k) or k0 - 1 .. k0 + 1 (bilinear: texel k is read by taps k - 1
// and k), within the kernel; the farthest from the centre is at one end of that range. k0 is -1
// for the first block of a kernel starting at an odd texel (its texel -1 has weight 0).
float pairReach(int k0, bool bilinear, float centre) {
    float first = float(max(k0 - (bilinear ? 1 : 0), 0));
    float last = float(min(k0 + 1, uKernel - 1));
    return max(abs(first - centre), abs(last - centre)) * uOffsetScale;
}

// The kernel's texels t0 + k, 0 <= k < m, per axis (see above): t0 (origin), f, m.
struct KernelTexels {
    vec2 origin;
    vec2 f;
    int texels;
};

KernelTexels kernelTexels(vec3 coord, bool bilinear) {
    float centre = 0.5 * float(uKernel - 1);
    vec2 start = coord.xy * uLightDepth.w - centre - (bilinear ? 0.5 : 0.0);
    KernelTexels k;
    k.origin = floor(start);
    // f in steps of 1/256, the texture unit's own precision for a bilinear weight: every weight
    // product then has at most 16 fractional bits and every sum of them (n^2 <= 225) is exact in
    // a float, so a pixel whose every comparison passes sums to exactly n^2 (1 after the division,
    // as a decided pixel; with unrounded weights a few ulps below it, which a half-float target
    // may store as 1 - 2^-11).
    k.f = bilinear ? floor((start - k.origin) * 256.0 + 0.5) / 256.0 : vec2(0.0);
    k.texels = uKernel + (bilinear ? 1 : 0);
    return k;
}

// Weight of kernel texel k along one axis, 0 outside the kernel's `texels` texels.
float kernelTexelWeight(int k, float f, int texels) {
    return k >= 0 && k < texels ? texelWeight(k, f) : 0.0;
}

// Gather and folded: the kernel's texels in 2 x 2 blocks at even texel coordinates (the kernel's
// first texel t0 rounded down to even), visited cell by cell, a cell being the 4 x 4 texels of one
// texel of the depth-range mips' level 1 (two blocks by two). A block's texels k0, k0 + 1 (k
// counted from t0: k0 is -1 when t0 is odd, and the last block may hold texel m) take the weights
// of the kernel, 0 outside it (kernelTexelWeight); a block of weight 0 is skipped.
// Gather: one comparing textureGather at the corner the block's four texels share, the four weighted
// in the shader. Folded: one bilinear comparison placed so that the texture unit's weights are the
// block's (a pair weighted (w0, w1) is the bilinear lookup w1 / (w0 + w1) of the way from the first
// texel's centre to the second's, times w0 + w1; in 2D the product of the two axes: Castano 2013's
// optimised PCF). Nearest taps put folded lookups on texel corners (1/2, 1/2) or centres (1, 0).
// Weights are in steps of 1/256 (kernelTexels), as the texture unit keeps a bilinear weight; it may
// round a tap's own weight the other way, by up to 1/512.
// References: every block is compared against one depth. Without the cone bias that is every
// tap's, and both samplings are the taps' filter exactly. With it each tap has its own,
// z - slope * r (r: the tap's distance from the centre), and a block's texels are read by up to
// 2 x 2 (nearest) or 3 x 3 (bilinear) taps; the block compares against the smallest of theirs,
// the farthest tap's (pairReach). That keeps the cone conservative (a texel is never darker than
// in the taps: every pixel's term here is >= its taps term) and moves it outwards by at most one
// texel diagonal (slope * sqrt 2 of extra bias, seen at contacts and where a receiver turns away
// from the light; a block's centroid instead, not conservative, was further from the taps and
// darker at contacts on llvmpipe: tests/test_soft_filtering.cpp). An exact per-tap comparison
// would need raw depths and up to 16 shader comparisons per block: on an H200 that was 1.3-1.5x
// slower than the taps (build c84cf6c).
// classify = cells (`decide`): before a cell's blocks, its nearest and farthest depth (one fetch
// of mips level 1, the cell clamped to the map as the lookups clamp their texels) decide every
// block whose reference is at or in front of the nearest depth (all four comparisons pass: 1) or
// behind the farthest (all four fail: 0), exactly as the lookup would; only the other blocks are
// fetched. Where the whole kernel cannot be decided (classify = depth-range: a receiver tilted
// against the light has texels on its near side closer to the light than its own depth), most of
// its cells still can, each against its own blocks' cone-biased references.
// Cost, measured on an H200 (docs/results/h200-2026-12-03-issue10): one 2 x 2 lookup costs 2.0
// single taps whatever the arithmetic around it, so without decisions the 36 lookups at 11 x 11
// are 0.60-0.66x of the 121 taps, not 0.30x.
float pcfBlocks(vec3 coord, float slope, bool folded, bool decide) {
    float resolution = uLightDepth.w;
    float centre = 0.5 * float(uKernel - 1);
    bool bilinear = uBilinear != 0;
    KernelTexels kernel = kernelTexels(coord, bilinear);
    ivec2 first = ivec2(kernel.origin);   // t0
    ivec2 last = first + kernel.texels - 1;
    ivec2 firstCell = ivec2(floor(vec2(first) * 0.25));   // floor(t / 4), below 0 too
    ivec2 lastCell = ivec2(floor(vec2(last) * 0.25));
    ivec2 cells = max(textureSize(uDepthRange, 0) >> 1, ivec2(1));   // level 1's size, from level 0 (see depth_range.glsl)
    float lit = 0.0;
    for (int cy = firstCell.y; cy <= lastCell.y; ++cy) {
        for (int cx = firstCell.x; cx <= lastCell.x; ++cx) {
            // Undecided unless the bounds say otherwise: no reference is below -1e30 or above 1e30.
            vec2 range = decide ? texelFetch(uDepthRange, clamp(ivec2(cx, cy), ivec2(0), cells - 1), 1).rg : vec2(-1e30, 1e30);
            for (int j = 0; j < 2; ++j) {
                int by = 4 * cy + 2 * j;
                int ky = by - first.y;
                vec2 wy = vec2(kernelTexelWeight(ky, kernel.f.y, kernel.texels), kernelTexelWeight(ky + 1, kernel.f.y, kernel.texels));
                float sy = wy.x + wy.y;
                if (sy == 0.0) continue;
                float reachY = pairReach(ky, bilinear, centre);
                for (int i = 0; i < 2; ++i) {
                    int bx = 4 * cx + 2 * i;
                    int kx = bx - first.x;
                    vec2 wx = vec2(kernelTexelWeight(kx, kernel.f.x, kernel.texels), kernelTexelWeight(kx + 1, kernel.f.x, kernel.texels));
                    float sx = wx.x + wx.y;
                    if (sx == 0.0) continue;
                    float reference = coord.z - slope * length(vec2(pairReach(kx, bilinear, centre), reachY));
                    float decided = range.x >= reference ? 1.0 : (range.y < reference ? 0.0 : -1.0);
                    if (folded) {
                        vec2 at = (vec2(bx, by) + 0.5 + vec2(wx.y / sx, wy.y / sy)) / resolution;
                        lit += sx * sy * (decided >= 0.0 ? decided : texture(uShadowMap, vec3(at, reference)));
                    } else {
                        vec4 visible = decided >= 0.0 ? vec4(decided)
                                                      : textureGather(uShadowMap, vec2(bx + 1, by + 1) / resolution, reference);
                        lit += dot(visible, vec4(wx.x * wy.y, wx.y * wy.y, wx.y * wy.x, wx.x * wy.x));
                    }
                }
            }
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
    if (uSampling != 0) return vec3(pcfBlocks(coord, slope, uSampling == 2, uClassify == 2) / float(uKernel * uKernel));
    return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, uKernel, uOffsetScale, slope, uBilinear != 0));
}
