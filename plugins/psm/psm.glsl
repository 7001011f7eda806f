// Perspective shadow maps, main-pass side: the map lives in the camera's post-perspective space,
// and its whole matrix (light projection, light view, PP) is one projective warp of world space.
#include "warped_shadow_map.glsl"

vec3 shadowTerm(ShadowInput s) { return vec3(warpedShadowMap(s.worldPos)); }
