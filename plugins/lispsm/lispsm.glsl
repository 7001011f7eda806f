// Light space perspective shadow maps, main-pass side: the warped map's lookup (P L, projective),
// with the reference depth and the comparison of the biasing method (kit::LayeredDepthMap).
#include "layered_depth.glsl"

vec3 shadowTerm(ShadowInput s) { return vec3(layeredShadowMap(s.worldPos)); }
