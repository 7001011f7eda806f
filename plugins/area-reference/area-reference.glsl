// Area-light reference, main-pass side: the average of the N sample visibilities accumulated for
// this pixel before the main pass (the host's camera pre-pass rasterised the same surfaces, so gl_FragCoord
// addresses the same point).
#include "area_reference_shared.h"

layout(binding = kAverageUnit) uniform sampler2D uAverageVisibility;

vec3 shadowTerm(ShadowInput s) {
    return vec3(texelFetch(uAverageVisibility, ivec2(s.fragCoord), 0).r);
}
