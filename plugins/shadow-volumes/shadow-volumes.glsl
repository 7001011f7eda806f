// Stencil shadow volumes, main-pass side: the volume pass left its count in the stencil of a
// depth-stencil texture at the main target's size (sampled as GL_STENCIL_INDEX); the shaded pixel
// reads its own texel: lit where no volume holds it (count 0).
#include "shadow_volumes_shared.h"

layout(binding = kVolumeMaskUnit) uniform usampler2D uVolumeCount;

vec3 shadowTerm(ShadowInput s) {
    return texelFetch(uVolumeCount, ivec2(s.fragCoord), 0).r == 0u ? vec3(1.0) : vec3(0.0);
}
