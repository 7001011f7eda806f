// Cascaded shadow maps, main-pass side: the cascade is chosen by the point's view depth (the
// first whose split range reaches it; if the point lies outside that cascade's map, the next one
// holding it), looked up as n x n comparisons (box_pcf.glsl's taps) in its layer of the 2D array,
// and blended into the next cascade over the blend band at the far end of its range (the next
// cascade's map is fitted to reach back over that band, kit/cascades.h: cascadeRanges). Point
// lights: the kit's cube map.
#include "light_space.glsl"
#include "cube_shadow.glsl"
#include "box_pcf.glsl"
#include "shadowlab/kit/csm_shared.h"

layout(binding = kCascadeMapsUnit) uniform sampler2DArrayShadow uCascadeMaps;

vec3 cascadeColour(int i) {
    const vec3 kColours[8] = vec3[8](vec3(1.0, 0.25, 0.25), vec3(0.25, 1.0, 0.25), vec3(0.3, 0.45, 1.0),
                                     vec3(1.0, 0.9, 0.2), vec3(1.0, 0.3, 1.0), vec3(0.2, 1.0, 1.0),
                                     vec3(1.0, 0.6, 0.2), vec3(0.7, 0.7, 0.7));
    return kColours[i];
}

vec3 cascadeCoord(int i, vec3 worldPos) {
    return shadowMapCoord(uCascadeMatrix[i], worldPos);
}

float cascadeLit(int i, vec3 coord) {
    int n = uCsmOptions.x;
    float texel = 1.0 / uCsmParams.w;
    float lit = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            lit += texture(uCascadeMaps, vec4(coord.xy + boxPcfOffset(x, y, n) * texel, float(i), coord.z));
    return lit / float(n * n);
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, uCsmOptions.x, 1.0, 1.0));
    int count = int(uCsmParams.x);
    float depth = -(uView * vec4(s.worldPos, 1.0)).z;
    int chosen = 0;
    while (chosen < count - 1 && depth > uCascadeRange[chosen].y) ++chosen;
    // The first cascade from there whose map holds the point (all of them do, but for a depth
    // range a frame late: fit = sdsm while the camera moves).
    int cascade = -1;
    vec3 coord = vec3(0.0);
    for (int i = chosen; i < count && cascade < 0; ++i) {
        coord = cascadeCoord(i, s.worldPos);
        if (insideShadowMap(coord)) cascade = i;
    }
    if (cascade < 0) return vec3(1.0);   // outside every map: nothing was drawn that could occlude
    float lit = cascadeLit(cascade, coord);
    // Blend band: the last fraction uCsmParams.y of the cascade's range fades into the next one.
    float begin = uCascadeRange[cascade].x, end = uCascadeRange[cascade].y;
    float bandStart = end - uCsmParams.y * (end - begin);
    if (cascade + 1 < count && uCsmParams.y > 0.0 && depth > bandStart) {
        vec3 next = cascadeCoord(cascade + 1, s.worldPos);
        if (insideShadowMap(next)) lit = mix(lit, cascadeLit(cascade + 1, next), clamp((depth - bandStart) / (end - bandStart), 0.0, 1.0));
    }
    if (uCsmParams.z > 0.5) return vec3(lit) * 0.6 + cascadeColour(cascade) * (0.2 + 0.2 * lit);
    return vec3(lit);
}
