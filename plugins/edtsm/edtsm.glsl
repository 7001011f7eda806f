// Euclidean distance transform shadow mapping, main-pass side (edtsm.cpp, edtsm.comp and
// docs/anti-aliased-edges.md). The receiver's texel holds its nearest caster-edge site o and
// background-edge site b. Where o occludes this receiver and b does not, the rebuilt edge is the
// bisector between them: the signed distance (|P - o| - |P - b|) / 2, in texels from texel
// centres, gives a ramp `width` texels wide through it (Macedo and Apolinario's EDTSM normalises
// the two distances likewise, s_b / (s_o + s_b), in screen space). Elsewhere the plain test.
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "light_depth.glsl"
#include "cube_shadow.glsl"
#include "receiver_plane.glsl"
#include "edtsm_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2D uEdtDepthMap;
layout(binding = kEdtSitesUnit) uniform sampler2D uEdtNearest;

// The receiver's depth on its plane at a texel's centre (receiver_plane.glsl): the sites lie up
// to `reach` texels away, where a tilted receiver's own depth differs.
float edtReceiverAt(vec2 centre, vec3 mapPos, vec2 gradient) {
    return mapPos.z + dot(gradient, centre - mapPos.xy);
}

float edtShadow(vec3 mapPos, vec2 gradient) {
    vec2 P = mapPos.xy;
    vec2 c = floor(P);
    // The plain test on the receiver's plane at the texel's centre, where the map holds its depth
    // (as rbsm's): at the pixel itself a tilted receiver half a texel off it fell behind its own
    // depth (3.27% false shadow on forest-002 at the default offset; 0.68% so).
    float hard = edtReceiverAt(c + 0.5, mapPos, gradient) <= texelFetch(uEdtDepthMap, ivec2(c), 0).r ? 1.0 : 0.0;
    vec4 sites = texelFetch(uEdtNearest, ivec2(c), 0);
    vec2 o = sites.xy + 0.5, b = sites.zw + 0.5;   // texel centres
    float toCaster = distance(P, o), toBackground = distance(P, b);
    if (max(toCaster, toBackground) > uEdtReach) return hard;
    // The two sites must straddle this receiver's own test (the test depends on the receiver): the
    // caster site at least an edge's step in front of it, the background site not in front. A
    // receiver on the caster itself (a sphere near its terminator) keeps the plain test.
    float casterDepth = lightLinearDepth(texelFetch(uEdtDepthMap, ivec2(o), 0).r, uLightDepth);
    float receiverAtCaster = lightLinearDepth(edtReceiverAt(o, mapPos, gradient), uLightDepth);
    if (receiverAtCaster - casterDepth < uEdtMainEdgeDepth) return hard;
    if (edtReceiverAt(b, mapPos, gradient) > texelFetch(uEdtDepthMap, ivec2(b), 0).r) return hard;
    float signedDistance = 0.5 * (toCaster - toBackground);   // > 0: nearer the lit side
    return clamp(0.5 + signedDistance / uEdtWidth, 0.0, 1.0);
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, 1, 1.0, 0.0));
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    vec3 mapPos = vec3(coord.xy * uLightDepth.w, coord.z);
    vec2 gradient = receiverPlaneGradient(mapPos);   // in uniform control flow
    if (!insideShadowMap(coord)) return vec3(1.0);
    return vec3(edtShadow(mapPos, gradient));
}
