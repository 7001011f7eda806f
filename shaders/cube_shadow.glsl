// The kit's cube depth map, main-pass side: a point light's shadow from the six faces, looked up
// by the direction from the light (samplerCubeShadow compares distance / far with the stored one).
#ifndef SHADOWLAB_CUBE_SHADOW_GLSL
#define SHADOWLAB_CUBE_SHADOW_GLSL
#include "shadowlab/kit/cube_depth_map_shared.h"

layout(binding = kCubeDepthMapUnit) uniform samplerCubeShadow uCubeDepthMap;

// n x n taps `spacing` texels apart on the plane across the ray from the light (a texel of a 90
// degree face spans 2 / resolution at unit distance along its axis; the face centre's value is
// used everywhere). With `coneBias` (0 or 1) each tap's reference is pulled towards the light by
// what the receiver's plane gains over the tap's offset, r tan(theta) (theta between the normal and
// the light ray, tan capped at 8): the cube analogue of seed 000 sec. 3.2.4's cone bias.
float cubeShadow(vec3 worldPos, vec3 worldNormal, int kernel, float spacing, float coneBias) {
    vec3 toPoint = worldPos - uCubeLight.xyz;
    float dist = max(length(toPoint), 1e-6);
    vec3 dir = toPoint / dist;
    float ref = dist / uCubeLight.w;
    if (kernel <= 1) return texture(uCubeDepthMap, vec4(dir, ref));
    vec3 u = normalize(cross(dir, abs(dir.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 v = cross(dir, u);
    float texel = 2.0 / uCubeBias.z;
    float cosTheta = clamp(abs(dot(worldNormal, dir)), 1e-3, 1.0);
    float tanTheta = min(sqrt(1.0 - cosTheta * cosTheta) / cosTheta, 8.0);
    float centre = 0.5 * float(kernel - 1);
    float lit = 0.0;
    for (int y = 0; y < kernel; ++y)
        for (int x = 0; x < kernel; ++x) {
            vec2 offset = (vec2(x, y) - centre) * spacing * texel;   // tangent units at distance 1
            float pull = coneBias * length(offset) * dist * tanTheta / uCubeLight.w;
            lit += texture(uCubeDepthMap, vec4(dir + offset.x * u + offset.y * v, ref - pull));
        }
    return lit / float(kernel * kernel);
}

#endif
