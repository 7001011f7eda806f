// Percentage-closer soft shadows, main-pass side (Fernando 2005; seed 000 sec. 3.2.6):
//   1. blocker search: average the depths closer than the receiver inside the search radius,
//   2. penumbra estimate from the average blocker depth by similar triangles,
//   3. adaptive PCF (shaders/disc_sampling.glsl) with that radius.
// Both sample sets are jittered discs (seed 000 sec. 4.3.3: "adaptive techniques for both").
// Depths z below are linear: distance from the light along its axis (spot/point, perspective map)
// or from the map's near plane (directional, orthographic map).
// Point lights: the same three steps in cube space (pcssCube below).
#include "light_space.glsl"
#include "disc_sampling.glsl"
#include "depth_range.glsl"
#include "cube_shadow.glsl"

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/depth_range_mips_shared.h"
#include "pcss_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2D uShadowDepth;  // raw depths: the search reads them, the filter compares
layout(binding = kSearchOffsetsUnit) uniform sampler3D uSearchOffsets;
layout(binding = kFilterOffsetsUnit) uniform sampler3D uFilterOffsets;
layout(binding = kDepthRangeMipsUnit) uniform sampler2D uDepthRange;   // level k texel: (min, max) depth over 2^(k+1) x 2^(k+1) map texels

layout(binding = kCompareUnit) uniform sampler2DShadow uShadowCompare;   // the same map, bilinear comparison

layout(binding = kCubeRawUnit) uniform samplerCube uCubeRaw;               // the cube's raw distances / far
layout(binding = kCubeMinDepthUnit) uniform sampler2DArray uCubeMinDepth;  // its min-depth mips, a layer per face

// The cube path's ray: while gCubeTaps is set, a tap's uv is its offset in tangent units across it.
bool gCubeTaps = false;
CubeRay gCubeRay;

