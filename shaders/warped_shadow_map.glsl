// A shadow map whose light matrix is a projective warp of world space (lispsm, psm): the shaded
// point goes through the whole matrix (divide by w) and the texture unit compares depths, as in
// plain shadow mapping. Points behind the warp's centre (w <= 0) or outside the map lie outside
// the focus body, where nothing visible is: lit.
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;

float warpedShadowMap(vec3 worldPos) {
    if ((uShadowMatrix * vec4(worldPos, 1.0)).w <= 0.0) return 1.0;
    vec3 coord = shadowMapCoord(uShadowMatrix, worldPos);
    if (!insideShadowMap(coord)) return 1.0;
    return texture(uShadowMap, coord);
}
