// kit::LayeredDepthMap, main-pass side (seed 002 ch. 5): the map's lookup through its whole matrix
// (warped or not: warped_shadow_map.glsl), with the reference depth the map stores (the matrix's
// own z, or linear depth along the light) and the comparison of the biasing method. With neither
// linear depth nor two layers it is the plain comparison of warpedShadowMap().
#include "warped_shadow_map.glsl"
#include "shadowlab/kit/layered_depth_shared.h"

layout(binding = kFirstDepthUnit) uniform sampler2D uFirstLayer;
layout(binding = kSecondDepthUnit) uniform sampler2D uSecondLayer;

float layeredShadowMap(vec3 worldPos) {
    if (uBiasMethod == 0 && uLinearDepth == 0) return warpedShadowMap(worldPos);
    vec4 clip = uShadowMatrix * vec4(worldPos, 1.0);
    if (clip.w <= 0.0) return 1.0;
    vec3 coord = clip.xyz / clip.w * 0.5 + 0.5;
    if (!insideShadowMap(coord)) return 1.0;
    // Linear depth beyond the map's far end (a receiver past B by rounding) compares as the far
    // end: a 32F map does not clamp the reference, and its cleared 1.0 must read lit (issue 28).
    float reference = uLinearDepth == 1 ? min(dot(uLinearDepthPlane, vec4(worldPos, 1.0)), 1.0) : coord.z;
    if (uBiasMethod == 0) return texture(uShadowMap, vec3(coord.xy, reference));
    float first = texture(uFirstLayer, coord.xy).r, second = texture(uSecondLayer, coord.xy).r;
    // Eq. 5.1: halfway to the second surface (closed casters), at most z_offset (far pairs).
    if (uBiasMethod == 1) return reference <= first + min(0.5 * (second - first), uZOffset) ? 1.0 : 0.0;
    // Second-depth shadow mapping (Wang and Molnar): the test moves to the second surface.
    return reference <= second ? 1.0 : 0.0;
}
