// Light space perspective shadow maps, main-pass side: the warped map's lookup (P L, projective).
#include "warped_shadow_map.glsl"

vec3 shadowTerm(ShadowInput s) { return vec3(warpedShadowMap(s.worldPos)); }
