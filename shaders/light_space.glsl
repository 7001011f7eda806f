// Projection of a world point into a shadow map: uv in [0,1]^2 and depth in [0,1].
#ifndef SHADOWLAB_LIGHT_SPACE_GLSL
#define SHADOWLAB_LIGHT_SPACE_GLSL

// seed 000 eq. 3.4 does the NDC -> texture mapping with an offset matrix; in GL it is
// 0.5 * ndc + 0.5 for x, y and z (no y flip: GL textures start at the bottom row).
vec3 shadowMapCoord(mat4 lightViewProjection, vec3 worldPos) {
    vec4 clip = lightViewProjection * vec4(worldPos, 1.0);
    return clip.xyz / clip.w * 0.5 + 0.5;
}

bool insideShadowMap(vec3 coord) {
    return all(greaterThanEqual(coord, vec3(0.0))) && all(lessThanEqual(coord, vec3(1.0)));
}

#endif
