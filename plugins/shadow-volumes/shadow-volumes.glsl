// Stencil shadow volumes, main-pass side: the volume pass left a screen-space mask (1 lit, 0 in
// shadow) at the main target's size; the shaded pixel reads its own texel.
#include "shadow_volumes_shared.h"

layout(binding = kVolumeMaskUnit) uniform sampler2D uVolumeMask;

vec3 shadowTerm(ShadowInput s) {
    return vec3(texelFetch(uVolumeMask, ivec2(s.fragCoord), 0).r);
}
