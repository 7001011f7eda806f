// Light space perspective shadow maps, main-pass side: the warped map's lookup (P L, projective),
// with the reference depth and the comparison of the biasing method (seed 002 ch. 5).
#include "warped_shadow_map.glsl"
#include "lispsm_shared.h"

layout(binding = kFirstDepthUnit) uniform sampler2D uFirstLayer;
layout(binding = kSecondDepthUnit) uniform sampler2D uSecondLayer;

vec3 shadowTerm(ShadowInput s) {
    if (uBiasMethod == 0 && uLinearDepth == 0) return vec3(warpedShadowMap(s.worldPos));
    vec4 clip = uShadowMatrix * vec4(s.worldPos, 1.0);
    if (clip.w <= 0.0) return vec3(1.0);
    vec3 coord = clip.xyz / clip.w * 0.5 + 0.5;
    if (!insideShadowMap(coord)) return vec3(1.0);
    float reference = uLinearDepth == 1 ? dot(uLinearDepthPlane, vec4(s.worldPos, 1.0)) : coord.z;
    if (uBiasMethod == 0) return vec3(texture(uShadowMap, vec3(coord.xy, reference)));
    float first = texture(uFirstLayer, coord.xy).r, second = texture(uSecondLayer, coord.xy).r;
    if (uBiasMethod == 1) {
        // Eq. 5.1: halfway to the second surface (closed casters), at most z_offset (far pairs).
        float bias = min(0.5 * (second - first), uZOffset);
        return vec3(reference <= first + bias ? 1.0 : 0.0);
    }
    // Second-depth shadow mapping (Wang and Molnar): the test moves to the second surface.
    return vec3(reference <= second ? 1.0 : 0.0);
}
