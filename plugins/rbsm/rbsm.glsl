// Revectorization-based shadow mapping, main-pass side (Macedo and Apolinario 2016; rbsm.cpp and
// docs/anti-aliased-edges.md). Units: P is the receiver's position in texels of the map, c its
// texel, f = fract(P) its normalized position inside c (the paper's "normalized relative position").
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "cube_shadow.glsl"
#include "receiver_plane.glsl"
#include "rbsm_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2D uRbsmDepth;

// The receiver: its position P in texels, depth at P and depth gradient per texel (a plane).
vec2 rbsmP;
float rbsmZ;
vec2 rbsmGrad;

// The binary test of texel t for the receiver plane at t's centre: 1 lit, 0 shadowed (as
// sampler2DShadow's "ref <= stored"); texels beyond the map repeat its border.
float rbsmLit(ivec2 t) {
    int last = int(uLightDepth.w) - 1;
    float z = rbsmZ + dot(rbsmGrad, vec2(t) + 0.5 - rbsmP);
    return z <= texelFetch(uRbsmDepth, clamp(t, ivec2(0), ivec2(last)), 0).r ? 1.0 : 0.0;
}

// Step (2): from c along `dir`, the run of texels of class s whose neighbour across side n is of
// the other class. Returns (texels beyond c in the run, the step's height at its end): +0.5 when
// the next texel of the row is of the other class (the boundary steps into c's row), -0.5 when the
// next texel's neighbour across n is of c's class (it steps away), 0 when the search ran out.
vec2 rbsmWalk(ivec2 c, ivec2 n, ivec2 dir, float s) {
    for (int i = 1; i <= uRbsmMaxSearch; ++i) {
        ivec2 t = c + dir * i;
        if (rbsmLit(t) != s) return vec2(float(i - 1), 0.5);
        if (rbsmLit(t + n) == s) return vec2(float(i - 1), -0.5);
    }
    return vec2(float(uRbsmMaxSearch), 0.0);
}

// Step (3): height of the revectorized boundary above the texel border (towards c's inside) at
// the receiver, from the distances to the run's two ends and their steps. A staircase (steps of
// opposite signs) is one line through both steps' midpoints; a notch or a single step, a line from
// the nearer step's midpoint down to the border at the run's middle.
float rbsmBoundaryHeight(float dMinus, float hMinus, float dPlus, float hPlus) {
    if (hMinus * hPlus < 0.0) return mix(hMinus, hPlus, dMinus / (dMinus + dPlus));
    float halfRun = 0.5 * (dMinus + dPlus);
    float h = dMinus < dPlus ? hMinus : hPlus;
    return h * max(1.0 - min(dMinus, dPlus) / halfRun, 0.0);
}

// The share of the receiver that lies beyond the revectorized boundary of side n (of the other
// class): 0 or 1, or with `filtered` the ramp over the pixel's footprint `width` (texels along n).
float rbsmAcross(ivec2 c, vec2 f, ivec2 n, float s, float width) {
    ivec2 along = ivec2(abs(n.y), abs(n.x));
    float fa = dot(f, vec2(along));
    vec2 minus = rbsmWalk(c, n, -along, s), plus = rbsmWalk(c, n, along, s);
    float h = rbsmBoundaryHeight(minus.x + fa, minus.y, plus.x + 1.0 - fa, plus.y);
    float fn = dot(f, abs(vec2(n)));
    float depthIn = n.x + n.y > 0 ? 1.0 - fn : fn;   // the receiver's distance from the border into c
    if (uRbsmFiltered != 0) return clamp((h - depthIn) / width + 0.5, 0.0, 1.0);
    return depthIn < h ? 1.0 : 0.0;
}

float rbsmShadow(vec3 coord, vec2 footprint, vec2 gradient) {
    rbsmP = coord.xy * uLightDepth.w;
    rbsmZ = coord.z;
    rbsmGrad = gradient;
    ivec2 c = ivec2(floor(rbsmP));
    vec2 f = rbsmP - vec2(c);
    float s = rbsmLit(c);
    // Conservative: a shadowed texel stays shadowed (the boundary moves into lit texels only).
    if (uRbsmConservative != 0 && s == 0.0) return 0.0;
    const ivec2 kSides[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
    float across = 0.0;
    // Step (1): discontinuities in the 4-neighbourhood; only those sides are revectorized.
    for (int k = 0; k < 4; ++k) {
        ivec2 n = kSides[k];
        if (rbsmLit(c + n) == s) continue;
        float width = max(dot(footprint, abs(vec2(n))), 1e-3);
        across = max(across, rbsmAcross(c, f, n, s, width));
    }
    return mix(s, 1.0 - s, across);
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, 1, 1.0, 0.0));
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    // The pixel's footprint in texels (filtered edges) and the receiver's plane, taken here in
    // uniform control flow.
    vec3 mapPos = vec3(coord.xy * uLightDepth.w, coord.z);
    vec2 footprint = fwidth(mapPos.xy);
    vec2 gradient = receiverPlaneGradient(mapPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    return vec3(rbsmShadow(coord, footprint, gradient));
}
