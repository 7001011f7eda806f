// Trapezoidal shadow maps, main-pass side: the map through N_T P_L V_L (projective), compared
// against the linear depth it stores (kit::LayeredDepthMap's lookup, with its bias methods).
#include "layered_depth.glsl"

vec3 shadowTerm(ShadowInput s) { return vec3(layeredShadowMap(s.worldPos)); }
