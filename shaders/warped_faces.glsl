// kit::WarpedFaceMaps, main-pass side: a point light's faces, each a map of its own in one atlas.
// The face is the major axis of (P - light) (cube_faces.glsl, GL's rule), then that face's whole
// matrix, the reference depth and the bias method's comparison as layered_depth.glsl's. The map
// pass drew each face over a slightly wider frustum, so the face chosen here always holds P's
// casters and the 2x2 filter's texels; the tile coordinates are clamped half a texel inside the
// tile so the filter never reads a neighbouring face. A face not drawn saw no visible point: lit.
#include "layered_depth.glsl"
#include "cube_faces.glsl"
#include "shadowlab/kit/warped_faces_shared.h"

float warpedFacesShadow(vec3 worldPos) {
    vec2 st;
    int face = cubeFaceCoord(worldPos - uFaceLight.xyz, st);
    if ((uFaceInfo.y & (1 << face)) == 0) return 1.0;
    vec4 clip = uFaceMatrix[face] * vec4(worldPos, 1.0);
    if (clip.w <= 0.0) return 1.0;
    vec3 coord = clip.xyz / clip.w * 0.5 + 0.5;
    if (any(lessThan(coord.xy, vec2(0.0))) || any(greaterThan(coord.xy, vec2(1.0)))) return 1.0;
    vec2 uv = uFaceTile[face].xy + clamp(coord.xy, vec2(uFaceLight.w), vec2(1.0 - uFaceLight.w)) * uFaceTile[face].zw;
    // The farthest receivers define B_f's far end (a floor under the light), so rounding puts half
    // of them just beyond depth 1: compared as the far end, where depth clamp put their casters.
    float reference = min(uLinearDepth == 1 ? dot(uFaceLinearPlane[face], vec4(worldPos, 1.0)) : coord.z, 1.0);
    if (uBiasMethod == 0) return texture(uShadowMap, vec3(uv, reference));
    float first = texture(uFirstLayer, uv).r, second = texture(uSecondLayer, uv).r;
    if (uBiasMethod == 1) return reference <= first + min(0.5 * (second - first), uZOffset) ? 1.0 : 0.0;   // eq. 5.1
    return reference <= second ? 1.0 : 0.0;
}

// The warped map's lookup: the faces under a point light, else the single map.
float warpedOrFacesShadow(vec3 worldPos) {
    return uFaceInfo.x == 1 ? warpedFacesShadow(worldPos) : layeredShadowMap(worldPos);
}
