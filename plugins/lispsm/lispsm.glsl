// Light space perspective shadow maps, main-pass side: the shaded point goes through the warped
// light matrix P L (projective: divide by w) and the texture unit compares depths, as in plain
// shadow mapping. Points behind the warp's centre (w <= 0) lie outside the focus body, where
// nothing visible is: lit.
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;

vec3 shadowTerm(ShadowInput s) {
    if ((uShadowMatrix * vec4(s.worldPos, 1.0)).w <= 0.0) return vec3(1.0);
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    return vec3(texture(uShadowMap, coord));
}
