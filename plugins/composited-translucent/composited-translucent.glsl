// Composited translucent shadows, main-pass side: the lookup of translucent shadows
// (shaders/translucent_maps.glsl, seed 001 sec. 2.1.3), visibility = o (t + (1 - t) C), on the maps
// bound for the surface being drawn: the whole frame's for opaque receivers, those rebuilt from the
// meshes nearer the light for each translucent one (sec. 4.2.3).
#include "translucent_maps.glsl"

vec3 shadowTerm(ShadowInput s) { return translucentMapsVisibility(s); }
