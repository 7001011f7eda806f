// Perspective shadow maps, main-pass side: the map lives in the camera's post-perspective space,
// and its whole matrix (light projection, light view, PP) is one projective warp of world space;
// the comparison of bias_method (layered_depth.glsl).
#include "layered_depth.glsl"

vec3 shadowTerm(ShadowInput s) { return vec3(layeredShadowMap(s.worldPos)); }
