// Adaptive PCF, main-pass side (seed 000 sec. 3.2.4; GPU Gems 2 ch. 17): the pixel picks one of
// m x m jittered disc sets (pixel mod m), tests the outer ring first and stops there when the
// ring agrees (per pixel, or per 2x2 quad with `coherent`); only penumbra pixels pay for all n^2
// taps. With `count_early_outs`, two atomic counters count the calls and the early outs; the
// technique reads them back a few frames later ("early-out rate"). Off by default: every fragment
// incrementing the same two counters costs more than the filter on a GPU.
// Point lights: the same disc in cube space (kit/cube_depth_map.h): the unit-disc offsets scaled
// by the radius in tangent units (radius texels x 2 / resolution, a face texel at its centre),
// laid across the ray from the light, each tap the cube's comparison along its direction, with the
// cone bias per tangent unit (CubeRay::pullPerTan). Seamless cube filtering: taps reach across faces.
#include "light_space.glsl"
#include "disc_sampling.glsl"
#include "depth_range.glsl"
#include "cube_shadow.glsl"

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/depth_range_mips_shared.h"
#include "adaptive_pcf_shared.h"

// The counters are side effects: without this a GPU must shade every fragment before the depth
// test (no early z), so neither overdraw culling nor the host's depth pre-pass would spare any
// (measured on an H200: 36.4 ms on forest with or without the pre-pass). The main pass writes no
// gl_FragDepth and discards nothing, so testing depth first changes no pixel.
layout(early_fragment_tests) in;

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;
layout(binding = kDiscOffsetsUnit) uniform sampler3D uDiscOffsets;
layout(binding = kDepthRangeMipsUnit) uniform sampler2D uDepthRange;
layout(binding = kCounterBinding, offset = 0) uniform atomic_uint uShadedCount;
layout(binding = kCounterBinding, offset = 4) uniform atomic_uint uEarlyOutCount;

// The cube path's ray: while gCubeTaps is set, a tap's uv is its offset in tangent units across it.
bool gCubeTaps = false;
CubeRay gCubeRay;

float discTap(vec2 uv, float ref) {
    if (gCubeTaps) return texture(uCubeDepthMap, vec4(cubeTapDirection(gCubeRay, uv), ref));
    return texture(uShadowMap, vec3(uv, ref));
}

vec3 shadowTerm(ShadowInput s) {
    bool count = uCountEarlyOuts != 0;
    if (count) atomicCounterIncrement(uShadedCount);
    vec3 coord;
    vec2 radius;
    float rimBias;
    bool inside;
    if (lightType() == LIGHT_POINT) {   // a uniform: the quad vote stays in uniform control flow
        gCubeTaps = true;
        gCubeRay = cubeRay(s.worldPos, s.worldNormal);
        coord = vec3(0.0, 0.0, gCubeRay.ref);   // the taps' uv are offsets across the ray
        radius = vec2(uRadius * cubeTexelTan());
        rimBias = uConeBias * gCubeRay.pullPerTan * radius.x;
        inside = true;                          // the cube sees every direction
    } else {
        coord = shadowMapCoord(uShadowMatrix, s.worldPos);
        // No early return outside the map: the quad vote below needs uniform control flow.
        inside = insideShadowMap(coord);
        // The offsets are unit-disc positions: scaled by the radius they stay texel-independent.
        radius = vec2(uRadius / uLightDepth.w);
        rimBias = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize) * uRadius;
    }
    // classify = depth-range (2D maps; the host sets uClassify 0 under a point light): every tap
    // lies within the disc plus the texel beyond it that a bilinear tap reads; all lit where the
    // nearest depth there is at or behind the receiver (ref <= z <= every depth), all shadowed
    // where the farthest is in front of the rim's reference (every depth < z - rimBias <= every
    // tap's ref). Such a pixel's ring is unanimous too, so the ring test would stop there with the
    // same value: the image is the ring's.
    float decided = -1.0;
    if (uClassify == 1 && inside) {
        vec2 range = depthRangeIn(uDepthRange, coord.xy, vec2((uRadius + 1.0) / uLightDepth.w), uLightDepth.w);
        if (range.x >= coord.z) decided = 1.0;
        else if (range.y < coord.z - rimBias) decided = 0.0;
    }
    bool earlyOut;
    float lit = adaptiveDiscPcf(uDiscOffsets, ivec2(s.fragCoord), uGrid, coord, radius, rimBias, uCoherent != 0,
                                !inside || decided >= 0.0, earlyOut);
    if (decided >= 0.0) lit = decided;
    if (count && inside && (earlyOut || decided >= 0.0)) atomicCounterIncrement(uEarlyOutCount);
    return vec3(inside ? lit : 1.0);
}
