// Shared by every program: the host's per-frame uniform block and per-object uniforms.
// Locations 0-15, uniform block binding 0 and texture units 0-3 belong to the host; techniques
// use locations 16+, blocks 1+ and units 4+.
#ifndef SHADOWLAB_COMMON_GLSL
#define SHADOWLAB_COMMON_GLSL

#include "shadowlab/frame_block.h"

// Per-object transforms live in one buffer; the host draws runs of objects that share a mesh and
// a material as one instanced draw (5000 trees: a few draws, not 5000). uFirstObject is the first
// object of the draw, gl_InstanceID the object within it. Use uModel and uNormalMatrix in vertex
// stages only (gl_InstanceID exists there alone).
struct ObjectTransform {
    mat4 model;
    mat4 normalMatrix;   // mat3 in a mat4, for std430 layout
};
layout(std430, binding = 0) readonly buffer ObjectTransforms {
    ObjectTransform uObjectTransforms[];
};
layout(location = 0) uniform int uFirstObject;
#define uModel (uObjectTransforms[uFirstObject + gl_InstanceID].model)
#define uNormalMatrix (mat3(uObjectTransforms[uFirstObject + gl_InstanceID].normalMatrix))
layout(location = 2) uniform vec4 uBaseColor;      // rgb, a = alpha
layout(location = 3) uniform vec4 uTransmission;   // rgb transmission colour
layout(location = 4) uniform vec4 uSpecular;       // rgb, a = shininess
// Material textures, bound by the host on units 1 and 2 for every draw (light passes included;
// a white texel where the material has none). x: transmission texture, y: base colour texture.
layout(location = 5) uniform ivec4 uMaterialTextures;
layout(binding = 1) uniform sampler2D uTransmissionTexture;   // rgb = t (linear), a = alpha
layout(binding = 2) uniform sampler2D uBaseColorTexture;      // sRGB-decoded rgb

// What a translucent surface lets through at `uv`: rgb = transmission colour t, a = alpha
// (coverage). The texture replaces the material's values where there is one.
vec4 surfaceTransmission(vec2 uv) {
    return uMaterialTextures.x != 0 ? texture(uTransmissionTexture, uv) : vec4(uTransmission.rgb, uBaseColor.a);
}

// Base colour (rgb, linear) and alpha of the surface at `uv`.
vec4 surfaceBaseColor(vec2 uv) {
    vec3 rgb = uBaseColor.rgb;
    if (uMaterialTextures.y != 0) rgb *= texture(uBaseColorTexture, uv).rgb;
    return vec4(rgb, surfaceTransmission(uv).a);
}

const int LIGHT_DIRECTIONAL = 0;
const int LIGHT_SPOT = 1;
const int LIGHT_POINT = 2;

int lightType() { return int(uLightPosition.w + 0.5); }

// Unit vector from a surface point towards the light.
vec3 directionToLight(vec3 worldPos) {
    return lightType() == LIGHT_DIRECTIONAL ? -uLightDirection.xyz : normalize(uLightPosition.xyz - worldPos);
}

// 1 inside a spot light's inner cone, 0 outside its outer cone, smooth between; 1 otherwise.
float spotFactor(vec3 worldPos) {
    if (lightType() != LIGHT_SPOT) return 1.0;
    float cosAngle = dot(normalize(worldPos - uLightPosition.xyz), uLightDirection.xyz);
    return smoothstep(uLightSpot.x, uLightSpot.y, cosAngle);
}

// What the main pass hands to a technique's shadowTerm().
struct ShadowInput {
    vec3 worldPos;
    vec3 worldNormal;   // unit, facing the viewer
    vec3 toLight;       // unit
    float NdotL;
    vec2 fragCoord;     // pixel centre in the main render target
};

#endif
