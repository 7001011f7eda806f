// Light space perspective shadow maps, main-pass side: the warped map's lookup (P L, projective),
// with the reference depth and the comparison of the biasing method (kit::LayeredDepthMap); under
// a point light the face's map by (P - light)'s major axis (kit::WarpedFaceMaps).
#include "warped_faces.glsl"

vec3 shadowTerm(ShadowInput s) { return vec3(warpedOrFacesShadow(s.worldPos)); }