// One filter tap: lit when ref <= stored depth (GL_LEQUAL, as the texture unit compares). The
// bilinear variant is the texture unit's own 2x2 comparison filter on a second binding of the map:
// one instruction instead of a gather, four comparisons and three mixes in the shader.
float discTap(vec2 uv, float ref) {
    if (gCubeTaps) {
        vec3 dir = cubeTapDirection(gCubeRay, uv);
        if (uBilinear == 0) return step(ref, textureLod(uCubeRaw, dir, 0.0).r);
        return texture(uCubeDepthMap, vec4(dir, ref));
    }
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

// ---------------------------------------------------------------------------------------------
// Point lights, in cube space. Offsets are tangent units across the ray from the light (an angle:
// tan of it), distances radial (the cube stores distance / far). With the light a sphere of radius
// s_lw, the cone from a receiver at distance z_r to it is s_lw (z_r - z) / z_r wide at distance z
// from the light, s_lw (z_r - z) / (z_r z) in tangent units: eq. 3.17-3.18 with the frustum's width
// at unit depth W = 1 (searchRadius above). The penumbra (eq. 3.19-3.20) likewise:
// (z_r - z_b) / z_b * s_lw / z_r tangent units. The disc sets and the adaptive filter are the 2D
// path's (the taps' uv are their offsets, discTap looks them up along the cube's directions).

// Nearest stored distance (over far) within `radiusTan` of the ray: the min-depth texels (of the
// first level whose texels span the region) holding the region's centre and the four corners of
// its square dir +- r u +- r v, each looked up in the face its own direction picks, so the region
// may cross a seam. A face's texels are up to 1 / cos^2 = 3 times denser per tangent unit than at
// its centre (the gnomonic stretch); the level is chosen for the stretch at the ray's direction,
// with a quarter of margin.
float nearestCubeDepthIn(CubeRay r, float radiusTan) {
    float faceSize = uCubeBias.z;
    float major = max(max(abs(r.dir.x), abs(r.dir.y)), abs(r.dir.z));
    float radiusTexels = 1.25 * radiusTan / (major * major) * 0.5 * faceSize;
    int top = textureQueryLevels(uCubeMinDepth) - 1;
    int level = clamp(int(ceil(log2(max(radiusTexels, 1.0)))), 0, top);
    int size = max(textureSize(uCubeMinDepth, 0).x >> level, 1);
    int span = 2 << level;   // cube texels per texel of this level
    float nearest = 1.0;
    for (int k = 0; k < 5; ++k) {
        vec2 corner = k == 0 ? vec2(0.0) : vec2((k & 1) != 0 ? 1.0 : -1.0, (k & 2) != 0 ? 1.0 : -1.0) * radiusTan;
        vec2 st;
        int face = cubeFaceCoord(cubeTapDirection(r, corner), st);
        ivec2 texel = clamp(ivec2(floor((st * 0.5 + 0.5) * faceSize)) / span, ivec2(0), ivec2(size - 1));
        nearest = min(nearest, texelFetch(uCubeMinDepth, ivec3(texel, face), level).r);
    }
    return nearest;
}

vec3 pcssCube(ShadowInput s) {
    CubeRay r = cubeRay(s.worldPos, s.worldNormal);
    float far = uCubeLight.w;
    float zReceiver = r.dist;
    float slope = uConeBias * r.pullPerTan;   // stored units per tangent unit of offset
    ivec2 pixel = ivec2(s.fragCoord);

    // Step 1a: the search region, from the cube's near plane (as printed) or shrunk twice to the
    // cone at the nearest distance stored within it (search_bound = min-depth).
    float zNear = far * 1e-3;   // kit::cubeDepthRange's near plane
    float searchTan = uLightSize * (zReceiver - zNear) / (zReceiver * zNear);
    if (uSearchBound >= 1) {   // the cube path has no fully-blocked stop (depth-range acts as min-depth)
        for (int i = 0; i < 2; ++i) {
            zNear = max(zNear, nearestCubeDepthIn(r, searchTan) * far);
            if (zNear >= zReceiver) return vec3(1.0);   // nothing nearer to the light than this point
            searchTan = uLightSize * (zReceiver - zNear) / (zReceiver * zNear);
        }
    }

    // Step 1b: blocker search over the disc, raw distances.
    int count = uSearchGrid * uSearchGrid;
    float sum = 0.0;
    int blockers = 0;
    for (int k = 0; k < count; ++k) {
        vec4 pair = discOffsetPair(uSearchOffsets, pixel, k / 2);
        vec2 offset = (k & 1) == 0 ? pair.xy : pair.zw;
        float d = textureLod(uCubeRaw, cubeTapDirection(r, offset * searchTan), 0.0).r;
        if (d < r.ref - slope * searchTan * length(offset)) {
            sum += d * far;
            ++blockers;
        }
    }
    if (blockers == 0) return vec3(1.0);
    float zBlocker = sum / float(blockers);

    // Step 2: penumbra, at least one face texel (contacts hard but anti-aliased).
    float filterTan = max((zReceiver - zBlocker) / zBlocker * uLightSize / zReceiver, cubeTexelTan());

    // Step 3: adaptive PCF with that radius along the cube's directions.
    gCubeTaps = true;
    gCubeRay = r;
    bool earlyOut;
    return vec3(adaptiveDiscPcf(uFilterOffsets, pixel, uFilterGrid, vec3(0.0, 0.0, r.ref), vec2(filterTan),
                                slope * filterTan, earlyOut));
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return pcssCube(s);
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float resolution = uLightDepth.w;
    bool perspective = uLightDepth.z > 0.5;
    float zReceiver = lightLinearDepth(coord.z, uLightDepth);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);   // per texel
    ivec2 pixel = ivec2(s.fragCoord);

    // Step 1a: the search region. eq. 3.18 as printed takes n = the near plane. Where the map's near
    // plane sits close to the light (spot and point lights fitted around a large ground), that
    // region covers half the map and n_s^2 samples miss the casters; with search_bound >= 1 the
    // region shrinks twice to the cone at the nearest depth stored within it (a lower bound on
    // any blocker's depth, read from the kit's depth-range mips). Deviation from the seed, same cone.
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
