// Planar shadows, main-pass side: the mask drawn in this pixel (1 lit, 0 shadowed).
#include "planar_shared.h"

layout(binding = kMaskUnit) uniform sampler2D uPlanarMask;

vec3 shadowTerm(ShadowInput s) {
    return vec3(texelFetch(uPlanarMask, ivec2(s.fragCoord), 0).r);
}
