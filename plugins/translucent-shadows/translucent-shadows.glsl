// Translucent shadows, main-pass side: the kit's lookup of the three maps (shaders/translucent_maps.glsl,
// seed 001 sec. 2.1.3): visibility = o (t + (1 - t) C).
#include "translucent_maps.glsl"

vec3 shadowTerm(ShadowInput s) { return translucentMapsVisibility(s); }
