// Translucent shadows, main-pass side (seed 001 sec. 2.1.3; kit/translucent_maps.h): o = [z <= D_o]
// and t = [z <= D_t] through the texture unit's comparison (2x2 bilinear with the hardware filter,
// as seed 001 timed it, Fig. 5.3.B), C the colour buffer (bilinear), and
//   visibility = o (t + (1 - t) C):
// unshadowed in front of every translucent caster, C behind the nearest one, 0 behind an opaque
// one. Every point behind the nearest translucent surface gets all of C, including the filters of
// surfaces behind it: translucent surfaces shadow themselves and far layers tint near ones
// (Figs. 2.1.3.A, 5.3.3.A), unless the maps are rebuilt per receiver (composited, sec. 4.2.3).
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/translucent_maps_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uOpaqueDepth;
layout(binding = kTranslucentDepthUnit) uniform sampler2DShadow uTranslucentDepth;
layout(binding = kShadowColourUnit) uniform sampler2D uShadowColour;

vec3 translucentMapsVisibility(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float o = texture(uOpaqueDepth, coord);
    float t = texture(uTranslucentDepth, coord);
    vec3 C = texture(uShadowColour, coord.xy).rgb;
    return o * (t + (1.0 - t) * C);
}
