// Shadow mapping, main-pass side: project the shaded point into the map and let the texture unit
// compare (sampler2DShadow returns 1 where ref <= stored depth; with GL_LINEAR it is the
// bilinear blend of the four neighbouring comparisons), or the two-layer test of bias_method
// (layered_depth.glsl). Outside the map nothing was rendered that could occlude: lit.
#include "layered_depth.glsl"
#include "cube_shadow.glsl"

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, 1, 1.0, 0.0));
    return vec3(layeredShadowMap(s.worldPos));
}
