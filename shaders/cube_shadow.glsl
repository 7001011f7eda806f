// The kit's cube depth map, main-pass side: a point light's shadow from the six faces, looked up
// by the direction from the light (samplerCubeShadow compares distance / far with the stored one).
#ifndef SHADOWLAB_CUBE_SHADOW_GLSL
#define SHADOWLAB_CUBE_SHADOW_GLSL
#include "shadowlab/kit/cube_depth_map_shared.h"
#include "cube_faces.glsl"

layout(binding = kCubeDepthMapUnit) uniform samplerCubeShadow uCubeDepthMap;

// The ray from the light to a shaded point, with what filters in cube space need: a tangent frame
// (u, v) across it, so that dir + x u + y v is the direction of a tap offset by (x, y) tangent
// units at unit distance (one texel of a 90-degree face is 2 / resolution of them at the face's
// centre, 2 / (resolution cos^2) off-centre: the centre's value is used everywhere), and the
// receiver's slope for the cone bias. ref is the stored quantity of the point: distance / far.
struct CubeRay {
    vec3 dir;         // unit, light -> point
    vec3 u, v;        // unit, across the ray
    float dist;       // world distance to the light
    float ref;        // dist / far, as the cube stores it
    float pullPerTan; // cone bias: what the receiver's plane gains, in stored units, per tangent
                      // unit of tap offset: dist tan(theta) / far (theta between normal and ray,
                      // tan capped at 8; the cube analogue of seed 000 sec. 3.2.4's cone bias)
};

CubeRay cubeRay(vec3 worldPos, vec3 worldNormal) {
    CubeRay r;
    vec3 toPoint = worldPos - uCubeLight.xyz;
    r.dist = max(length(toPoint), 1e-6);
    r.dir = toPoint / r.dist;
    r.ref = r.dist / uCubeLight.w;
    r.u = normalize(cross(r.dir, abs(r.dir.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    r.v = cross(r.dir, r.u);
    float cosTheta = clamp(abs(dot(worldNormal, r.dir)), 1e-3, 1.0);
    float tanTheta = min(sqrt(1.0 - cosTheta * cosTheta) / cosTheta, 8.0);
    r.pullPerTan = r.dist * tanTheta / uCubeLight.w;
    return r;
}

// Direction of the tap `offset` tangent units across the ray (not normalised: cube lookups need not).
vec3 cubeTapDirection(CubeRay r, vec2 offset) {
    return r.dir + offset.x * r.u + offset.y * r.v;
}

// One tangent unit per texel of a face at its centre.
float cubeTexelTan() {
    return 2.0 / uCubeBias.z;
}

// n x n taps `spacing` texels apart on the plane across the ray from the light. With `coneBias`
// (0 or 1) each tap's reference is pulled towards the light by what the receiver's plane gains
// over the tap's offset (CubeRay::pullPerTan).
float cubeShadow(vec3 worldPos, vec3 worldNormal, int kernel, float spacing, float coneBias) {
    CubeRay r = cubeRay(worldPos, worldNormal);
    if (kernel <= 1) return texture(uCubeDepthMap, vec4(r.dir, r.ref));
    float texel = cubeTexelTan();
    float centre = 0.5 * float(kernel - 1);
    float lit = 0.0;
    for (int y = 0; y < kernel; ++y)
        for (int x = 0; x < kernel; ++x) {
            vec2 offset = (vec2(x, y) - centre) * spacing * texel;   // tangent units at distance 1
            float pull = coneBias * length(offset) * r.pullPerTan;
            lit += texture(uCubeDepthMap, vec4(cubeTapDirection(r, offset), r.ref - pull));
        }
    return lit / float(kernel * kernel);
}

#endif
