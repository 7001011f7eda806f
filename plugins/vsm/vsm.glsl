// Variance shadow maps, main-pass side: the Chebyshev upper bound of the lit fraction from the
// filtered moments (seed 000 eq. 3.13-3.15), then the light-bleeding reduction.
#include "moment_shadows.glsl"

#include "vsm_shared.h"

vec3 shadowTerm(ShadowInput s) {
    MomentSample m = sampleMoments(s.worldPos);
    float pMax = chebyshevUpperBound(m.moments.xy, m.depth, uMinVariance);
    float visibility = reduceLightBleeding(pMax, uLightBleedingReduction);
    return vec3(m.inside ? visibility : 1.0);
}
