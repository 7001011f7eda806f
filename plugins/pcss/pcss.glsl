// Percentage-closer soft shadows, main-pass side (Fernando 2005; seed 000 sec. 3.2.6):
//   1. blocker search: average the depths closer than the receiver inside the search radius,
//   2. penumbra estimate from the average blocker depth by similar triangles,
//   3. adaptive PCF (shaders/disc_sampling.glsl) with that radius.
// Both sample sets are jittered discs (seed 000 sec. 4.3.3: "adaptive techniques for both").
// Depths z below are linear: distance from the light along its axis (spot/point, perspective map)
// or from the map's near plane (directional, orthographic map).
#include "light_space.glsl"
#include "disc_sampling.glsl"
#include "depth_range.glsl"

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/depth_range_mips_shared.h"
#include "pcss_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2D uShadowDepth;  // raw depths: the search reads them, the filter compares
layout(binding = kSearchOffsetsUnit) uniform sampler3D uSearchOffsets;
layout(binding = kFilterOffsetsUnit) uniform sampler3D uFilterOffsets;
layout(binding = kDepthRangeMipsUnit) uniform sampler2D uDepthRange;   // level k texel: (min, max) depth over 2^(k+1) x 2^(k+1) map texels

layout(binding = kCompareUnit) uniform sampler2DShadow uShadowCompare;   // the same map, bilinear comparison

// One filter tap: lit when ref <= stored depth (GL_LEQUAL, as the texture unit compares). The
// bilinear variant is the texture unit's own 2x2 comparison filter on a second binding of the map:
// one instruction instead of a gather, four comparisons and three mixes in the shader.
float discTap(vec2 uv, float ref) {
    if (uBilinear == 0) return step(ref, textureLod(uShadowDepth, uv, 0.0).r);
    return texture(uShadowCompare, vec3(uv, ref));
}

// Step 1: mean linear depth of the samples closer to the light than the receiver (minus the cone
// bias, so the receiver's own tilted surface is not taken for a blocker); 0 blockers: lit.
float blockerSearch(ivec2 pixel, vec3 coord, vec2 radiusUv, float rimBias, out int blockers) {
    int count = uSearchGrid * uSearchGrid;
    float depthSum = 0.0;
    blockers = 0;
    for (int k = 0; k < count; ++k) {
        vec4 pair = discOffsetPair(uSearchOffsets, pixel, k / 2);
        vec2 offset = (k & 1) == 0 ? pair.xy : pair.zw;
        float d = textureLod(uShadowDepth, coord.xy + offset * radiusUv, 0.0).r;
        if (d < coord.z - rimBias * length(offset)) {
            depthSum += lightLinearDepth(d, uLightDepth);
            ++blockers;
        }
    }
    return blockers > 0 ? depthSum / float(blockers) : 0.0;
}

// Light cone from the receiver at depth zReceiver, at the depth zNear of the nearest possible
// blocker: its radius in uv. eq. 3.17-3.18 with n = zNear: s_lv = s_lw / s_lf where s_lf = W n is
// the frustum's width at n (W: width at unit depth), r = s_lv (z_r - n) / z_r. Orthographic: the
// limit of a light of radius D tan(alpha) at D -> infinity: r = tan(alpha) (z_r - n) / W.
vec2 searchRadius(float zReceiver, float zNear, bool perspective) {
    return perspective ? uLightSize / (uLightWorldSize * zNear) * (zReceiver - zNear) / zReceiver
                       : uLightSize * (zReceiver - zNear) / uLightWorldSize;
}

vec3 shadowTerm(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float resolution = uLightDepth.w;
    bool perspective = uLightDepth.z > 0.5;
    float zReceiver = lightLinearDepth(coord.z, uLightDepth);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);   // per texel
    ivec2 pixel = ivec2(s.fragCoord);

    // Step 1a: the search region. eq. 3.18 as printed takes n = the near plane. Where the map's near
    // plane sits close to the light (spot and point lights fitted around a large ground), that
    // region covers half the map and n_s^2 samples miss the casters; with search_bound = 1 the
    // region shrinks twice to the cone at the nearest depth stored within it (a lower bound on
    // any blocker's depth, read from the min-depth mips). Deviation from the seed, same cone.
    float zNear = perspective ? uLightDepth.x : 0.0;
    vec2 searchUv = searchRadius(zReceiver, zNear, perspective);
    if (uSearchBound >= 1) {
        for (int i = 0; i < 2; ++i) {
            zNear = max(zNear, lightLinearDepth(depthRangeIn(uDepthRange, coord.xy, searchUv, resolution).x, uLightDepth));
            if (zNear >= zReceiver) return vec3(1.0);   // nothing nearer to the light than this point
            searchUv = searchRadius(zReceiver, zNear, perspective);
        }
    }
    // Step 1a': fully blocked (search_bound = depth-range). Every blocker in the final region lies at
    // or behind zNear, so the average blocker depth does too and the filter radius of step 2
    // (decreasing in the blocker depth, by the same similar triangles as searchRadius) is at most
    // the search radius, or one texel: every filter tap, and the texel beyond it that a bilinear
    // tap reads, lies within max(search radius, 1 texel) + 1 texel. Where the farthest depth stored
    // there is in front of the most biased reference (the rim's), every search sample is a
    // blocker and every filter tap is shadowed: the full computation returns 0, and so does this.
    if (uSearchBound == 2) {
        float searchTexels = max(max(searchUv.x, searchUv.y) * resolution, 1.0);
        vec2 regionUv = vec2((searchTexels + 1.0) / resolution);
        float farthest = depthRangeIn(uDepthRange, coord.xy, regionUv, resolution).y;
        if (farthest < coord.z - slope * searchTexels) return vec3(0.0);
    }

    // Step 1b: blocker search.
    int blockers;
    float zBlocker = blockerSearch(pixel, coord, searchUv, slope * max(searchUv.x, searchUv.y) * resolution, blockers);
    if (blockers == 0) return vec3(1.0);

    // Step 2: penumbra. eq. 3.19 s_p = (z_r - z_avg) / z_avg * s_lv and eq. 3.20 s_f = n / z_r * s_p
    // (re-derived by similar triangles: the penumbra's world width at the receiver is
    // (z_r - z_b) / z_b * s_lw; n / z_r projects it onto the near plane, where s_lv = s_lw / (W n)
    // is measured, so s_f = (z_r - z_b) / z_b * s_lw / (W z_r): n cancels). Orthographic: the same
    // with the light at distance D -> infinity and s_lw = D tan(alpha):
    // (z_r - z_b) / z_b * s_lw -> (z_r - z_b) tan(alpha), and no perspective shrink (n / z_r -> 1).
    vec2 filterUv = perspective ? (zReceiver - zBlocker) / zBlocker * uLightSize / (uLightWorldSize * zReceiver)
                                : (zReceiver - zBlocker) * uLightSize / uLightWorldSize;
    // At least one texel: contacts stay hard but anti-aliased instead of jittered nearest taps.
    filterUv = max(filterUv, vec2(1.0 / resolution));

    // Step 3: PCF with the estimated kernel, adaptive (outer ring first).
    bool earlyOut;
    return vec3(adaptiveDiscPcf(uFilterOffsets, pixel, uFilterGrid, coord, filterUv,
                                slope * max(filterUv.x, filterUv.y) * resolution, earlyOut));
}
