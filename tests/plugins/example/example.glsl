// The example's shadow term: 3 x 3 bilinear comparisons around the point, darkened by uDarkness.
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "example_shared.h"
layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;

vec3 shadowTerm(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float lit = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) lit += texture(uShadowMap, coord + vec3(vec2(x, y) / uLightDepth.w, 0.0)) / 9.0;
    return vec3(1.0 - uDarkness * (1.0 - lit));
}
