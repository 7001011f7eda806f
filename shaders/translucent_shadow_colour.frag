// The third map of translucent shadows (kit/translucent_maps.h) (seed 001 sec. 2.1.3, 4.2.1): each translucent caster in front of
// the opaque depth D_o (depth-tested against it, no writes) multiplies the colour buffer, cleared
// to white, by what it lets through, drawn front to back from the light:
//   original  the surface colour (StarCraft II: transmission taken to be the colour; seed 001
//             Fig. 4.2.1.A, a green plane casting no shadow on a green pot),
//   modified  (1 - a) t, seed 001's correction after CSSM2's transmission (sec. 4.2.1).
// The blend (DST_COLOR, ZERO) is a product, so the order does not change the result; seed 001's
// front-to-back order would matter only for a blend that does not commute.
#include "common.glsl"
#include "shadowlab/kit/translucent_maps_shared.h"

in vec2 vUv;

layout(location = 0) out vec4 outFilter;

void main() {
    vec3 filterColour;
    if (uVariant == kVariantModified) {
        vec4 surface = surfaceTransmission(vUv);
        filterColour = (1.0 - surface.a) * surface.rgb;
    } else {
        filterColour = surfaceBaseColor(vUv).rgb;
    }
    outFilter = vec4(filterColour, 1.0);
}
