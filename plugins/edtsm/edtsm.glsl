// Euclidean distance transform shadow mapping, main-pass side (edtsm.cpp, edtsm.comp and
// docs/anti-aliased-edges.md). The receiver's texel holds its nearest caster-edge site o and
// background-edge site b. Where o occludes this receiver and b does not, the rebuilt edge is the
// bisector between them: the signed distance (|P - o| - |P - b|) / 2, in texels from texel
// centres, gives a ramp `width` texels wide through it (Macedo and Apolinario's EDTSM normalises
// the two distances likewise, s_b / (s_o + s_b), in screen space). Elsewhere the plain test.
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "cube_shadow.glsl"
#include "edtsm_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2D uEdtDepthMap;
layout(binding = kEdtSitesUnit) uniform sampler2D uEdtNearest;

float edtLit(vec2 texel, float z) {
    return z <= texelFetch(uEdtDepthMap, ivec2(texel), 0).r ? 1.0 : 0.0;
}

float edtShadow(vec3 coord) {
    vec2 P = coord.xy * uLightDepth.w;
    vec2 c = floor(P);
    float hard = edtLit(c, coord.z);
    vec4 sites = texelFetch(uEdtNearest, ivec2(c), 0);
    vec2 o = sites.xy + 0.5, b = sites.zw + 0.5;   // texel centres
    float toCaster = distance(P, o), toBackground = distance(P, b);
    if (max(toCaster, toBackground) > uEdtReach) return hard;
    // The two sites must straddle this receiver's own test (the test depends on the receiver).
    if (edtLit(o, coord.z) != 0.0 || edtLit(b, coord.z) != 1.0) return hard;
    float signedDistance = 0.5 * (toCaster - toBackground);   // > 0: nearer the lit side
    return clamp(0.5 + signedDistance / uEdtWidth, 0.0, 1.0);
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, 1, 1.0, 0.0));
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    return vec3(edtShadow(coord));
}
