// Shadow mapping, main-pass side: project the shaded point into the map and let the texture unit
// compare (sampler2DShadow returns 1 where ref <= stored depth; with GL_LINEAR it is the
// bilinear blend of the four neighbouring comparisons).
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "cube_shadow.glsl"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, 1, 1.0, 0.0));
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    // Outside the map nothing was rendered that could occlude: lit.
    if (!insideShadowMap(coord)) return vec3(1.0);
    return vec3(texture(uShadowMap, coord));
}
